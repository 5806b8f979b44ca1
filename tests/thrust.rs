//! Closed-form validation of the thrust physics (MODEL.md sections 2, 5, 7 and 8).
//!
//! Each test runs the scalar reference (and, for free flight, every f64 kernel this CPU
//! has) at several parameter values and compares a measured quantity with its closed-form
//! answer, within a tolerance argued at the check. Every test prints its whole table of
//! measured against expected values before it fails on any row, so that `cargo test
//! --release --test tests thrust -- --nocapture` shows every number, passing or not.

use crate::common::Table;
use crate::lander::{
    CG_HEIGHT_M, FALL_WITHIN_S, Facing, quiet, regular, sample_of, standing, tipping_slope_between,
};
use glam::{DMat3, DQuat, DVec3};
use kernels::block::Block;
use kernels::isa::{Isa, Kernel, KernelKind, Precision, WithKernel};
use touchdown::control::Thrust;
use touchdown::control::{ControlModel, LaneControl, Truth, attitude_torque};
use touchdown::reference::step::{step, step_size};
use touchdown::reference::{Model, State, StepReport, initial_state, run};
use touchdown::sampling;
use touchdown::scenario::Sample;
use touchdown::scenario::{Dist, G0_M_S2, Inputs, Scenario, Sensors, Target};
use touchdown::slope::Surface;
use touchdown::sweep::{kernel_params, lane_init, lane_thrust};

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

/// Inputs of a slope with its downhill azimuth, nothing else.
fn on_slope(slope_deg: f64, downhill_azimuth_deg: f64) -> Inputs<f64> {
    Inputs {
        slope_deg,
        downhill_azimuth_deg,
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

// ---------------------------------------------------------------------------------------
// 1. Constant thrust in free flight: exact, like gravity (MODEL.md sections 2 and 7).
// ---------------------------------------------------------------------------------------

/// Length of the free-flight runs, s.
const FLIGHT_S: f64 = 100.0;

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

/// The flights of `cases` in the lanes of one block of kernel `K` (one case per lane): the
/// errors of each against the closed form, checked after every 10 steps.
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
        let mut block = Block::<K>::new(&params);
        assert!(self.cases.len() <= K::LANES);
        let mut starts = Vec::new();
        for (i, case) in self.cases.iter().enumerate() {
            let sample = sample_of(posed(
                case.attitude_deg,
                case.velocity_m_s,
                case.rates_deg_s,
            ));
            block.load(i, &lane_init(&model, &sample));
            let thrust = constant_thrust(
                DVec3::from_array(case.force_b_n),
                DVec3::from_array(case.moment_b_n_m),
            );
            block.set_thrust(i, &lane_thrust(&thrust));
            let surface = Surface::of(&sample);
            starts.push(initial_state(&model, &surface, &sample).body);
        }
        let mut errors = vec![FlightErrors::default(); self.cases.len()];
        loop {
            let advanced = K::advance(&params, &mut block, 10);
            assert_eq!(advanced.events, 0, "{}: no control event comes", K::NAME);
            for (i, case) in self.cases.iter().enumerate() {
                let t = block.t_s.lane(i);
                let exact = flight_exact(&model, &starts[i], case, t);
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
            if (0..self.cases.len()).all(|i| block.t_s.lane(i) >= FLIGHT_S - 1e-9) {
                break;
            }
        }
        errors
    }
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

// ---------------------------------------------------------------------------------------
// 2. Hold-down at rest: the legs bear the weight's normal component plus the thrust.
// ---------------------------------------------------------------------------------------

/// Settling time before each measurement of the hold-down test, s.
const SETTLE_S: f64 = 10.0;

#[test]
fn thrust_hold_down_adds_to_the_normal_force() {
    // The default lander set down aligned with a plane (flat, 10 and 20 deg, mu 0.6: below
    // the friction angle of 31 deg and the tipping limits of 44.7 deg and more) settles for
    // 10 s; then a thrust F along -Z_B through the CG (Z_B along the normal, to the
    // settling's 1e-3 deg) pushes it for 10 s more. At rest the sum of the legs' normal
    // forces balances the normal components of weight and thrust: m g0 cos(a) + F
    // (before the thrust, m g0 cos(a)). Newton's law along the normal says the residual is
    // m times the CG's normal acceleration (plus F (1 - cos tilt), 1e-10 F): what is left
    // of the settling transient. Its slowest mode, the stick-slip friction springs on the
    // yaw and sway axes (4 k_f r^2 = 7.2e4 N m/rad against I_z = 15 kg m^2, damped by
    // 4 c_f r^2 = 1.6e3 N m s/rad: a time constant below 0.02 s), is below 1e-100 of the
    // load after 10 s, so only rounding is left (sums of four forces of up to 11 N: 1e-14
    // N). Tolerance 1e-9 relative to the load, with margin for rounding-level limit cycles
    // of the stick-slip spring. A thrust lost, doubled or tilted by 1 deg would be off by
    // 5 N, 2e-4 N and more.
    let mut table = Table::new("thrust: hold-down at rest, sum of normal forces");
    for (slope, downhill) in [(0.0, 0.0), (10.0, 0.0), (10.0, 45.0), (20.0, 30.0)] {
        for thrust in [5.0, 20.0, 40.0] {
            let s = standing(regular(4, 0.6, 45.0), 0.6);
            let mut sim = Sim::of(&s, on_slope(slope, downhill));
            let (m, g0) = (sim.model.mass_kg, sim.model.gravity_m_s2);
            let weight = m * g0 * slope.to_radians().cos();
            let case = format!("slope {slope} azimuth {downhill}, F {thrust} N");
            sim.advance_to(SETTLE_S);
            table.relative(
                &case,
                "passive: sum N (N)",
                sim.normal_force_n(),
                weight,
                1e-9,
            );
            let (x0, tilt0) = (sim.state.body.position_m, sim.tilt_deg());
            sim.state.thrust = constant_thrust(DVec3::new(0.0, 0.0, -thrust), DVec3::ZERO);
            sim.state.thrust.powered = false;
            sim.advance_to(2.0 * SETTLE_S);
            let mut worst: f64 = 0.0;
            let end = 2.0 * SETTLE_S + 1.0;
            while sim.state.t_s < end - 1e-9 {
                sim.advance();
                worst = worst.max((sim.normal_force_n() / (weight + thrust) - 1.0).abs());
            }
            table.relative(
                &case,
                "thrust: sum N (N)",
                sim.normal_force_n(),
                weight + thrust,
                1e-9,
            );
            table.at_most(&case, "thrust: max rel. error, last 1 s", worst, 1e-9);
            // Stuck in place: the thrust only presses the springs (F / (4 k) = 0.2 mm at
            // 40 N on flat ground), and no leg slides. Tolerance 1 mm, tilt 0.1 deg.
            let moved = (sim.state.body.position_m - x0).length();
            table.at_most(&case, "CG moved under thrust (m)", moved, 1e-3);
            table.at_most(
                &case,
                "tilt change under thrust (deg)",
                (sim.tilt_deg() - tilt0).abs(),
                0.1,
            );
            table.equal(
                &case,
                "a leg slips",
                sim.report.legs.iter().any(|l| l.slipping),
                false,
            );
        }
    }
    table.finish();
}

// ---------------------------------------------------------------------------------------
// 3. Static tipping limit under hold-down thrust.
// ---------------------------------------------------------------------------------------

/// The slope at which a gear pushed by `thrust` along -Z_B through the CG tips: about the
/// downhill edge, weight (m g0 at height h above the footpad plane, r behind the edge)
/// tips it while m g0 (h sin a - r cos a) exceeds F r, i.e. a = atan(r / h) + asin(F r /
/// (m g0 L)), L = sqrt(h^2 + r^2). `r` and `h` from `stability::static_limit_deg` (the
/// passive limit atan(r / h)), deg.
fn thrust_limit_deg(scenario: &Scenario, downhill_deg: f64, thrust: f64) -> (f64, f64) {
    let tips = scenario.lander.tips_m();
    let passive = touchdown::stability::static_limit_deg(&tips, downhill_deg).expect("stands");
    let h = -tips[0][2];
    let r = h * passive.to_radians().tan();
    let weight = scenario.lander.mass_kg * scenario.gravity_m_s2;
    let lift = (thrust * r / (weight * h.hypot(r))).asin();
    (passive, passive + lift.to_degrees())
}

/// Sets the gear of `scenario` on `slope_deg` at `downhill_deg` with `thrust` along -Z_B
/// from the start and steps it for `duration_s` or until its tilt from the normal passes
/// 90 deg; returns (largest tilt change, deg; largest CG displacement, m; time its tilt
/// passed 90 deg).
fn stand(
    scenario: &Scenario,
    slope_deg: f64,
    downhill_deg: f64,
    thrust: f64,
    duration_s: f64,
) -> (f64, f64, Option<f64>) {
    let mut sim = Sim::of(scenario, on_slope(slope_deg, downhill_deg));
    sim.state.thrust = constant_thrust(DVec3::new(0.0, 0.0, -thrust), DVec3::ZERO);
    let (tilt0, x0) = (sim.tilt_deg(), sim.state.body.position_m);
    let (mut tilt, mut moved) = (0.0f64, 0.0f64);
    while sim.state.t_s < duration_s - 1e-9 {
        sim.advance();
        tilt = tilt.max((sim.tilt_deg() - tilt0).abs());
        moved = moved.max((sim.state.body.position_m - x0).length());
        if sim.tilt_deg() > 90.0 {
            return (tilt, moved, Some(sim.state.t_s));
        }
    }
    (tilt, moved, None)
}

/// The gear set down gently: contact damping 2e4 N s/m per leg, normal and tangential
/// (overdamped, still stable at 1 ms), friction 3 (no sliding below 71 deg, nor with the
/// thrust's friction cap, below the 85 deg of these cases).
fn gently(legs: usize, footpad_radius_m: f64, first_leg_deg: f64) -> Scenario {
    let mut s = standing(regular(legs, footpad_radius_m, first_leg_deg), 3.0);
    s.surface.damping_n_s_per_m = 2.0e4;
    s.surface.friction_damping_n_s_per_m = 2.0e4;
    s.simulation.t_max_s = 2.0 * FALL_WITHIN_S;
    s
}

/// Bisects, to 1/64 deg, the slope between `stays` and `falls` at which the gear of
/// `scenario` with `thrust` falls over within FALL_WITHIN_S.
fn tipping_slope(scenario: &Scenario, downhill: f64, thrust: f64, stays: f64, falls: f64) -> f64 {
    tipping_slope_between(stays, falls, |slope| {
        stand(scenario, slope, downhill, thrust, FALL_WITHIN_S)
            .2
            .is_some()
    })
}

#[test]
fn thrust_raises_the_static_tipping_limit() {
    // A gear set down gently, aligned with the slope, with a thrust F along -Z_B through
    // the CG from the start: it tips at a = atan(r/h) + asin(F r / (m g0 L))
    // (`thrust_limit_deg`; g0 = 0.0168, m g0 = 1.68 N, so 0.25-1 N moves the limit by
    // 6-29 deg). As the passive test (tests/validation.rs): 0.5 deg below, over 60 s its
    // tilt may change by the contact compliance alone ((m g0 + F) / (4 k) ~ 1e-5 m over a
    // ~1 m footprint: ~1e-3 deg; tolerance 1 deg) and its CG move by the settling into the
    // springs (tolerance 3 mm); 0.5 deg above, it must fall over (tilt past 90 deg) within
    // FALL_WITHIN_S. Past the limit the thrust's moment about the edge stays F r (it turns
    // with the body) while the weight's grows with the tilt, up to m g0 L, which exceeds
    // F r by a factor (m g0 L) / (F r) >= 2 here: nothing holds it before
    // 90 deg. Four- and three-leg gears, a side and a leg facing downhill, F 0.25, 0.5, 1
    // N. For the default gear at 0.5 N the limit is also found by bisection to 1/64 deg:
    // within 0.05 deg, as the passive gentle test (the compliance moves it by ~1e-3 deg, and
    // a lander 0.01 deg past it takes ~70 s of the 400 s to fall).
    let mut table = Table::new("thrust: static tipping limit under hold-down thrust");
    for (legs, radius, first) in [(4, 0.6, 45.0), (3, 0.6, 30.0)] {
        for facing in [Facing::Side, Facing::Leg] {
            let s = gently(legs, radius, first);
            let downhill = facing.azimuth_deg(legs, first);
            for thrust in [0.25, 0.5, 1.0] {
                let (passive, limit) = thrust_limit_deg(&s, downhill, thrust);
                let case = format!(
                    "{legs} legs R {radius} {facing:?} downhill, F {thrust} N: \
                     {passive:.2} -> {limit:.2} deg"
                );
                let (tilt, moved, fell) = stand(&s, limit - 0.5, downhill, thrust, 60.0);
                table.at_most(&case, "-0.5: tilt change in 60 s (deg)", tilt, 1.0);
                table.at_most(&case, "-0.5: CG moved in 60 s (m)", moved, 3e-3);
                table.equal(&case, "-0.5: fell over", fell.is_some(), false);
                let (_, _, fell) = stand(&s, limit + 0.5, downhill, thrust, FALL_WITHIN_S);
                table.at_most(
                    &case,
                    "+0.5: time to tilt 90 deg (s)",
                    fell.unwrap_or(f64::INFINITY),
                    FALL_WITHIN_S,
                );
                if legs == 4 && thrust == 0.5 {
                    let measured = tipping_slope(&s, downhill, thrust, limit - 0.5, limit + 0.5);
                    table.close(&case, "tipping slope (deg)", measured, limit, 0.05);
                }
            }
        }
    }
    table.finish();
}

// ---------------------------------------------------------------------------------------
// 4. Attitude hold: PD torque, continuous and by pulse-width thrusters.
// ---------------------------------------------------------------------------------------

/// The tilt of `I theta'' = -kp theta - kd theta'` from `theta0` at rest, and its
/// impulse response (the tilt after a unit angular-velocity kick), at `t`.
fn pd_response(kp: f64, kd: f64, inertia: f64, theta0: f64, t: f64) -> (f64, f64) {
    let omega = (kp / inertia).sqrt();
    let zeta = kd / (2.0 * (kp * inertia).sqrt());
    if zeta < 1.0 {
        let wd = omega * (1.0 - zeta * zeta).sqrt();
        let decay = (-zeta * omega * t).exp();
        let (s, c) = (wd * t).sin_cos();
        (theta0 * decay * (c + zeta * omega / wd * s), decay * s / wd)
    } else {
        let root = omega * (zeta * zeta - 1.0).sqrt();
        let (s1, s2) = (-zeta * omega + root, -zeta * omega - root);
        let (e1, e2) = ((s1 * t).exp(), (s2 * t).exp());
        (
            theta0 * (s2 * e1 - s1 * e2) / (s2 - s1),
            (e1 - e2) / (s1 - s2),
        )
    }
}

#[test]
fn thrust_attitude_pd_follows_the_step_response() {
    // A body moment from `attitude_torque` (kp, kd, no deadband, target Z_I), recomputed
    // at the start of every 1 ms step and held over it, far above the surface: the roll
    // theta from theta0 at rest follows I_x theta'' = -kp theta - kd theta' (the law's
    // error is the rotation vector, exactly linear in theta; turning about X_B alone
    // there is no gyroscopic term). Under- and overdamped gains, two initial tilts, over
    // 30 s (or at least five time constants).
    //
    // Tolerance: holding the torque over a step is a forcing d(t) = M_n - M(t) of mean
    // -(dt/2) M'(t); the error e = theta - exact obeys the same equation driven by d / I, so
    // |e| <= (dt / 2) max|M'| / I * int |h|, h the impulse response (`pd_response`), to
    // first order in dt (the forcing's zero-mean sawtooth adds O(dt^2)). Twice that bound.
    // A moment applied with the wrong sign, twice, or one step late would be off by a
    // sizeable fraction of theta0.
    let mut table = Table::new("thrust: attitude PD (continuous torque), roll step response");
    let dt = 1e-3;
    for (kp, kd) in [
        (20.0, 5.0),
        (100.0, 20.0),
        (20.0, 40.0),
        (5.0, 60.0),
        (2.0, 1.0),
    ] {
        for theta0_deg in [5.0, 40.0] {
            let mut s = flight_scenario(0.0168, dt);
            s.simulation.t_max_s = 1e3;
            let mut sim = Sim::of(&s, posed([theta0_deg, 0.0, 0.0], [0.0; 3], [0.0; 3]));
            let inertia = sim.model.inertia_kg_m2.x;
            let theta0 = theta0_deg.to_radians();
            let zeta = kd / (2.0 * (kp * inertia).sqrt());
            let omega = (kp / inertia).sqrt();
            // The slowest decay rate of the response.
            let slowest = if zeta < 1.0 {
                zeta * omega
            } else {
                omega * (zeta - (zeta * zeta - 1.0).sqrt())
            };
            let duration = (5.0 / slowest).max(30.0);
            let steps = (duration / dt).round() as usize;
            sim.state.thrust = constant_thrust(DVec3::ZERO, DVec3::ZERO);
            let (mut worst, mut off_axis): (f64, f64) = (0.0, 0.0);
            // At t = 0: theta' = 0, theta'' = -kp theta0 / I.
            let mut max_dm = kd * kp * theta0 / inertia;
            let mut int_h = 0.0f64;
            for k in 0..steps {
                let b = sim.state.body;
                sim.state.thrust.moment_b_n_m =
                    attitude_torque(kp, kd, 0.0, b.attitude, b.rate_rad_s, DVec3::Z);
                sim.step_by(dt);
                let t = (k + 1) as f64 * dt;
                let q = sim.state.body.attitude;
                let theta = 2.0 * q.x.atan2(q.w);
                let (exact, h) = pd_response(kp, kd, inertia, theta0, t);
                worst = worst.max((theta - exact).abs());
                off_axis = off_axis.max(q.y.abs() + q.z.abs() + sim.state.body.rate_rad_s.y.abs());
                // Along the exact response: theta' = -(kp / I) theta0 h (it solves the
                // same equation from 0 with theta''(0) = -(kp / I) theta0),
                // theta'' = -(kp theta + kd theta') / I, M' = -kp theta' - kd theta''; and
                // the integral of |h|.
                let rate = -kp / inertia * theta0 * h;
                let accel = -(kp * exact + kd * rate) / inertia;
                max_dm = max_dm.max((kp * rate + kd * accel).abs());
                int_h += h.abs() * dt;
            }
            let tolerance = 2.0 * (0.5 * dt) * max_dm / inertia * int_h;
            let case = format!(
                "kp {kp} kd {kd} (zeta {zeta:.2}, w {omega:.2}) theta0 {theta0_deg} deg, {duration:.0} s"
            );
            table.at_most(&case, "max |theta - exact| (rad)", worst, tolerance);
            table.at_most(&case, "off-axis q_y, q_z, w_y", off_axis, 1e-12);
        }
    }
    table.finish();
}

/// The control model of scenarios/hold-down.toml with only attitude hold (gain `kp`, no
/// deadband), no sensor errors, no thruster errors and no latency.
fn attitude_hold_model(kp: f64) -> (Scenario, ControlModel) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/hold-down.toml");
    let mut s = Scenario::from_file(&path).expect("scenarios/hold-down.toml reads");
    s.propulsion.thrust_error_sd = 0.0;
    s.propulsion.misalignment_sd_deg = 0.0;
    let c = s.control.as_mut().expect("it has a control loop");
    c.latency_periods = 0;
    c.sensors = Sensors::default();
    c.hold_down = None;
    let a = c.attitude_hold.as_mut().expect("it has attitude hold");
    a.kp_n_m_per_rad = Dist::Fixed(kp);
    a.kd_n_m_s_per_rad = Dist::Fixed(40.0);
    a.deadband_deg = 0.0;
    a.target = Target::Vertical;
    let model = Model::new(&s).control.expect("a control model");
    (s, model)
}

#[test]
fn thrust_attitude_pulse_width_gives_the_commanded_torque() {
    // The thrusters of scenarios/hold-down.toml, attitude hold only (no noise, bias,
    // errors or latency, no deadband), a lander held at a fixed tilt at rest: over each
    // control period the thrust's moment, integrated over the segments between the loop's
    // events and divided by the period, must equal the law's command kp * (rotation
    // vector from Z_B to Z_I), clipped as a whole where the thrusters cannot give it
    // (the largest duty 1). Quantising each thruster's on-time to whole minimum on-times
    // moves it by at most half one: per axis, the torque moves by at most the sum over
    // the thrusters fired of |their torque about it| * min_on / (2 period); for the
    // attitude couples (two 1 N thrusters 0.45 m from the CG, 10 ms, 0.1 s) that is one
    // minimum impulse bit's torque, 1 N * 0.45 m * 0.01 s / 0.1 s = 0.045 N m. The mean
    // force must be zero to the same quantisation (the couples push both ways). Three
    // periods each, every period alike (a fixed truth). Tilts about X_B, Y_B and both, from
    // below one impulse bit (0.05 deg at kp 20) to saturated (10 deg), two gains.
    let mut table = Table::new("thrust: attitude hold by pulse-width thrusters, torque per period");
    for kp in [20.0, 5.0] {
        let (_, m) = attitude_hold_model(kp);
        let period = m.period_s;
        for (roll, pitch) in [
            (0.05, 0.0),
            (1.0, 0.0),
            (0.0, -2.0),
            (2.5, 0.0),
            (-1.0, 1.5),
            (0.0, 10.0),
            (-6.0, 8.0),
        ] {
            let attitude = touchdown::reference::run::from_euler_zyx(
                0.0,
                f64::to_radians(pitch),
                f64::to_radians(roll),
            );
            let command = attitude_torque(kp, 40.0, 0.0, attitude, DVec3::ZERO, DVec3::Z);
            // The law's torque, scaled down as a whole where a thruster would need more
            // than the period (`Allocation::duties`), from each axis's unit duties.
            let mut need = vec![0.0; m.thrusters.len()];
            for (axis, w) in command.to_array().into_iter().enumerate() {
                let k = (3 + axis) * 2 + usize::from(w < 0.0);
                if let Some(unit) = &m.allocation.unit[k] {
                    for (n, u) in need.iter_mut().zip(unit) {
                        *n += w.abs() * u;
                    }
                }
            }
            let most = need.iter().copied().fold(0.0, f64::max);
            let expected = command / most.max(1.0);
            // Per axis: the thrusters fired, their torque about it, half a minimum on-time.
            let mut bound = DVec3::ZERO;
            let mut force_bound = 0.0;
            for (j, t) in m.thrusters.iter().enumerate() {
                if need[j] > 0.0 {
                    let f = DVec3::from_array(t.direction) * t.max_thrust_n;
                    let tau = DVec3::from_array(t.position_m).cross(f);
                    bound += tau.abs() * (t.min_on_time_s / (2.0 * period));
                    force_bound += f.length() * t.min_on_time_s / (2.0 * period);
                }
            }
            let sample = Sample {
                seed: 7,
                ..sample_of(quiet())
            };
            let mut control = LaneControl::new(&m, &sample);
            let mut t_s = 0.0;
            let truth = |t_s: f64| Truth {
                t_s,
                position_m: DVec3::new(0.0, 0.0, 100.0),
                velocity_m_s: DVec3::ZERO,
                attitude,
                rate_rad_s: DVec3::ZERO,
                contact: false,
                normal: DVec3::Z,
            };
            let case = format!(
                "kp {kp} roll {roll} pitch {pitch}: command {:.4} {:.4}, saturation {most:.2}",
                command.x, command.y
            );
            for p in 0..3 {
                let (mut torque, mut force, mut elapsed, mut segments) =
                    (DVec3::ZERO, DVec3::ZERO, 0.0, 0);
                while elapsed < period - 1e-12 {
                    let thrust = control.event(&m, &truth(t_s));
                    assert!(thrust.event_in_s.is_finite() && thrust.event_in_s > 0.0);
                    torque += thrust.moment_b_n_m * thrust.event_in_s;
                    force += thrust.force_b_n * thrust.event_in_s;
                    elapsed += thrust.event_in_s;
                    t_s += thrust.event_in_s;
                    segments += 1;
                    assert!(segments < 100, "{case}: the period never ends");
                }
                let (torque, force) = (torque / period, force / period);
                let quantity = |what: &str| format!("period {p}: {what}");
                table.close(
                    &case,
                    &quantity("segments sum to the period (s)"),
                    elapsed,
                    period,
                    1e-12,
                );
                for (axis, name) in [(0, "X"), (1, "Y"), (2, "Z")] {
                    table.close(
                        &case,
                        &quantity(&format!("mean torque {name} (N m)")),
                        torque[axis],
                        expected[axis],
                        bound[axis] + 1e-12,
                    );
                }
                table.at_most(
                    &case,
                    &quantity("|mean force| (N)"),
                    force.length(),
                    force_bound + 1e-12,
                );
            }
        }
    }
    table.finish();
}

// ---------------------------------------------------------------------------------------
// 5. Propellant: the thrust's integral over isp g0.
// ---------------------------------------------------------------------------------------

#[test]
fn thrust_propellant_is_the_flow_integral() {
    // Whole reference runs of scenarios/hold-down.toml samples (attitude hold in the
    // stepped fall, hold-down after contact, sampled thruster errors and sensor noise),
    // at its Isp (220 s) and at 300 s: the propellant the loop books is the integral of
    // the firing thrusters' thrust magnitudes over the steps, over isp g0, to rounding
    // (relative 1e-9: the loop sums thrust times segment, the steps split each segment;
    // ~1e5 additions of rounding 1e-16). The hold-down impulse is a part of that
    // integral: at most it (plus rounding). The on-time is the thrusters firing, counted
    // per step, times the step (same tolerance).
    let mut table = Table::new("thrust: propellant = integral of thrust / (isp g0)");
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/hold-down.toml");
    let base = Scenario::from_file(&path).expect("scenarios/hold-down.toml reads");
    for isp in [220.0, 300.0] {
        let mut s = base.clone();
        s.propulsion.isp_s = isp;
        let model = Model::new(&s);
        for index in 0..8 {
            let sample = sampling::sample(&s, index);
            let (mut impulse, mut on_time, mut steps) = (0.0, 0.0, 0u64);
            let summary = run(&model, &sample, |r: &StepReport| {
                impulse += r.thrust.flow_n * r.dt_s;
                let firing = r
                    .control
                    .as_ref()
                    .map_or(0, |c| c.thrust_n.iter().filter(|&&f| f > 0.0).count());
                on_time += firing as f64 * r.dt_s;
                steps += 1;
            });
            let c = *summary.control.expect("a control summary");
            let case = format!(
                "isp {isp} sample {index} ({:?} at {:.1} s, {steps} steps, hold-down {:.1} N)",
                summary.outcome, summary.decided_s, c.hold_down_thrust_n
            );
            table.relative(
                &case,
                "propellant (kg)",
                c.propellant_kg,
                impulse / (isp * G0_M_S2),
                1e-9,
            );
            table.relative(&case, "on-time (s)", c.on_time_s, on_time, 1e-9);
            table.at_most(
                &case,
                "hold-down impulse - impulse (N s)",
                c.hold_down_impulse_n_s - impulse,
                1e-9 * impulse,
            );
        }
    }
    table.finish();
}

// ---------------------------------------------------------------------------------------
// 6. Descent: the final burn releases the lander into a ballistic fall.
// ---------------------------------------------------------------------------------------

/// The descent scenario of a perfect loop: four 1 N thrusters pushing along +Z_B and four
/// 10 N along -Z_B, symmetric about the CG, no thrust or pointing errors, no sensor
/// errors, no attitude hold; latency `latency` periods at 10 Hz; the descent of
/// scenarios/descent.toml (15 m at 0.2 m/s, braking 0.01 m/s^2, gain 2/s, release below
/// 0.01 m/s).
fn perfect_descent(latency: u32) -> Scenario {
    let mut text = String::from(
        "[initial]\nstart = \"descent\"\n[simulation]\nt_max_s = 150.0\n\
         [propulsion]\nthrust_error_sd = 0.0\nmisalignment_sd_deg = 0.0\n",
    );
    for (x, y) in [(0.45, 0.0), (-0.45, 0.0), (0.0, 0.45), (0.0, -0.45)] {
        for (z, thrust) in [(1.0, 1.0), (-1.0, 10.0)] {
            text += &format!(
                "[[thrusters]]\nposition_m = [{x}, {y}, 0.3]\ndirection = [0.0, 0.0, {z}]\n\
                 max_thrust_n = {thrust}\nmin_on_time_s = 0.01\n"
            );
        }
    }
    text += &format!(
        "[control]\nrate_hz = 10.0\nlatency_periods = {latency}\n[control.descent]\n\
         start_altitude_m = 15.0\nstart_speed_m_s = 0.2\nbraking_m_s2 = 0.01\n\
         gain_per_s = 2.0\nrelease_speed_m_s = 0.01\n"
    );
    Scenario::from_toml(&text).expect("the perfect descent reads")
}

#[test]
fn thrust_descent_releases_into_a_ballistic_fall() {
    // A perfect loop (sensors without errors) on level ground, upright and without rates,
    // at release heights 5, 7.5 and 10 m and latencies of 0, 1 and 2 periods:
    // - it releases at or below the release height (the altimeter reads the truth), at the
    //   first control instant whose reading allows it: no earlier reading of the descent
    //   was both at or below the release height and slower than the release speed;
    // - its approach rate at release is below the release speed (the sensed one is the
    //   true one);
    // - no thruster fires after the release (the burn's queued commands are dropped), and
    //   the first contact comes when the ballistic fall from the recorded release state,
    //   H + v t - g0 t^2 / 2 = 0, reaches the surface: t = (v + sqrt(v^2 + 2 g0 H)) / g0,
    //   within one 1 ms contact step (the upright gear's four footpads touch at once;
    //   tolerance 2 ms).
    let mut table = Table::new("thrust: descent, release and ballistic fall");
    let g0 = 0.0168;
    for latency in [0, 1, 2] {
        let s = perfect_descent(latency);
        let model = Model::new(&s);
        for release in [5.0, 7.5, 10.0] {
            let sample = sample_of(Inputs {
                release_height_m: release,
                ..quiet()
            });
            let mut fired_after_release = 0.0_f64;
            // Readings of the descent that would have allowed a release.
            let mut could_release = 0;
            let mut last_reading = f64::NAN;
            let summary = run(&model, &sample, |r: &StepReport| {
                let Some(c) = r.control.as_ref() else { return };
                if c.phase != "descent" {
                    fired_after_release = fired_after_release.max(r.thrust.flow_n);
                    return;
                }
                if let Some(s) = c.sensed
                    && s.t_s != last_reading
                {
                    last_reading = s.t_s;
                    let height = s.altitude_m - CG_HEIGHT_M;
                    could_release +=
                        usize::from(height <= release && s.velocity_m_s.z.abs() < 0.01);
                }
            });
            let c = *summary.control.expect("a control summary");
            let case = format!("latency {latency}, release height {release} m");
            table.equal(&case, "released", c.release_time_s.is_finite(), true);
            table.at_most(
                &case,
                "release altitude - release height (m)",
                c.release_altitude_m - release,
                0.0,
            );
            table.equal(
                &case,
                "readings that could release before the release",
                could_release,
                0,
            );
            let [vx, vy, vz] = c.release_velocity_m_s;
            table.at_most(&case, "|approach rate| at release (m/s)", vz.abs(), 0.01);
            table.at_most(
                &case,
                "horizontal speed at release (m/s)",
                vx.hypot(vy),
                1e-9,
            );
            table.at_most(&case, "thrust after release (N)", fired_after_release, 0.0);
            let fall = (vz + (vz * vz + 2.0 * g0 * c.release_altitude_m).sqrt()) / g0;
            table.close(
                &case,
                "first contact (s)",
                summary.first_contact_s.unwrap_or(f64::NAN),
                c.release_time_s + fall,
                2e-3,
            );
        }
    }
    table.finish();
}

#[test]
fn thrust_descent_parameters_are_drawn_per_sample() {
    // The descent's parameters are inputs like any other: a start altitude uniform in
    // 12-18 m and a braking on a grid of 0.005 and 0.01 m/s^2. Each sample starts with its
    // lowest footpad at its drawn altitude above the initial clearance (to rounding),
    // the grid alternates sample by sample (law parameters vary fastest), and the sweep's
    // rows carry the draws the initial state and the loop used.
    let mut s = perfect_descent(1);
    let d = s.control.as_mut().and_then(|c| c.descent.as_mut()).unwrap();
    d.start_altitude_m = Dist::Uniform {
        min: 12.0,
        max: 18.0,
    };
    d.braking_m_s2 = Dist::Grid {
        min: 0.005,
        max: 0.01,
        count: 2,
    };
    let model = Model::new(&s);
    let mut table = Table::new("thrust: descent parameters drawn per sample");
    let n = 16;
    let mut rows = Vec::new();
    let never = std::sync::atomic::AtomicUsize::new(0);
    touchdown::sweep::run_until(&s, &model, Isa::detect(), 0..n, 8, &never, |r| {
        rows.extend(r);
        Ok(())
    })
    .unwrap();
    let mut altitudes = Vec::new();
    for row in &rows {
        let sample = sampling::sample(&s, row.sample.index);
        let draw = model
            .control
            .as_ref()
            .and_then(|m| m.descent_draw(&sample))
            .expect("a descent");
        let case = format!("sample {}", row.sample.index);
        // The start puts the lowest footpad (along the slope's normal n) the clearance
        // above the surface, then raises the lander by the start altitude along Z_I: its
        // height above the plane is clearance + altitude n_z.
        let surface = Surface::of(&sample);
        let start = initial_state(&model, &surface, &sample);
        let n = surface.normal;
        let footpad = (model
            .legs
            .iter()
            .map(|l| n.dot(start.body.position_m + start.body.attitude * l.tip_m))
            .fold(f64::INFINITY, f64::min)
            - s.initial.clearance_m)
            / n.z;
        table.close(
            &case,
            "start footpad height (m)",
            footpad,
            draw.start_altitude_m,
            1e-12,
        );
        table.equal(
            &case,
            "braking on the grid (m/s^2)",
            draw.braking_m_s2,
            [0.005, 0.01][(row.sample.index % 2) as usize],
        );
        let row_draw = row
            .summary
            .control
            .as_ref()
            .and_then(|c| c.descent)
            .expect("the row's descent");
        table.equal(&case, "the row's draw", row_draw, draw);
        altitudes.push(draw.start_altitude_m);
    }
    let (lo, hi) = altitudes
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(lo, hi), &a| {
            (lo.min(a), hi.max(a))
        });
    table.equal(
        "16 samples",
        "start altitudes within 12-18 m and not all one",
        lo >= 12.0 && hi <= 18.0 && hi - lo > 1.0,
        true,
    );
    table.finish();
}
