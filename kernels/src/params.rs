//! Parameters of a sweep, broadcast to lanes once so that the step loads nothing twice.

use crate::lane::{Lane, splat};
use crate::terrain::Terrain;
use crate::vec3::Vec3;

/// One leg: footpad at zero stroke and strut axis, in B.
#[derive(Debug, Clone, Copy)]
pub struct LegParams {
    /// Footpad position in B at zero stroke, m.
    pub tip_m: Vec3,
    /// Unit strut axis in B, from hip to footpad.
    pub strut_axis: Vec3,
}

/// A crushable honeycomb cartridge: stage ends and forces, and the initial peak.
#[derive(Debug, Clone)]
pub struct HoneycombParams {
    /// (stroke at the end of the stage, crush force within it), first stage first.
    pub stages: Vec<(Lane, Lane)>,
    /// Crush force over the initial peak, N.
    pub peak_force_n: Lane,
    /// Stroke over which the initial peak acts, m.
    pub peak_stroke_m: Lane,
    /// The usable stroke, m.
    pub usable_stroke_m: Lane,
}

/// Everything the kernels hold fixed over a sweep.
///
/// Besides the parameters themselves it holds what the step would otherwise recompute
/// from them every time: reciprocals (the step multiplies by them instead of dividing)
/// and squared thresholds (compared with squared lengths, without a square root).
#[derive(Debug, Clone)]
#[allow(missing_docs)]
pub struct Params {
    pub gravity_m_s2: Lane,
    /// `1 / mass`.
    pub inverse_mass_per_kg: Lane,
    pub inertia_kg_m2: Vec3,
    /// `1 / inertia_kg_m2`, per axis.
    pub inverse_inertia: Vec3,
    pub legs: Vec<LegParams>,
    /// Edges of the support polygon (indices into `legs`).
    pub edges: Vec<[usize; 2]>,
    pub stiffness_n_per_m: Lane,
    pub damping_n_s_per_m: Lane,
    pub friction_coefficient: Lane,
    pub friction_stiffness_n_per_m: Lane,
    /// `1 / friction_stiffness_n_per_m`.
    pub friction_compliance_m_per_n: Lane,
    pub friction_damping_n_s_per_m: Lane,
    pub honeycomb: Option<HoneycombParams>,
    pub terrain: Option<Terrain>,
    pub step_s: Lane,
    pub flight_step_max_s: Lane,
    /// Whether free flight may take steps longer than `step_s`.
    pub long_flight_steps: bool,
    pub t_max_s: Lane,
    pub leg_reach_m: Lane,
    /// `rest_speed_m_s^2`.
    pub rest_speed_squared: Lane,
    /// `rest_rate_rad_s^2`.
    pub rest_rate_squared: Lane,
    pub hold_time_s: Lane,
    pub bounce_clearance_m: Lane,
    /// `diverged_speed_m_s^2`.
    pub diverged_speed_squared: Lane,
    /// `diverged_rate_rad_s^2`.
    pub diverged_rate_squared: Lane,
    pub diverged_penetration_m: Lane,
    /// Whether `tipped` is decided at the point of no return, not only past 90 deg.
    pub early_tipping: bool,
    /// `(2 m g)^2`: a contact force within twice the weight means no impact is under way.
    pub quasi_static_force_squared: Lane,
    /// Legs that must touch for rest: three, or all when fewer.
    pub rest_contacts: Lane,
}

/// Broadcasts a scalar.
#[inline]
#[must_use]
pub fn lane(x: f64) -> Lane {
    splat(x)
}
