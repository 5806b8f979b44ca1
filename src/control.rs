//! The control loop (MODEL.md section 7): sensors with noise and bias, a latency of whole
//! control periods, the built-in laws, the mapping of a commanded force and torque onto
//! the thrusters, and the thrust each lander gets until its next control event.
//!
//! The loop runs between steps, once per event of a lander (a control instant, or a
//! thruster switching off), for the kernels' lanes and the scalar reference alike: both
//! call `LaneControl::event` with the lander's true state and apply the thrust it returns
//! until the next event. The step never passes an event, so a thrust is constant over
//! every step it acts in.

use crate::reference::model::Surface;
use crate::reference::step::Thrust;
use crate::sampling::{Sample, normal_quantile, quantile, stream, uniform_open01};
use crate::scenario::{Control, Dist, G0_M_S2, Scenario, ScenarioError, Target, Thruster};
use glam::{DQuat, DVec3};
use rand_xoshiro::Xoshiro256PlusPlus;

/// The wrench a law asks for over one control period: a force and a torque about the CG,
/// both in B, as means over the period.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Wrench {
    pub force_b_n: DVec3,
    pub torque_b_n_m: DVec3,
}

impl Wrench {
    fn axes(&self) -> [f64; 6] {
        let (f, m) = (self.force_b_n, self.torque_b_n_m);
        [f.x, f.y, f.z, m.x, m.y, m.z]
    }
}

/// How a commanded wrench is shared among the thrusters: for each of the twelve signed
/// wrench axes (force along +-X_B, +-Y_B, +-Z_B, torque about them), the thrusters' duty
/// (fraction of a period at full thrust) that gives one unit of that wrench alone (1 N, or
/// 1 N m) and nothing else, or `None` where the cluster cannot give it pure. Found once,
/// from the nominal thrusters, by non-negative least squares.
#[derive(Debug, Clone, PartialEq)]
pub struct Allocation {
    /// `[axis * 2 + (0 for +, 1 for -)]`.
    pub unit: [Option<Vec<f64>>; 12],
}

/// How far from the asked-for axis an allocation may land, relative to the unit it gives,
/// and still count as pure: the least-squares solution of a cluster that can give the
/// wrench pure misses by the ridge's shrinkage (about 1e-9); one that cannot misses by a
/// sizeable fraction of it.
const PURE_TOLERANCE: f64 = 1e-6;

impl Allocation {
    /// The allocation of `thrusters` (nominal force directions and thrusts).
    #[must_use]
    pub fn new(thrusters: &[Thruster]) -> Allocation {
        let columns: Vec<[f64; 6]> = thrusters
            .iter()
            .map(|t| {
                let d = DVec3::from_array(t.direction) * t.max_thrust_n;
                let m = DVec3::from_array(t.position_m).cross(d);
                [d.x, d.y, d.z, m.x, m.y, m.z]
            })
            .collect();
        let unit = std::array::from_fn(|k| {
            let mut target = [0.0; 6];
            target[k / 2] = if k % 2 == 0 { 1.0 } else { -1.0 };
            let duty = nnls(&columns, target);
            let mut miss: f64 = 0.0;
            for (axis, want) in target.iter().enumerate() {
                let got: f64 = columns.iter().zip(&duty).map(|(c, u)| c[axis] * u).sum();
                miss = miss.max((got - want).abs());
            }
            (miss < PURE_TOLERANCE && duty.iter().any(|&u| u > 0.0)).then_some(duty)
        });
        Allocation { unit }
    }

    /// Whether the cluster can give the signed wrench axis `k` (as `unit`) pure.
    #[must_use]
    pub fn can(&self, k: usize) -> bool {
        self.unit[k].is_some()
    }

    /// The duty of every thruster for `wrench` (into `duty`): the torque first, scaled
    /// down as a whole where it alone would need a thruster for longer than the period,
    /// then as much of the force as the thrusters have left, scaled as a whole. Axes the
    /// cluster cannot give pure get nothing.
    pub fn duties(&self, wrench: &Wrench, duty: &mut [f64]) {
        let w = wrench.axes();
        let share = |axes: std::ops::Range<usize>, out: &mut [f64]| {
            out.fill(0.0);
            for axis in axes {
                let k = axis * 2 + usize::from(w[axis] < 0.0);
                if let Some(unit) = &self.unit[k] {
                    for (o, u) in out.iter_mut().zip(unit) {
                        *o += w[axis].abs() * u;
                    }
                }
            }
        };
        let n = duty.len();
        let mut torque = [0.0; crate::scenario::MAX_THRUSTERS];
        let mut force = [0.0; crate::scenario::MAX_THRUSTERS];
        share(3..6, &mut torque[..n]);
        share(0..3, &mut force[..n]);
        let most = torque[..n].iter().copied().fold(0.0, f64::max);
        if most > 1.0 {
            torque[..n].iter_mut().for_each(|t| *t /= most);
        }
        let mut scale: f64 = 1.0;
        for (t, f) in torque[..n].iter().zip(&force[..n]) {
            if *f > 0.0 {
                scale = scale.min((1.0 - t).max(0.0) / f);
            }
        }
        for ((d, t), f) in duty.iter_mut().zip(&torque[..n]).zip(&force[..n]) {
            *d = t + scale * f;
        }
    }
}

/// Non-negative least squares, `min |A u - target|^2 + ridge |u|^2` over `u >= 0` (`A`
/// given by its columns), by Lawson and Hanson's active-set method (exact, in finitely
/// many steps). The ridge, `1e-9` of the largest column's squared length, makes the
/// minimiser unique and picks, among exact solutions, the one of least `|u|`: the thrust
/// spread most evenly (a symmetric cluster fires symmetrically). It shrinks the solution
/// by about that fraction, far below `PURE_TOLERANCE`. Small sizes (at most
/// `MAX_THRUSTERS` columns, six rows), once per sweep.
fn nnls(columns: &[[f64; 6]], target: [f64; 6]) -> Vec<f64> {
    let n = columns.len();
    let scale = columns
        .iter()
        .map(|c| c.iter().map(|x| x * x).sum::<f64>())
        .fold(0.0, f64::max);
    let ridge = 1e-9 * scale.max(f64::MIN_POSITIVE);
    // Normal equations of the ridge problem: G = A^T A + ridge I, b = A^T target.
    let dot = |a: &[f64; 6], b: &[f64; 6]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let g: Vec<Vec<f64>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| dot(&columns[i], &columns[j]) + if i == j { ridge } else { 0.0 })
                .collect()
        })
        .collect();
    let b: Vec<f64> = columns.iter().map(|c| dot(c, &target)).collect();
    // The gradient's negative, b - G u.
    let descent = |u: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|i| b[i] - (0..n).map(|j| g[i][j] * u[j]).sum::<f64>())
            .collect()
    };
    // Unconstrained minimiser over the free set, zero elsewhere.
    let solve = |free: &[bool]| -> Vec<f64> {
        let idx: Vec<usize> = (0..n).filter(|&i| free[i]).collect();
        let k = idx.len();
        let mut m: Vec<Vec<f64>> = idx
            .iter()
            .map(|&i| {
                let mut row: Vec<f64> = idx.iter().map(|&j| g[i][j]).collect();
                row.push(b[i]);
                row
            })
            .collect();
        for col in 0..k {
            let pivot = (col..k)
                .max_by(|&x, &y| m[x][col].abs().total_cmp(&m[y][col].abs()))
                .unwrap_or(col);
            m.swap(col, pivot);
            let (top, rest) = m.split_at_mut(col + 1);
            let pivot_row = &top[col];
            for row in rest.iter_mut() {
                let f = row[col] / pivot_row[col];
                for (x, p) in row[col..].iter_mut().zip(&pivot_row[col..]) {
                    *x -= f * p;
                }
            }
        }
        let mut z = vec![0.0; k];
        for r in (0..k).rev() {
            let sum: f64 = (r + 1..k).map(|c| m[r][c] * z[c]).sum();
            z[r] = (m[r][k] - sum) / m[r][r];
        }
        let mut out = vec![0.0; n];
        for (&i, v) in idx.iter().zip(z) {
            out[i] = v;
        }
        out
    };
    let mut u = vec![0.0; n];
    let mut free = vec![false; n];
    let tolerance = 1e-12 * b.iter().fold(0.0f64, |a, x| a.max(x.abs())).max(1e-300);
    for _ in 0..(3 * n + 10) {
        let w = descent(&u);
        let Some(t) = (0..n)
            .filter(|&j| !free[j] && w[j] > tolerance)
            .max_by(|&x, &y| w[x].total_cmp(&w[y]))
        else {
            break;
        };
        free[t] = true;
        loop {
            let z = solve(&free);
            if (0..n).filter(|&j| free[j]).all(|j| z[j] > 0.0) {
                u = z;
                break;
            }
            let alpha = (0..n)
                .filter(|&j| free[j] && z[j] <= 0.0)
                .map(|j| u[j] / (u[j] - z[j]))
                .fold(f64::INFINITY, f64::min);
            for j in 0..n {
                u[j] += alpha * (z[j] - u[j]);
                if free[j] && u[j] <= 1e-15 {
                    free[j] = false;
                    u[j] = 0.0;
                }
            }
        }
    }
    u
}

/// Numbers a law keeps per lander from one control instant to the next (`Law::command`).
pub const LAW_MEMORY: usize = 8;

/// What a law commands for one lander over the next control period.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LawCommand {
    /// The force and torque (B) to give, as means over the period: the control loop shares
    /// them among the thrusters (`Allocation`) and quantises the on-times.
    pub wrench: Wrench,
    /// The law will command nothing more for this lander: once its last firing is over the
    /// lander is left to itself (its rest clock and the early rules count again).
    pub done: bool,
}

/// A control law of the user's own, named by a scenario (`[control] law = "NAME"`) and
/// registered under that name (`register_law`) by a program that embeds touchdown.
///
/// At every control instant the loop reads the sensors (with their noise, bias and
/// latency as the scenario gives them) and asks the law for a command. The landers of a
/// block that reach a control instant together are handed over at once, as slices of the
/// same length: `sensed[i]` is what lander `i`'s sensors read, `memory[i]` what the law
/// kept for that lander (zero at the start of its sample), and the law writes its command
/// into `command[i]` (zero when it is called). The law commands in every phase until it
/// says `done`; contact shows in `Sensed::contact` (the touchdown switches). Called from
/// the sweep's worker threads: it must not depend on the order or grouping of landers, or
/// a sweep would not give the same file for every thread count.
pub trait Law: Send + Sync {
    /// Commands for the landers of `sensed`.
    fn command(
        &self,
        sensed: &[Sensed],
        memory: &mut [[f64; LAW_MEMORY]],
        command: &mut [LawCommand],
    );
}

/// A registered law and its name.
#[derive(Clone)]
pub struct NamedLaw {
    pub name: String,
    pub law: std::sync::Arc<dyn Law>,
}

impl std::fmt::Debug for NamedLaw {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "law {:?}", self.name)
    }
}

static LAWS: std::sync::Mutex<Vec<(String, std::sync::Arc<dyn Law>)>> =
    std::sync::Mutex::new(Vec::new());

/// Registers `law` under `name` for scenarios to name (`[control] law = "NAME"`): a
/// program that embeds touchdown calls this before `cli::main` (see
/// `examples/user_law.rs`). A later registration under the same name replaces it.
pub fn register_law(name: &str, law: impl Law + 'static) {
    let mut laws = LAWS
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    laws.retain(|(n, _)| n != name);
    laws.push((name.to_string(), std::sync::Arc::new(law)));
}

/// The law registered under `name`.
#[must_use]
pub fn registered(name: &str) -> Option<NamedLaw> {
    let laws = LAWS
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    laws.iter().find(|(n, _)| n == name).map(|(n, l)| NamedLaw {
        name: n.clone(),
        law: l.clone(),
    })
}

/// What stays fixed over a sweep: the control loop of the scenario, the thrusters as
/// designed, and what the step-size bound needs.
#[derive(Debug, Clone)]
pub struct ControlModel {
    pub config: Control,
    /// The user's law the scenario names (`[control] law`), if any.
    pub law: Option<NamedLaw>,
    pub thrusters: Vec<Thruster>,
    pub allocation: Allocation,
    pub period_s: f64,
    /// `isp g0`, m/s: propellant used is the thrust's integral over it.
    pub exhaust_speed_m_s: f64,
    pub thrust_error_sd: f64,
    pub misalignment_sd_rad: f64,
    pub mass_kg: f64,
    pub gravity_m_s2: f64,
    /// Depth of the lowest footpad below the CG along `-Z_B`, m: the descent law takes the
    /// footpads' height as the altimeter's CG altitude less this.
    pub footpad_depth_m: f64,
    pub inertia_min_kg_m2: f64,
    pub leg_reach_m: f64,
    pub flight_step_max_s: f64,
    pub rest_speed_m_s: f64,
    pub rest_rate_rad_s: f64,
    pub hold_time_s: f64,
}

impl ControlModel {
    /// The control loop of a validated scenario, if it has one.
    #[must_use]
    pub fn of(s: &Scenario, leg_reach_m: f64, footpad_depth_m: f64) -> Option<ControlModel> {
        let config = s.control.clone()?;
        Some(ControlModel {
            law: config.law.as_deref().and_then(registered),
            period_s: 1.0 / config.rate_hz,
            config,
            thrusters: s.thrusters.clone(),
            allocation: Allocation::new(&s.thrusters),
            exhaust_speed_m_s: s.propulsion.isp_s * G0_M_S2,
            thrust_error_sd: s.propulsion.thrust_error_sd,
            misalignment_sd_rad: s.propulsion.misalignment_sd_deg.to_radians(),
            mass_kg: s.lander.mass_kg,
            gravity_m_s2: s.gravity_m_s2,
            footpad_depth_m,
            inertia_min_kg_m2: s
                .lander
                .inertia_kg_m2
                .iter()
                .copied()
                .fold(f64::INFINITY, f64::min),
            leg_reach_m,
            flight_step_max_s: s.simulation.flight_step_max_s,
            rest_speed_m_s: s.outcome.rest_speed_m_s,
            rest_rate_rad_s: s.outcome.rest_rate_deg_s.to_radians(),
            hold_time_s: s.outcome.hold_time_s,
        })
    }
}

/// A sample's descent (`[control.descent]`): its parameters as drawn.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DescentDraw {
    pub start_altitude_m: f64,
    pub start_speed_m_s: f64,
    pub braking_m_s2: f64,
    pub gain_per_s: f64,
    pub release_speed_m_s: f64,
}

impl ControlModel {
    /// The descent of `sample`, if the loop has one: each parameter drawn from a stream of
    /// its own (at the sample's grid point for a grid). The initial state (a descent's
    /// start) and the loop both take it from here.
    #[must_use]
    pub fn descent_draw(&self, sample: &Sample) -> Option<DescentDraw> {
        let d = self.config.descent.as_ref()?;
        let g = crate::sampling::law_grid(&self.config, sample.law_cell);
        let seed = sample.seed;
        Some(DescentDraw {
            start_altitude_m: draw(&d.start_altitude_m, seed, "descent_start_altitude_m", g[4]),
            start_speed_m_s: draw(&d.start_speed_m_s, seed, "descent_start_speed_m_s", g[5]),
            braking_m_s2: draw(&d.braking_m_s2, seed, "descent_braking_m_s2", g[6]),
            gain_per_s: draw(&d.gain_per_s, seed, "descent_gain_per_s", g[7]),
            release_speed_m_s: draw(
                &d.release_speed_m_s,
                seed,
                "descent_release_speed_m_s",
                g[8],
            ),
        })
    }
}

/// Refuses a control loop that cannot work: one without thrusters or without a law, a
/// hold-down the thrusters cannot push pure along `-Z_B` (or not as hard as asked), an
/// attitude hold they cannot turn about `X_B` and `Y_B`, a descent they cannot brake, or a
/// descent start without a descent law (and the other way round).
pub fn check(s: &Scenario) -> Result<(), ScenarioError> {
    let invalid = |key: &str, value: String, allowed: String| ScenarioError::Invalid {
        key: key.to_string(),
        value,
        allowed,
    };
    let descent = s.control.as_ref().and_then(|c| c.descent);
    let descent_start = s.initial.start == crate::scenario::Start::Descent;
    if descent_start && descent.is_none() {
        return Err(invalid(
            "initial.start",
            "\"descent\"".into(),
            "\"touchdown\" or \"release\", unless [control.descent] gives the descent and \
             its law (with [[thrusters]] to brake it)"
                .into(),
        ));
    }
    if descent.is_some() && !descent_start {
        return Err(invalid(
            "control.descent",
            "a descent law".into(),
            "initial.start = \"descent\" with it: the law brakes a descent that the sample \
             starts in"
                .into(),
        ));
    }
    let Some(c) = &s.control else {
        return Ok(());
    };
    if s.thrusters.is_empty() {
        return Err(invalid(
            "control",
            "a control loop".into(),
            "[[thrusters]] for it to fire: a control loop without thrusters does nothing".into(),
        ));
    }
    if let Some(name) = &c.law {
        if c.hold_down.is_some() || c.attitude_hold.is_some() || c.descent.is_some() {
            return Err(invalid(
                "control.law",
                format!("{name:?}"),
                "either a law of your own or the built-in laws ([control.hold_down], \
                 [control.attitude_hold], [control.descent]), not both: your law commands \
                 in every phase"
                    .into(),
            ));
        }
        if registered(name).is_none() {
            let laws = LAWS
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner);
            let known: Vec<String> = laws.iter().map(|(n, _)| format!("{n:?}")).collect();
            return Err(invalid(
                "control.law",
                format!("{name:?}"),
                if known.is_empty() {
                    "the name of a law registered by the program running the sweep; this \
                     program registers none (the `touchdown` binary has only the built-in \
                     laws: a program that embeds touchdown registers its own, see \
                     examples/user_law.rs)"
                        .into()
                } else {
                    format!(
                        "one of the laws this program registers: {}",
                        known.join(", ")
                    )
                },
            ));
        }
    } else if c.hold_down.is_none() && c.attitude_hold.is_none() && c.descent.is_none() {
        return Err(invalid(
            "control",
            "no law".into(),
            "a law for the loop to run: [control.hold_down], [control.attitude_hold], \
             [control.descent] or law = \"NAME\" (one of your own)"
                .into(),
        ));
    }
    let allocation = Allocation::new(&s.thrusters);
    if let Some(d) = &c.descent {
        // Braking at `braking_m_s2` against gravity, upright: along +Z_B, pure.
        let braking = d.braking_m_s2.support().1;
        let need = s.lander.mass_kg * (s.gravity_m_s2 + braking);
        let capacity = allocation.unit[4]
            .as_ref()
            .map_or(0.0, |u| 1.0 / u.iter().copied().fold(0.0, f64::max));
        if capacity < need {
            return Err(invalid(
                "control.descent.braking_m_s2",
                format!("up to {braking}"),
                format!(
                    "a braking the thrusters can give: against gravity it needs mass_kg \
                     (gravity_m_s2 + braking_m_s2) = {need:.4} N along +Z_B through the CG, \
                     and they give at most {capacity:.4} N so (thrusters pushing along +Z_B, \
                     placed symmetrically about the CG)"
                ),
            ));
        }
    }
    if let Some(h) = &c.hold_down {
        let most = h.thrust_n.support().1;
        if most > 0.0 {
            let Some(unit) = &allocation.unit[5] else {
                return Err(invalid(
                    "control.hold_down",
                    "[[thrusters]]".into(),
                    "thrusters that together push along -Z_B through the CG with no torque \
                     (for example, several pushing along -Z_B placed symmetrically about \
                     the CG)"
                        .into(),
                ));
            };
            // The unit allocation is shrunk by the ridge of `nnls` (about 1e-9 of it), so
            // the capacity it implies is that much short: the full thrust of the cluster is
            // allowed within `PURE_TOLERANCE`.
            let capacity = 1.0 / unit.iter().copied().fold(0.0, f64::max);
            if most > capacity * (1.0 + PURE_TOLERANCE) {
                return Err(invalid(
                    "control.hold_down.thrust_n",
                    format!("up to {most} N"),
                    format!(
                        "at most {capacity:.4} N: the most the thrusters give along -Z_B \
                         through the CG with no torque"
                    ),
                ));
            }
        }
    }
    if c.attitude_hold.is_some() && !(6..10).all(|k| allocation.can(k)) {
        return Err(invalid(
            "control.attitude_hold",
            "[[thrusters]]".into(),
            "thrusters that give a pure torque both ways about X_B and Y_B (couples: pairs \
             of opposite forces on either side of the CG)"
                .into(),
        ));
    }
    Ok(())
}

/// The true state of a lander at a control event, which the sensors read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Truth {
    pub t_s: f64,
    pub position_m: DVec3,
    pub velocity_m_s: DVec3,
    pub attitude: DQuat,
    pub rate_rad_s: DVec3,
    /// Whether a footpad touched the surface in the last step (the touchdown switches).
    pub contact: bool,
    /// The surface normal.
    pub normal: DVec3,
}

/// What the sensors report at a control instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sensed {
    /// Time of the control instant, s: `k` periods at the `k`-th instant (the flight
    /// computer's clock).
    pub t_s: f64,
    /// Attitude, B to I.
    pub attitude: DQuat,
    /// Body rates in B, rad/s.
    pub rate_rad_s: DVec3,
    /// CG velocity in I, m/s.
    pub velocity_m_s: DVec3,
    /// CG height above the surface plane along its normal, m.
    pub altitude_m: f64,
    /// A touchdown switch closed.
    pub contact: bool,
}

/// The phase of a lander's control loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Phase {
    /// From a descent start until the descent law releases the lander (or contact is
    /// sensed first): braking, and attitude hold if any.
    Descent,
    /// Before contact is sensed: attitude hold, if any.
    Fall,
    /// Hold-down since the instant at `since_s`, at rest (sensed) for `rest_s`.
    HoldDown { since_s: f64, rest_s: f64 },
    /// The user's law commands (until it says it is done).
    User,
    /// Nothing more to fire.
    Done,
}

/// A command: every thruster's on-time in its period, and whether hold-down asked for it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Command {
    on_s: [f64; crate::scenario::MAX_THRUSTERS],
    hold_down: bool,
}

const IDLE: Command = Command {
    on_s: [0.0; crate::scenario::MAX_THRUSTERS],
    hold_down: false,
};

/// What a lander's control loop did, for its row of the sweep.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ControlSummary {
    /// Propellant used: the thrust's integral over `isp g0`, kg.
    pub propellant_kg: f64,
    /// Sum of every thruster's time on, s.
    pub on_time_s: f64,
    /// Firings: a thruster on in a control period counts once.
    pub firings: u32,
    /// Integral of the thrust magnitude of the thrusters fired by `hold_down`, N s.
    pub hold_down_impulse_n_s: f64,
    /// The sample's drawn law parameters (NaN where the scenario has no such law).
    pub hold_down_thrust_n: f64,
    pub hold_down_duration_s: f64,
    pub kp_n_m_per_rad: f64,
    pub kd_n_m_s_per_rad: f64,
    /// When the descent law released the lander, s, and its true state then: the height
    /// of its footpads (the true CG altitude above the surface plane less the footpads'
    /// depth below the CG) and its CG velocity in I (NaN: never released, or no descent).
    pub release_time_s: f64,
    pub release_altitude_m: f64,
    pub release_velocity_m_s: [f64; 3],
    /// The sample's drawn descent (none without one).
    pub descent: Option<DescentDraw>,
}

/// One lander's control loop: its sampled thruster errors, sensor biases and law
/// parameters, its noise generator, and where it stands in its period.
#[derive(Debug, Clone)]
pub struct LaneControl {
    /// Each thruster's force on the lander as built (errors included), B, N.
    force_b_n: Vec<DVec3>,
    /// Its moment about the CG, B, N m.
    moment_b_n_m: Vec<DVec3>,
    noise: Xoshiro256PlusPlus,
    attitude_bias_rad: DVec3,
    rate_bias_rad_s: DVec3,
    velocity_bias_m_s: DVec3,
    altitude_bias_m: f64,
    phase: Phase,
    /// Commands issued and not yet applied, oldest first (`latency_periods` of them).
    queue: Vec<Command>,
    /// The command of the current period.
    current: Command,
    /// Time left in the current period, s.
    period_left_s: f64,
    /// Time each thruster still fires in it, s.
    on_left_s: [f64; crate::scenario::MAX_THRUSTERS],
    /// The length of the segment under way (from the last event to the next), s.
    segment_s: f64,
    /// Thrust magnitude summed over the thrusters firing in it, N.
    flow_n: f64,
    firing: u32,
    powered: bool,
    /// Thrust integral so far, N s.
    impulse_n_s: f64,
    /// What the sensors read at the last control instant.
    last_sensed: Option<Sensed>,
    /// The sample's release height, m: where the descent law releases the lander.
    release_height_m: f64,
    /// Whether the event under way is a control instant (`begin` to `end`).
    instant_due: bool,
    /// Control instants so far.
    instants: u64,
    /// The user's law's memory for this lander.
    memory: [f64; LAW_MEMORY],
    /// Which thrusters fire in the segment under way.
    firing_now: [bool; crate::scenario::MAX_THRUSTERS],
    pub summary: ControlSummary,
}

/// What a lander's control loop is doing during one step, for traces.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ControlReport {
    /// What the sensors read at the last control instant (`None` before the first).
    pub sensed: Option<Sensed>,
    /// The on-time of every thruster in the current period, s.
    pub commanded_on_s: Vec<f64>,
    /// The thrust of every thruster during the step (as built: errors included), N.
    pub thrust_n: Vec<f64>,
    /// The phase of the loop: "descent", "fall", "hold_down", "user" or "done".
    pub phase: &'static str,
}

/// A normal draw with standard deviation `sd` (0 draws nothing).
fn normal(rng: &mut Xoshiro256PlusPlus, sd: f64) -> f64 {
    if sd > 0.0 {
        sd * normal_quantile(uniform_open01(rng))
    } else {
        0.0
    }
}

fn normal3(rng: &mut Xoshiro256PlusPlus, sd: f64) -> DVec3 {
    DVec3::new(normal(rng, sd), normal(rng, sd), normal(rng, sd))
}

/// A draw of `dist` for the sample with generator seed `seed` (its own stream, `name`), at
/// `grid_index` where `dist` is a grid.
fn draw(dist: &Dist, seed: u64, name: &str, grid_index: u64) -> f64 {
    quantile(dist, uniform_open01(&mut stream(seed, name)), grid_index)
}

/// A normal draw truncated at three standard deviations (0 for `sd` 0).
fn truncated(rng: &mut Xoshiro256PlusPlus, sd: f64) -> f64 {
    if sd > 0.0 {
        let d = Dist::Normal {
            mean: 0.0,
            sd,
            min: -3.0 * sd,
            max: 3.0 * sd,
        };
        quantile(&d, uniform_open01(rng), 0)
    } else {
        0.0
    }
}

/// The unit quaternion of a small rotation vector `v` (rad), without trigonometry:
/// `(v / 2, 1)` normalised, within `|v|^3 / 48` of the exact rotation.
fn small_rotation(v: DVec3) -> DQuat {
    let h = v * 0.5;
    DQuat::from_xyzw(h.x, h.y, h.z, 1.0).normalize()
}

/// Below this, what is left of a period or an on-time is the rounding of differences of
/// the same times, not time, s.
const TIME_DUST_S: f64 = 1e-12;

impl LaneControl {
    /// The control loop of `sample`: its thruster errors, sensor biases and law parameters
    /// drawn from streams of its own (law parameters on a grid at the sample's point of it).
    #[must_use]
    pub fn new(m: &ControlModel, sample: &Sample) -> LaneControl {
        let seed = sample.seed;
        let g = crate::sampling::law_grid(&m.config, sample.law_cell);
        let mut errors = stream(seed, "thrusters");
        let (mut force_b_n, mut moment_b_n_m) = (Vec::new(), Vec::new());
        for t in &m.thrusters {
            let magnitude = t.max_thrust_n * (1.0 + truncated(&mut errors, m.thrust_error_sd));
            let d = DVec3::from_array(t.direction);
            let (a, b) = d.any_orthonormal_pair();
            let tilt = a * truncated(&mut errors, m.misalignment_sd_rad)
                + b * truncated(&mut errors, m.misalignment_sd_rad);
            let f = (small_rotation(tilt) * d) * magnitude;
            force_b_n.push(f);
            moment_b_n_m.push(DVec3::from_array(t.position_m).cross(f));
        }
        let s = &m.config.sensors;
        let mut bias = stream(seed, "sensor_bias");
        let attitude_bias_rad = normal3(&mut bias, s.attitude_bias_deg.to_radians());
        let rate_bias_rad_s = normal3(&mut bias, s.rate_bias_deg_s.to_radians());
        let velocity_bias_m_s = normal3(&mut bias, s.velocity_bias_m_s);
        let altitude_bias_m = normal(&mut bias, s.altitude_bias_m);
        let nan = f64::NAN;
        let (hold_down_thrust_n, hold_down_duration_s) =
            m.config.hold_down.map_or((nan, nan), |h| {
                (
                    draw(&h.thrust_n, seed, "hold_down_thrust_n", g[0]),
                    draw(&h.duration_s, seed, "hold_down_duration_s", g[1]),
                )
            });
        let (kp_n_m_per_rad, kd_n_m_s_per_rad) = m.config.attitude_hold.map_or((nan, nan), |a| {
            (
                draw(&a.kp_n_m_per_rad, seed, "kp_n_m_per_rad", g[2]),
                draw(&a.kd_n_m_s_per_rad, seed, "kd_n_m_s_per_rad", g[3]),
            )
        });
        LaneControl {
            force_b_n,
            moment_b_n_m,
            noise: stream(seed, "sensor_noise"),
            attitude_bias_rad,
            rate_bias_rad_s,
            velocity_bias_m_s,
            altitude_bias_m,
            phase: if m.law.is_some() {
                Phase::User
            } else if m.config.descent.is_some() {
                Phase::Descent
            } else {
                Phase::Fall
            },
            queue: Vec::with_capacity(m.config.latency_periods as usize + 1),
            current: IDLE,
            period_left_s: 0.0,
            on_left_s: [0.0; crate::scenario::MAX_THRUSTERS],
            segment_s: 0.0,
            flow_n: 0.0,
            firing: 0,
            powered: true,
            impulse_n_s: 0.0,
            last_sensed: None,
            release_height_m: sample.inputs.release_height_m,
            instant_due: false,
            instants: 0,
            memory: [0.0; LAW_MEMORY],
            firing_now: [false; crate::scenario::MAX_THRUSTERS],
            summary: ControlSummary {
                hold_down_thrust_n,
                hold_down_duration_s,
                kp_n_m_per_rad,
                kd_n_m_s_per_rad,
                release_time_s: nan,
                release_altitude_m: nan,
                release_velocity_m_s: [nan; 3],
                descent: m.descent_draw(sample),
                ..ControlSummary::default()
            },
        }
    }

    /// The phase the loop is in.
    #[must_use]
    pub fn phase(&self) -> Phase {
        self.phase
    }

    /// What the loop is doing in the segment under way, into `out` (for traces).
    pub fn report(&self, m: &ControlModel, out: &mut ControlReport) {
        let n = m.thrusters.len();
        out.sensed = self.last_sensed;
        out.commanded_on_s.clear();
        out.commanded_on_s
            .extend_from_slice(&self.current.on_s[..n]);
        out.thrust_n.clear();
        out.thrust_n.extend((0..n).map(|j| {
            if self.powered && self.firing_now[j] {
                self.force_b_n[j].length()
            } else {
                0.0
            }
        }));
        out.phase = match self.phase {
            Phase::Descent => "descent",
            Phase::Fall => "fall",
            Phase::HoldDown { .. } => "hold_down",
            Phase::User => "user",
            Phase::Done => "done",
        };
    }

    /// Takes in the event that ended the segment under way (or starts the loop: the first
    /// call, at `t = 0`) and returns the thrust until the next event: `begin`, the user's
    /// law for this lander alone where `begin` asks for it, and `end`.
    pub fn event(&mut self, m: &ControlModel, truth: &Truth) -> Thrust {
        let mut command = LawCommand::default();
        let asked = self.begin(m, truth).map(|sensed| {
            if let Some(law) = &m.law {
                law.law.command(
                    std::slice::from_ref(&sensed),
                    std::slice::from_mut(&mut self.memory),
                    std::slice::from_mut(&mut command),
                );
            }
        });
        self.end(m, truth, asked.map(|()| &command))
    }

    /// The first half of `event`: accounts for the segment that ended and, at a control
    /// instant, reads the sensors. Returns the reading where the user's law must command
    /// (`Law::command`, with `memory()`), for `end` to take its command.
    pub fn begin(&mut self, m: &ControlModel, truth: &Truth) -> Option<Sensed> {
        self.instant_due = false;
        if !self.powered {
            return None;
        }
        let elapsed = self.segment_s;
        self.spend(elapsed);
        self.period_left_s -= elapsed;
        let n = m.thrusters.len();
        for on in &mut self.on_left_s[..n] {
            *on -= elapsed.min(*on);
            if *on < TIME_DUST_S {
                *on = 0.0;
            }
        }
        if self.period_left_s >= TIME_DUST_S {
            return None;
        }
        self.instant_due = true;
        let sensed = self.sense(m, truth);
        self.last_sensed = Some(sensed);
        (m.law.is_some() && self.phase == Phase::User).then_some(sensed)
    }

    /// This lander's memory for the user's law (zero at the start of its sample).
    pub fn memory(&mut self) -> &mut [f64; LAW_MEMORY] {
        &mut self.memory
    }

    /// The second half of `event`: at a control instant, the command (the user's law's,
    /// `user`, where `begin` asked for one), and the thrust until the next event.
    pub fn end(&mut self, m: &ControlModel, truth: &Truth, user: Option<&LawCommand>) -> Thrust {
        if !self.powered {
            return Thrust::NONE;
        }
        let n = m.thrusters.len();
        if self.instant_due {
            self.instant(m, truth, user);
        }
        let mut segment = self.period_left_s;
        let (mut force, mut moment, mut flow, mut firing) = (DVec3::ZERO, DVec3::ZERO, 0.0, 0);
        for j in 0..n {
            let on = self.on_left_s[j];
            self.firing_now[j] = on > 0.0;
            if on > 0.0 {
                segment = segment.min(on);
                force += self.force_b_n[j];
                moment += self.moment_b_n_m[j];
                flow += self.force_b_n[j].length();
                firing += 1;
            }
        }
        self.flow_n = flow;
        self.firing = firing;
        let idle = firing == 0
            && self.phase == Phase::Done
            && self
                .queue
                .iter()
                .all(|c| c.on_s[..n].iter().all(|&t| t == 0.0));
        if idle {
            self.powered = false;
            self.segment_s = 0.0;
            return Thrust::NONE;
        }
        self.segment_s = segment;
        Thrust {
            force_b_n: force,
            moment_b_n_m: moment,
            event_in_s: segment,
            approach_m_s: (force.length() / m.mass_kg
                + moment.length() / m.inertia_min_kg_m2 * m.leg_reach_m)
                * m.flight_step_max_s,
            powered: true,
            flow_n: flow,
        }
    }

    /// Accounts for `elapsed` of the segment under way.
    fn spend(&mut self, elapsed: f64) {
        let impulse = self.flow_n * elapsed;
        self.impulse_n_s += impulse;
        self.summary.on_time_s += f64::from(self.firing) * elapsed;
        if self.current.hold_down {
            self.summary.hold_down_impulse_n_s += impulse;
        }
    }

    /// Closes the books at the decision, `event_in_s` before the event the segment under
    /// way was heading for; returns the summary, propellant in kg.
    #[must_use]
    pub fn finish(&mut self, m: &ControlModel, event_in_s: f64) -> ControlSummary {
        if self.powered {
            let elapsed = (self.segment_s - event_in_s).clamp(0.0, self.segment_s);
            self.spend(elapsed);
        }
        let mut s = self.summary;
        s.propellant_kg = self.impulse_n_s / m.exhaust_speed_m_s;
        s
    }

    /// A control instant: read the sensors, advance the phase, issue a command, and start
    /// the period of the command whose latency has passed.
    fn instant(&mut self, m: &ControlModel, truth: &Truth, user: Option<&LawCommand>) {
        let c = &m.config;
        let sensed = self.last_sensed.expect("begin read the sensors");
        let t = sensed.t_s;
        if self.phase == Phase::Descent && !sensed.contact {
            let d = self.summary.descent.expect("a descent phase has its law");
            let height = sensed.altitude_m - m.footpad_depth_m;
            let approach = truth.normal.dot(sensed.velocity_m_s);
            if height <= self.release_height_m && approach.abs() < d.release_speed_m_s {
                self.phase = Phase::Fall;
                // The release ends the burn at once: its commands still in the latency
                // queue are dropped, so the free fall starts from the state recorded here.
                self.queue.clear();
                let s = &mut self.summary;
                s.release_time_s = truth.t_s;
                s.release_altitude_m = truth.normal.dot(truth.position_m) - m.footpad_depth_m;
                s.release_velocity_m_s = truth.velocity_m_s.to_array();
            }
        }
        if matches!(self.phase, Phase::Descent | Phase::Fall) && sensed.contact {
            let (thrust, duration) = (
                self.summary.hold_down_thrust_n,
                self.summary.hold_down_duration_s,
            );
            self.phase = if c.hold_down.is_some() && thrust > 0.0 && duration > 0.0 {
                Phase::HoldDown {
                    since_s: t,
                    rest_s: 0.0,
                }
            } else {
                Phase::Done
            };
        }
        if let Phase::HoldDown { since_s, rest_s } = self.phase {
            let at_rest = sensed.velocity_m_s.length() < m.rest_speed_m_s
                && sensed.rate_rad_s.length() < m.rest_rate_rad_s;
            let rest_s = if at_rest { rest_s + m.period_s } else { 0.0 };
            let until_rest = c.hold_down.is_some_and(|h| h.until_rest);
            // Periods are counted from the instant contact was sensed: `duration` asks for
            // that many periods' worth (the last one whole).
            let periods = (self.summary.hold_down_duration_s / m.period_s - 1e-9).ceil();
            let done_s = since_s + periods * m.period_s;
            self.phase = if t >= done_s - 0.5 * m.period_s
                || (until_rest && rest_s >= m.hold_time_s - 1e-9)
            {
                Phase::Done
            } else {
                Phase::HoldDown { since_s, rest_s }
            };
        }
        let (wrench, hold_down) = match self.phase {
            Phase::User => {
                let command = user.copied().unwrap_or_default();
                if command.done {
                    self.phase = Phase::Done;
                }
                (command.wrench, false)
            }
            Phase::Descent => (self.descent(m, &sensed, truth.normal), false),
            Phase::Fall => (self.attitude_hold(m, &sensed, truth.normal), false),
            Phase::HoldDown { .. } => (
                Wrench {
                    force_b_n: DVec3::new(0.0, 0.0, -self.summary.hold_down_thrust_n),
                    torque_b_n_m: DVec3::ZERO,
                },
                true,
            ),
            Phase::Done => (Wrench::default(), false),
        };
        let mut command = IDLE;
        command.hold_down = hold_down;
        let n = m.thrusters.len();
        if wrench != Wrench::default() {
            m.allocation.duties(&wrench, &mut command.on_s[..n]);
            for (on, t) in command.on_s[..n].iter_mut().zip(&m.thrusters) {
                *on = quantise(*on * m.period_s, t.min_on_time_s, m.period_s);
            }
        }
        self.queue.push(command);
        self.current = if self.queue.len() > c.latency_periods as usize {
            self.queue.remove(0)
        } else {
            IDLE
        };
        self.on_left_s[..n].copy_from_slice(&self.current.on_s[..n]);
        self.summary.firings += self.current.on_s[..n].iter().filter(|&&t| t > 0.0).count() as u32;
        self.period_left_s = m.period_s;
    }

    /// The sensors' reading of `truth`: bias and a fresh draw of noise on every quantity.
    fn sense(&mut self, m: &ControlModel, truth: &Truth) -> Sensed {
        let s = &m.config.sensors;
        let r = &mut self.noise;
        let attitude_error = self.attitude_bias_rad + normal3(r, s.attitude_noise_deg.to_radians());
        let rate =
            truth.rate_rad_s + self.rate_bias_rad_s + normal3(r, s.rate_noise_deg_s.to_radians());
        let velocity =
            truth.velocity_m_s + self.velocity_bias_m_s + normal3(r, s.velocity_noise_m_s);
        let altitude = truth.normal.dot(truth.position_m)
            + self.altitude_bias_m
            + normal(r, s.altitude_noise_m);
        // The flight computer's clock: instant k is at k periods, the same in every
        // precision (the true time of the step that reached it differs by roundings).
        let t_s = self.instants as f64 * m.period_s;
        self.instants += 1;
        Sensed {
            t_s,
            attitude: truth.attitude * small_rotation(attitude_error),
            rate_rad_s: rate,
            velocity_m_s: velocity,
            altitude_m: altitude,
            contact: truth.contact,
        }
    }

    /// The descent's wrench: `descent_force`, and `attitude_hold`'s torque if the loop has
    /// it.
    fn descent(&self, m: &ControlModel, sensed: &Sensed, normal: DVec3) -> Wrench {
        let d = self.summary.descent.expect("a descent phase has its law");
        Wrench {
            force_b_n: descent_force(
                &d,
                m.mass_kg,
                m.gravity_m_s2,
                sensed.altitude_m - m.footpad_depth_m,
                self.release_height_m,
                sensed,
                normal,
            ),
            ..self.attitude_hold(m, sensed, normal)
        }
    }

    /// `attitude_hold`'s wrench, with this sample's gains (`attitude_torque`).
    fn attitude_hold(&self, m: &ControlModel, sensed: &Sensed, normal: DVec3) -> Wrench {
        let Some(a) = &m.config.attitude_hold else {
            return Wrench::default();
        };
        let target = match a.target {
            Target::Vertical => DVec3::Z,
            Target::Normal => normal,
        };
        Wrench {
            force_b_n: DVec3::ZERO,
            torque_b_n_m: attitude_torque(
                self.summary.kp_n_m_per_rad,
                self.summary.kd_n_m_s_per_rad,
                a.deadband_deg.to_radians(),
                sensed.attitude,
                sensed.rate_rad_s,
                target,
            ),
        }
    }
}

/// The descent law's force on the lander (`[control.descent]`), in B: its mass times
/// `gain (h'_ref - h') n + g up`, where `h' = n . v` is the rate of the footpads' height
/// `height_m` along the surface normal `n` (`v` the sensed velocity) and `h'_ref` the
/// braking profile's, `-sqrt(2 braking (height - release))` above the release height
/// `release_height_m` and 0 at or below it; the sensed attitude turns it into B. Only the
/// approach along the normal is controlled: a velocity along the surface (the navigation
/// error) changes no height and is left as it is.
#[must_use]
pub fn descent_force(
    d: &DescentDraw,
    mass_kg: f64,
    gravity_m_s2: f64,
    height_m: f64,
    release_height_m: f64,
    sensed: &Sensed,
    normal: DVec3,
) -> DVec3 {
    let above = (height_m - release_height_m).max(0.0);
    let rate_ref = -(2.0 * d.braking_m_s2 * above).sqrt();
    let rate = normal.dot(sensed.velocity_m_s);
    let accel = normal * ((rate_ref - rate) * d.gain_per_s) + DVec3::Z * gravity_m_s2;
    sensed.attitude.inverse() * (accel * mass_kg)
}

/// The attitude-hold law (`[control.attitude_hold]`): torque in B, `kp` times the rotation
/// vector (axis times angle) that turns `Z_B` onto `target` (in I; zero while the angle is
/// below `deadband_rad`), minus `kd` times the body rates. About `Z_B` only the rate term
/// acts (no yaw target).
#[must_use]
pub fn attitude_torque(
    kp: f64,
    kd: f64,
    deadband_rad: f64,
    attitude: DQuat,
    rate_rad_s: DVec3,
    target: DVec3,
) -> DVec3 {
    let t_b = attitude.inverse() * target;
    let axis = DVec3::new(-t_b.y, t_b.x, 0.0);
    let sin = axis.length();
    let angle = libm::atan2(sin, t_b.z);
    let error = if angle < deadband_rad {
        DVec3::ZERO
    } else if sin > 1e-12 {
        axis * (angle / sin)
    } else {
        // Upside down: any horizontal axis turns it back.
        DVec3::X * angle
    };
    error * kp - rate_rad_s * kd
}

/// An on-time `on` (s) as a whole multiple of the minimum on-time `min_on` (nearest), at
/// most a period's worth of them.
#[must_use]
pub fn quantise(on: f64, min_on: f64, period: f64) -> f64 {
    let most = (period / min_on + 1e-9).floor();
    (on / min_on).round().clamp(0.0, most) * min_on
}

/// The truth a lander's control loop reads from the reference's state (`contact`: a
/// footpad touched in the last step).
#[must_use]
pub fn truth_of(state: &crate::reference::step::State, surface: &Surface, contact: bool) -> Truth {
    Truth {
        t_s: state.t_s,
        position_m: state.body.position_m,
        velocity_m_s: state.body.velocity_m_s,
        attitude: state.body.attitude,
        rate_rad_s: state.body.rate_rad_s,
        contact,
        normal: surface.normal,
    }
}
