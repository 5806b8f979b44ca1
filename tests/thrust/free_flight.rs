//! Constant thrust in free flight: exact, like gravity (MODEL.md sections 2 and 7), in the
//! scalar reference and in every f64 kernel this CPU has.

use super::{FLIGHT_S, Sim, constant_thrust, f64_kernels, flight_scenario, posed, quat_apart};
use crate::common::Table;
use crate::lander::sample_of;
use glam::{DMat3, DQuat, DVec3};
use kernels::block::Block;
use kernels::isa::{Kernel, WithKernel};
use kernels::params::Params;
use touchdown::reference::{Model, initial_state};
use touchdown::scenario::Scenario;
use touchdown::slope::Surface;
use touchdown::sweep::{kernel_params, lane_init, lane_thrust};

/// Gravity of the free-flight runs: none and the default (0.0168), m/s^2.
const FLIGHT_GRAVITIES: [f64; 2] = [0.0, 0.0168];

/// A constant-thrust case: thrust (force and moment in B), attitude (roll, pitch, yaw,
/// deg), initial velocity (m/s) and body rates (deg/s).
#[derive(Debug, Clone, Copy)]
struct FlightCase {
    force_b_n: [f64; 3],
    moment_b_n_m: [f64; 3],
    attitude_deg: [f64; 3],
    velocity_m_s: [f64; 3],
    rates_deg_s: [f64; 3],
}

/// Thrust forces through the CG of a body that does not turn: up along Z_B upright and
/// tilted, oblique, sideways, pushing the lander down, one below the weight (0.02 N against
/// 1.68 N) and one nearly horizontal.
const FORCE_CASES: [FlightCase; 7] = [
    FlightCase {
        force_b_n: [0.0, 0.0, 5.0],
        moment_b_n_m: [0.0; 3],
        attitude_deg: [0.0, 0.0, 0.0],
        velocity_m_s: [0.0, 0.0, -0.5],
        rates_deg_s: [0.0; 3],
    },
    FlightCase {
        force_b_n: [0.0, 0.0, 5.0],
        moment_b_n_m: [0.0; 3],
        attitude_deg: [30.0, -20.0, 45.0],
        velocity_m_s: [0.1, 0.0, -0.3],
        rates_deg_s: [0.0; 3],
    },
    FlightCase {
        force_b_n: [3.0, -2.0, 1.0],
        moment_b_n_m: [0.0; 3],
        attitude_deg: [10.0, 60.0, -120.0],
        velocity_m_s: [0.3, -0.2, 0.1],
        rates_deg_s: [0.0; 3],
    },
    FlightCase {
        force_b_n: [0.0, 10.0, 0.0],
        moment_b_n_m: [0.0; 3],
        attitude_deg: [-45.0, 0.0, 90.0],
        velocity_m_s: [0.0, 0.0, 0.0],
        rates_deg_s: [0.0; 3],
    },
    FlightCase {
        force_b_n: [-1.0, 0.5, -4.0],
        moment_b_n_m: [0.0; 3],
        attitude_deg: [80.0, 10.0, 0.0],
        velocity_m_s: [-0.2, 0.4, 0.0],
        rates_deg_s: [0.0; 3],
    },
    FlightCase {
        force_b_n: [0.0, 0.0, 0.02],
        moment_b_n_m: [0.0; 3],
        attitude_deg: [5.0, 5.0, 5.0],
        velocity_m_s: [0.0, 0.0, 0.2],
        rates_deg_s: [0.0; 3],
    },
    FlightCase {
        force_b_n: [2.0, 2.0, 2.0],
        moment_b_n_m: [0.0; 3],
        attitude_deg: [0.0, 85.0, 30.0],
        velocity_m_s: [0.05, 0.05, 0.05],
        rates_deg_s: [0.0; 3],
    },
];

/// A constant moment about one principal axis, with the body turning about that axis
/// alone (no force): the gyroscopic terms `(I_j - I_k) w_j w_k` stay zero, so the rate
/// grows as `w0 + M / I t` and the angle about the fixed axis as `w0 t + M t^2 / (2 I)`.
const MOMENT_CASES: [FlightCase; 4] = [
    FlightCase {
        force_b_n: [0.0; 3],
        moment_b_n_m: [0.05, 0.0, 0.0],
        attitude_deg: [0.0, 0.0, 0.0],
        velocity_m_s: [0.0; 3],
        rates_deg_s: [0.0; 3],
    },
    FlightCase {
        force_b_n: [0.0; 3],
        moment_b_n_m: [0.0, -0.03, 0.0],
        attitude_deg: [10.0, 20.0, 30.0],
        velocity_m_s: [0.0; 3],
        rates_deg_s: [0.0, 1.0, 0.0],
    },
    FlightCase {
        force_b_n: [0.0; 3],
        moment_b_n_m: [0.0, 0.0, 0.2],
        attitude_deg: [-15.0, 5.0, 0.0],
        velocity_m_s: [0.0; 3],
        rates_deg_s: [0.0, 0.0, -6.0],
    },
    FlightCase {
        force_b_n: [0.0; 3],
        moment_b_n_m: [-0.5, 0.0, 0.0],
        attitude_deg: [0.0, -30.0, 60.0],
        velocity_m_s: [0.0; 3],
        rates_deg_s: [3.0, 0.0, 0.0],
    },
];

/// The closed form of a flight from `body0` (position, velocity, attitude, rates at t = 0)
/// under the constant thrust of `case` after `t`: position, velocity, attitude, rates.
fn flight_exact(
    model: &Model,
    body0: &touchdown::reference::rigid_body::Body,
    case: &FlightCase,
    t: f64,
) -> (DVec3, DVec3, DQuat, DVec3) {
    let force_i = DMat3::from_quat(body0.attitude) * DVec3::from_array(case.force_b_n);
    let a = force_i / model.mass_kg - DVec3::Z * model.gravity_m_s2;
    let x = body0.position_m + body0.velocity_m_s * t + a * (0.5 * t * t);
    let v = body0.velocity_m_s + a * t;
    // About one principal axis (the moment's, or the rates', or none).
    let m = DVec3::from_array(case.moment_b_n_m);
    let w0 = body0.rate_rad_s;
    let accel = m / model.inertia_kg_m2;
    let w = w0 + accel * t;
    let turn = w0 * t + accel * (0.5 * t * t);
    let attitude = if turn.length() > 0.0 {
        body0.attitude * DQuat::from_axis_angle(turn.normalize(), turn.length())
    } else {
        body0.attitude
    };
    (x, v, attitude, w)
}

/// Largest errors of a flight against `flight_exact`: position (m), velocity (m/s),
/// attitude (`quat_apart`), rates (rad/s).
#[derive(Debug, Clone, Copy, Default)]
struct FlightErrors {
    position: f64,
    velocity: f64,
    attitude: f64,
    rate: f64,
}

impl FlightErrors {
    fn take(
        &mut self,
        exact: (DVec3, DVec3, DQuat, DVec3),
        x: DVec3,
        v: DVec3,
        q: DQuat,
        w: DVec3,
    ) {
        self.position = self.position.max((x - exact.0).length());
        self.velocity = self.velocity.max((v - exact.1).length());
        self.attitude = self.attitude.max(quat_apart(q, exact.2));
        self.rate = self.rate.max((w - exact.3).length());
    }
}

/// Tolerances of the free flights. The thrust enters as gravity does, as a constant
/// acceleration over the step (`x += v dt + a dt^2 / 2`, `v += a dt`), exact at any step, and
/// a moment about a principal axis of a body turning about it alone gives an exact rate
/// (`2 mid - w0 = w0 + M dt / I`) and an exact turn (`mid dt`, the increment's series
/// exact to 1e-17 at the 0.03 rad of these steps). What is left is rounding: at most 1e5
/// steps (100 s of 1 ms), each adding to a position below 1.1e4 m (ulp 1.8e-12 m), a
/// velocity below 16 m/s (ulp 3.6e-15 m/s), a rate below 2 rad/s (ulp 4.4e-16 rad/s) and
/// multiplying the attitude by an increment (a few 1e-16): worst cases 1.8e-7 m,
/// 3.6e-10 m/s, 4.4e-11 rad/s, 1e-10. Tolerances 1e-6 m, 1e-9 m/s, 1e-9 (attitude) and
/// 1e-9 rad/s. A thrust taken in the wrong frame, at the end of the step instead of
/// constant over it, or as semi-implicit Euler would give, is off by 1e-3 m and more.
const POSITION_TOLERANCE_M: f64 = 1e-6;
const VELOCITY_TOLERANCE_M_S: f64 = 1e-9;
const ATTITUDE_TOLERANCE: f64 = 1e-9;
const RATE_TOLERANCE_RAD_S: f64 = 1e-9;

fn flight_rows(table: &mut Table, case: &str, e: FlightErrors) {
    table.at_most(
        case,
        "max |x - exact| (m)",
        e.position,
        POSITION_TOLERANCE_M,
    );
    table.at_most(
        case,
        "max |v - exact| (m/s)",
        e.velocity,
        VELOCITY_TOLERANCE_M_S,
    );
    table.at_most(case, "max |q - exact|", e.attitude, ATTITUDE_TOLERANCE);
    table.at_most(
        case,
        "max |w - exact| (rad/s)",
        e.rate,
        RATE_TOLERANCE_RAD_S,
    );
}

/// The reference flight of `case`: errors against the closed form at every step.
fn reference_flight(scenario: &Scenario, case: &FlightCase) -> FlightErrors {
    let mut sim = Sim::of(
        scenario,
        posed(case.attitude_deg, case.velocity_m_s, case.rates_deg_s),
    );
    sim.state.thrust = constant_thrust(
        DVec3::from_array(case.force_b_n),
        DVec3::from_array(case.moment_b_n_m),
    );
    let body0 = sim.state.body;
    let mut e = FlightErrors::default();
    while sim.state.t_s < FLIGHT_S - 1e-9 {
        sim.advance();
        assert!(
            !sim.report.legs.iter().any(|l| l.in_contact()),
            "the free flight touched the surface"
        );
        let b = &sim.state.body;
        let exact = flight_exact(&sim.model, &body0, case, sim.state.t_s);
        e.take(
            exact,
            b.position_m,
            b.velocity_m_s,
            b.attitude,
            b.rate_rad_s,
        );
    }
    e
}

/// The flights of `cases` in the lanes of kernel `K` (one case per lane, in as many blocks as
/// the kernel's width takes): the errors of each against the closed form, checked after
/// every 10 steps.
struct KernelFlights<'a> {
    scenario: &'a Scenario,
    cases: &'a [FlightCase],
}

impl WithKernel for KernelFlights<'_> {
    type Output = Vec<FlightErrors>;

    fn run<K: Kernel>(self) -> Vec<FlightErrors> {
        let model = Model::new(self.scenario);
        let mut params = kernel_params::<K>(&model);
        // The scenario has no thrusters: compile the thrust path in by hand.
        params.thrust = true;
        self.cases
            .chunks(K::LANES)
            .flat_map(|cases| block_flights::<K>(&model, &params, cases))
            .collect()
    }
}

/// The flights of `cases` (at most `K::LANES`) in one block of kernel `K`.
fn block_flights<K: Kernel>(
    model: &Model,
    params: &Params<K>,
    cases: &[FlightCase],
) -> Vec<FlightErrors> {
    let mut block = Block::<K>::new(params);
    assert!(cases.len() <= K::LANES);
    let mut starts = Vec::new();
    for (i, case) in cases.iter().enumerate() {
        let sample = sample_of(posed(
            case.attitude_deg,
            case.velocity_m_s,
            case.rates_deg_s,
        ));
        block.load(i, &lane_init(model, &sample));
        let thrust = constant_thrust(
            DVec3::from_array(case.force_b_n),
            DVec3::from_array(case.moment_b_n_m),
        );
        block.set_thrust(i, &lane_thrust(&thrust));
        let surface = Surface::of(&sample);
        starts.push(initial_state(model, &surface, &sample).body);
    }
    let mut errors = vec![FlightErrors::default(); cases.len()];
    loop {
        let advanced = K::advance(params, &mut block, 10);
        assert_eq!(advanced.events, 0, "{}: no control event comes", K::NAME);
        for (i, case) in cases.iter().enumerate() {
            let t = block.t_s.lane(i);
            let exact = flight_exact(model, &starts[i], case, t);
            errors[i].take(
                exact,
                DVec3::from_array(block.position_m.lane(i)),
                DVec3::from_array(block.velocity_m_s.lane(i)),
                DQuat::from_array(block.attitude.lane(i)),
                DVec3::from_array(block.rate_rad_s.lane(i)),
            );
            assert!(
                block
                    .leg_step
                    .iter()
                    .all(|l| l.penetration_m.lane(i) <= 0.0),
                "the free flight touched the surface"
            );
        }
        if (0..cases.len()).all(|i| block.t_s.lane(i) >= FLIGHT_S - 1e-9) {
            break;
        }
    }
    errors
}

#[test]
fn thrust_constant_force_in_free_flight_is_exact() {
    // x0 + v0 t + (F_I / m - g0 Z) t^2 / 2 and v0 + (F_I / m - g0 Z) t, F_I = R F_B with
    // the body not turning (zero rates, thrust through the CG), at flight steps of 1 ms,
    // 0.05 s and 1 s, in the reference (its own step sizes) and in every f64 kernel
    // (one case per lane). Tolerances: see `POSITION_TOLERANCE_M`.
    let mut table = Table::new("thrust: constant force in free flight, 100 s, closed form");
    for g0 in FLIGHT_GRAVITIES {
        for flight_step in [1e-3, 0.05, 1.0] {
            let s = flight_scenario(g0, flight_step);
            for case in &FORCE_CASES {
                let name = format!(
                    "ref g0 {g0} dt<={flight_step} F_B {:?} att {:?}",
                    case.force_b_n, case.attitude_deg
                );
                flight_rows(&mut table, &name, reference_flight(&s, case));
            }
            for kernel in f64_kernels() {
                let errors = kernel.dispatch(KernelFlights {
                    scenario: &s,
                    cases: &FORCE_CASES,
                });
                for (case, e) in FORCE_CASES.iter().zip(errors) {
                    let name = format!(
                        "{} g0 {g0} dt<={flight_step} F_B {:?} att {:?}",
                        kernel.name(),
                        case.force_b_n,
                        case.attitude_deg
                    );
                    flight_rows(&mut table, &name, e);
                }
            }
        }
    }
    table.finish();
}

#[test]
fn thrust_moment_about_a_principal_axis_is_exact() {
    // Zero thrust force, a constant moment M about one principal axis, the body turning
    // about that axis alone: w = w0 + M / I t, turned by w0 t + M t^2 / (2 I) about the
    // fixed axis, CG ballistic. Flight steps of 1 ms and 0.05 s (0.03 rad per step at
    // most; at 1 s steps the increment's series would be off by (w dt / 2)^8 / 8!).
    // Reference and every f64 kernel. Tolerances: see `POSITION_TOLERANCE_M`.
    let mut table = Table::new("thrust: constant moment about a principal axis, 100 s");
    for g0 in FLIGHT_GRAVITIES {
        for flight_step in [1e-3, 0.05] {
            let s = flight_scenario(g0, flight_step);
            for case in &MOMENT_CASES {
                let name = format!(
                    "ref g0 {g0} dt<={flight_step} M_B {:?} w0 {:?}",
                    case.moment_b_n_m, case.rates_deg_s
                );
                flight_rows(&mut table, &name, reference_flight(&s, case));
            }
            for kernel in f64_kernels() {
                let errors = kernel.dispatch(KernelFlights {
                    scenario: &s,
                    cases: &MOMENT_CASES,
                });
                for (case, e) in MOMENT_CASES.iter().zip(errors) {
                    let name = format!(
                        "{} g0 {g0} dt<={flight_step} M_B {:?} w0 {:?}",
                        kernel.name(),
                        case.moment_b_n_m,
                        case.rates_deg_s
                    );
                    flight_rows(&mut table, &name, e);
                }
            }
        }
    }
    table.finish();
}
