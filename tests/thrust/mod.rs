//! Closed-form validation of the thrust physics (MODEL.md sections 2, 5, 7 and 8).
//!
//! Each test runs the scalar reference (and, for free flight, every f64 kernel this CPU
//! has) at several parameter values and compares a measured quantity with its closed-form
//! answer, within a tolerance argued at the check. Every test prints its whole table of
//! measured against expected values before it fails on any row, so that `cargo test
//! --release --test tests thrust -- --nocapture` shows every number, passing or not.

use crate::lander::{quiet, sample_in};
use glam::{DQuat, DVec3};
use kernels::isa::{Isa, KernelKind, Precision};
use touchdown::control::Thrust;
use touchdown::reference::step::{step, step_size};
use touchdown::reference::{Model, State, StepReport, initial_state};
use touchdown::scenario::{Inputs, Scenario};
use touchdown::slope::Surface;

mod accelerations;
mod attitude;
mod descent;
mod free_flight;
mod held;
mod hold_down;
mod propellant;
mod stop_tilt;
mod switches;
mod tipping;

// ---------------------------------------------------------------------------------------
// Helpers: inputs, a step driver, thrusts and the results table.
// ---------------------------------------------------------------------------------------

/// Inputs of an attitude (roll, pitch, yaw, deg), an initial velocity and body rates.
fn posed(attitude_deg: [f64; 3], velocity_m_s: [f64; 3], rates_deg_s: [f64; 3]) -> Inputs<f64> {
    Inputs {
        roll_deg: attitude_deg[0],
        pitch_deg: attitude_deg[1],
        yaw_deg: attitude_deg[2],
        velocity_error_x_m_s: velocity_m_s[0],
        velocity_error_y_m_s: velocity_m_s[1],
        velocity_error_z_m_s: velocity_m_s[2],
        rate_x_deg_s: rates_deg_s[0],
        rate_y_deg_s: rates_deg_s[1],
        rate_z_deg_s: rates_deg_s[2],
        ..quiet()
    }
}

/// A constant thrust (force and moment in B) with no control event to come.
fn constant_thrust(force_b_n: DVec3, moment_b_n_m: DVec3) -> Thrust {
    Thrust {
        force_b_n,
        moment_b_n_m,
        event_in_s: f64::INFINITY,
        approach_m_s: 0.0,
        powered: true,
        flow_n: force_b_n.length(),
    }
}

/// One lander stepped by hand (the thrust in `state.thrust` set by the test).
struct Sim {
    model: Model,
    surface: Surface,
    state: State,
    report: StepReport,
}

impl Sim {
    fn of(scenario: &Scenario, inputs: Inputs<f64>) -> Sim {
        let model = Model::new(scenario);
        let sample = sample_in(scenario, inputs);
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

    /// One step of the engine's own size (`step_size`).
    fn advance(&mut self) {
        let dt = step_size(&self.model, &self.surface, &self.state);
        self.step_by(dt);
    }

    /// One step of `dt`.
    fn step_by(&mut self, dt: f64) {
        step(
            &self.model,
            &self.surface,
            &mut self.state,
            dt,
            &mut self.report,
        );
    }

    /// Steps of the engine's size until `t` (to rounding).
    fn advance_to(&mut self, t: f64) {
        while self.state.t_s < t - 1e-9 {
            self.advance();
        }
    }

    /// Tilt of Z_B from the slope normal, deg.
    fn tilt_deg(&self) -> f64 {
        let z = self.state.body.attitude * DVec3::Z;
        z.dot(self.surface.normal)
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    }

    /// Sum of the legs' normal forces in the last step, N.
    fn normal_force_n(&self) -> f64 {
        self.report.legs.iter().map(|l| l.normal_n).sum()
    }
}

/// The f64 kernels this CPU runs.
fn f64_kernels() -> Vec<KernelKind> {
    Isa::ALL
        .into_iter()
        .filter(|i| i.available())
        .map(|isa| KernelKind {
            isa,
            precision: Precision::F64,
        })
        .collect()
}

/// Angle between two attitudes, as the length of the difference of their quaternions
/// (either sign): `2 sin(angle / 4)`, about half the angle.
fn quat_apart(a: DQuat, b: DQuat) -> f64 {
    (a - b).length().min((a + b).length())
}

/// Length of the free-flight runs, s.
const FLIGHT_S: f64 = 100.0;

/// The scenario of the free flights: 10 km above the surface (no contact in 100 s), the
/// default lander, gravity `g0`, flight steps of at most `flight_step_s`.
fn flight_scenario(g0: f64, flight_step_s: f64) -> Scenario {
    let mut s = Scenario {
        gravity_m_s2: g0,
        ..Scenario::default()
    };
    s.initial.clearance_m = 1.0e4;
    s.simulation.flight_step_max_s = flight_step_s;
    s.simulation.step_s = flight_step_s.min(1e-3);
    s.simulation.t_max_s = FLIGHT_S;
    s
}
