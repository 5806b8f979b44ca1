//! Analytic validation of the reference model (MODEL.md section 12).
//!
//! Every test runs the scalar reference model at several parameter values and compares a
//! measured quantity with its closed-form answer, within a tolerance stated (and argued) at
//! the check. Each test prints its whole table of measured against expected values, then
//! fails if any row failed, so that `cargo test --release --test tests validation --
//! --nocapture` shows every number, passing or not.

use crate::lander::{on_slope, quiet, sample_of};
use glam::{DMat3, DVec3};
use touchdown::reference::step::{step, step_size};
use touchdown::reference::{Model, State, StepReport, Summary, initial_state, run};
use touchdown::scenario::{Inputs, Scenario};
use touchdown::slope::Surface;

mod free_flight;
mod honeycomb;
mod outcome;
mod regolith;
mod restitution;
mod rocks;
mod sliding;
mod step_control;
mod tipping;
mod touchdown_state;

// ---------------------------------------------------------------------------------------
// Helpers: inputs, scenarios, a step driver and the results table.
// ---------------------------------------------------------------------------------------

/// Inputs with an initial velocity (in the attitude reference frame) and body rates.
fn moving(velocity_m_s: [f64; 3], rates_deg_s: [f64; 3]) -> Inputs<f64> {
    Inputs {
        velocity_error_x_m_s: velocity_m_s[0],
        velocity_error_y_m_s: velocity_m_s[1],
        velocity_error_z_m_s: velocity_m_s[2],
        rate_x_deg_s: rates_deg_s[0],
        rate_y_deg_s: rates_deg_s[1],
        rate_z_deg_s: rates_deg_s[2],
        ..quiet()
    }
}

/// One lander stepped by hand with the engine's own step size (`step_size`), which stops
/// exactly at `model.t_max_s`.
struct Sim {
    model: Model,
    surface: Surface,
    state: State,
    report: StepReport,
}

impl Sim {
    fn new(model: Model, inputs: Inputs<f64>) -> Sim {
        let sample = sample_of(inputs);
        let surface = Surface::of(&sample);
        let state = initial_state(&model, &surface, &sample);
        let report = StepReport::new(model.legs.len());
        Sim {
            model,
            surface,
            state,
            report,
        }
    }

    fn of(scenario: &Scenario, inputs: Inputs<f64>) -> Sim {
        Sim::new(Model::new(scenario), inputs)
    }

    /// Takes one step; false once `t_max_s` is reached.
    fn advance(&mut self) -> bool {
        if self.state.t_s >= self.model.t_max_s {
            return false;
        }
        let dt = step_size(&self.model, &self.surface, &self.state);
        step(
            &self.model,
            &self.surface,
            &mut self.state,
            dt,
            &mut self.report,
        );
        true
    }

    /// Steps while `go` holds and `t_max_s` is not reached; returns whether `go` stopped it.
    fn advance_while(&mut self, mut go: impl FnMut(&Sim) -> bool) -> bool {
        while go(self) {
            if !self.advance() {
                return false;
            }
        }
        true
    }

    /// Steps until `t` (at most `t_max_s`).
    fn advance_to(&mut self, t: f64) {
        self.advance_while(|s| s.state.t_s < t - 1e-12);
    }

    fn rotation(&self) -> DMat3 {
        DMat3::from_quat(self.state.body.attitude)
    }

    /// Tilt of Z_B from the slope normal, deg.
    fn tilt_deg(&self) -> f64 {
        let z = self.state.body.attitude * DVec3::Z;
        z.dot(self.surface.normal)
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    }

    fn translational_energy(&self) -> f64 {
        0.5 * self.model.mass_kg * self.state.body.velocity_m_s.length_squared()
    }

    fn rotational_energy(&self) -> f64 {
        let w = self.state.body.rate_rad_s;
        0.5 * (self.model.inertia_kg_m2 * w * w).element_sum()
    }

    fn potential_energy(&self) -> f64 {
        self.model.mass_kg * self.model.gravity_m_s2 * self.state.body.position_m.z
    }

    /// Kinetic plus potential energy, J.
    fn mechanical_energy(&self) -> f64 {
        self.translational_energy() + self.rotational_energy() + self.potential_energy()
    }

    /// Angular momentum about the CG in I, `R I w`.
    fn angular_momentum(&self) -> DVec3 {
        self.rotation() * (self.model.inertia_kg_m2 * self.state.body.rate_rad_s)
    }

    /// Penetration of every footpad in the current state (without stepping), m.
    fn penetrations(&self) -> Vec<f64> {
        let body = &self.state.body;
        let rotation = self.rotation();
        self.model
            .legs
            .iter()
            .zip(&self.state.legs)
            .map(|(leg, ls)| {
                let tip = body.position_m + rotation * (leg.tip_m - leg.strut_axis * ls.stroke_m);
                self.surface.penetration(self.model.terrain.as_ref(), tip).0
            })
            .collect()
    }

    fn in_contact(&self) -> bool {
        self.penetrations().iter().any(|d| *d > 0.0)
    }

    fn absorbed_j(&self) -> f64 {
        self.state.legs.iter().map(|l| l.absorbed_j).sum()
    }

    /// Velocity of the CG along the downhill direction of the slope, m/s.
    fn downhill_speed(&self) -> f64 {
        self.state.body.velocity_m_s.dot(self.surface.tangent_u)
    }
}

/// Runs a scenario's sample to its classified outcome with `reference::run`.
fn classify(scenario: &Scenario, inputs: Inputs<f64>) -> Summary {
    run(&Model::new(scenario), &sample_of(inputs), |_| {})
}

/// Sets a gear on `slope_deg` at `downhill_deg` and steps it for `duration_s` or until its
/// tilt from the normal passes 90 deg; returns (largest tilt change, deg; largest CG
/// displacement, m; time its tilt passed 90 deg).
fn stand(
    scenario: &Scenario,
    slope_deg: f64,
    downhill_deg: f64,
    duration_s: f64,
) -> (f64, f64, Option<f64>) {
    let mut s = scenario.clone();
    s.simulation.t_max_s = duration_s;
    let mut sim = Sim::of(&s, on_slope(slope_deg, downhill_deg));
    let (tilt0, x0) = (sim.tilt_deg(), sim.state.body.position_m);
    let (mut tilt, mut moved) = (0.0f64, 0.0f64);
    let fell = sim.advance_while(|s| {
        tilt = tilt.max((s.tilt_deg() - tilt0).abs());
        moved = moved.max((s.state.body.position_m - x0).length());
        s.tilt_deg() <= 90.0
    });
    (tilt, moved, fell.then_some(sim.state.t_s))
}
