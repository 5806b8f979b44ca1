//! Analytic validation of the reference model (MODEL.md section 12).
//!
//! Prototype: measurements only.

use glam::{DMat3, DVec3};
use touchdown::reference::step::{step, step_size};
use touchdown::reference::{Model, State, StepReport, Surface, initial_state};
use touchdown::sampling::Sample;
use touchdown::scenario::{Inputs, Scenario};

fn quiet_inputs() -> Inputs<f64> {
    Inputs::from_array([0.0; 12])
}

fn sample_of(inputs: Inputs<f64>) -> Sample {
    Sample {
        index: 0,
        seed: 0,
        inputs,
        terrain_tile: 0,
        terrain_offset_m: [0.0; 2],
    }
}

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
    fn advance(&mut self) {
        let dt = step_size(&self.model, &self.surface, &self.state);
        step(
            &self.model,
            &self.surface,
            &mut self.state,
            dt,
            &mut self.report,
        );
    }
    fn kinetic_energy(&self) -> f64 {
        let b = &self.state.body;
        let w = b.rate_rad_s;
        0.5 * self.model.mass_kg * b.velocity_m_s.length_squared()
            + 0.5 * (self.model.inertia_kg_m2 * w * w).element_sum()
    }
    fn angular_momentum(&self) -> DVec3 {
        let b = &self.state.body;
        DMat3::from_quat(b.attitude) * (self.model.inertia_kg_m2 * b.rate_rad_s)
    }
}

#[test]
fn proto_free_flight() {
    for inertia in [[18.0, 18.0, 15.0], [10.0, 20.0, 25.0], [30.0, 20.0, 12.0]] {
        for rates in [[5.0, -3.0, 10.0], [30.0, 20.0, -45.0], [100.0, 10.0, 50.0]] {
            for fmax in [0.05, 0.01, 0.001] {
                let mut s = Scenario::default();
                s.lander.inertia_kg_m2 = inertia;
                s.initial.clearance_m = 1.0e4;
                s.simulation.t_max_s = 100.0;
                s.simulation.flight_step_max_s = fmax;
                let model = Model::new(&s);
                let mut x = quiet_inputs();
                x.rate_x_deg_s = rates[0];
                x.rate_y_deg_s = rates[1];
                x.rate_z_deg_s = rates[2];
                let mut sim = Sim::new(model, x);
                let e0 = sim.kinetic_energy();
                let l0 = sim.angular_momentum();
                let mut emax: f64 = 0.0;
                let mut lmax: f64 = 0.0;
                while sim.state.t_s < 100.0 - 1e-9 {
                    sim.advance();
                    emax = emax.max((sim.kinetic_energy() / e0 - 1.0).abs());
                    lmax = lmax.max((sim.angular_momentum() - l0).length() / l0.length());
                }
                println!(
                    "{inertia:?} {rates:?} dt {fmax}: dE {emax:.3e} dL {lmax:.3e} last dt {}",
                    sim.report.dt_s
                );
            }
        }
    }
}
