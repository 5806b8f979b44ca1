//! The control laws: the built-in descent and attitude-hold laws, and the laws of a
//! program's own (`Law`), registered under a name for scenarios to name.

use super::allocation::Wrench;
use super::sensors::Sensed;
use glam::{DQuat, DVec3};

/// Whether the sensed tilt of `Z_B` from the surface normal `normal` exceeds `limit_deg`:
/// where `hold_down` with `stop_tilt_deg` stops pushing (a lander far over along the slope
/// is pushed further down it, not onto it).
#[must_use]
pub fn tilted_past(sensed: &Sensed, normal: DVec3, limit_deg: f64) -> bool {
    (sensed.attitude * DVec3::Z).dot(normal) < libm::cos(limit_deg.to_radians())
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
/// block that reach a control instant together (with `gathered`, every lander of a worker
/// at the instant) are handed over at once, as slices of the
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

    /// Whether a sweep gathers the landers of a worker at each control instant and calls
    /// the law once for all of them (up to 512 a call; `sweep::cohort`): worth it where a
    /// call costs far more than the work for one lander in it, as a Python law's does. The
    /// rows are the same either way. By default `false`: a sweep calls the law for the
    /// landers of a block that reach an instant together, and the landers stay in their
    /// lanes (gathering them moves each between blocks twice an instant, which made the
    /// Rust law of `examples/user_law` a fifth slower).
    fn gathered(&self) -> bool {
        false
    }
}

/// A registered law and its name.
#[derive(Clone)]
pub struct NamedLaw {
    /// The name it was registered under (`[control] law`).
    pub(super) name: String,
    /// The law itself, shared by every worker thread.
    pub(crate) law: std::sync::Arc<dyn Law>,
}

impl std::fmt::Debug for NamedLaw {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "law {:?}", self.name)
    }
}

static LAWS: std::sync::Mutex<Vec<(String, std::sync::Arc<dyn Law>)>> =
    std::sync::Mutex::new(Vec::new());

/// Registers `law` under `name` for scenarios to name (`[control] law = "NAME"`): a
/// program that embeds touchdown calls this before `commands::main` (see
/// `examples/user_law.rs`). A later registration under the same name replaces it.
pub fn register_law(name: &str, law: impl Law + 'static) {
    let mut laws = LAWS
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    laws.retain(|(n, _)| n != name);
    laws.push((name.to_string(), std::sync::Arc::new(law)));
}

/// The names of the laws registered, in the order they were registered.
#[must_use]
pub fn registered_names() -> Vec<String> {
    let laws = LAWS
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    laws.iter().map(|(n, _)| n.clone()).collect()
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

/// A sample's descent (`[control.descent]`): its parameters as drawn.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DescentDraw {
    /// Height of the lowest footpad above the touchdown point at the descent's start.
    pub start_altitude_m: f64,
    /// Speed down at the descent's start (before the velocity errors).
    pub start_speed_m_s: f64,
    /// Deceleration `b` of the braking profile `h'_ref = -sqrt(2 b (h - h_r))`.
    pub braking_m_s2: f64,
    /// Gain `k` on the error in the rate of height: acceleration `k (h'_ref - h')`.
    pub gain_per_s: f64,
    /// The burn stops at the first instant at or below the release height with the
    /// sensed `|h'|` under this.
    pub release_speed_m_s: f64,
    /// The law nulls the velocity along the surface too (the scenario's
    /// `null_lateral_velocity`, the same for every sample).
    pub null_lateral_velocity: bool,
}

/// The descent law's force on the lander (`[control.descent]`), in B: its mass times
/// `gain (h'_ref - h') n + g up`, where `h' = n . v` is the rate of the footpads' height
/// `height_m` along the surface normal `n` (`v` the sensed velocity) and `h'_ref` the
/// braking profile's, `-sqrt(2 braking (height - release))` above the release height
/// `release_height_m` and 0 at or below it; the sensed attitude turns it into B. A velocity
/// along the surface (the navigation error) changes no height: with `null_lateral_velocity` the
/// law nulls it at the same rate, asking for `gain (h'_ref n - v) + g up`; without, it is
/// left as it is.
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
    let v = sensed.velocity_m_s;
    let control = if d.null_lateral_velocity {
        (normal * rate_ref - v) * d.gain_per_s
    } else {
        normal * ((rate_ref - normal.dot(v)) * d.gain_per_s)
    };
    let accel = control + DVec3::Z * gravity_m_s2;
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
