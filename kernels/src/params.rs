//! Parameters of a sweep, broadcast to lanes once so that the step loads nothing twice.

use crate::lane::Lane;
use crate::terrain::Terrain;
use crate::vec3::Vec3;

/// One leg: footpad at zero stroke and strut axis, in B.
#[derive(Debug, Clone, Copy)]
pub struct LegParams<L> {
    /// Footpad position in B at zero stroke, m.
    pub tip_m: Vec3<L>,
    /// Unit strut axis in B, from hip to footpad.
    pub strut_axis: Vec3<L>,
}

/// A crushable honeycomb cartridge: stage ends and forces, and the initial peak.
#[derive(Debug, Clone)]
pub struct HoneycombParams<L> {
    /// (stroke at the end of the stage, crush force within it), first stage first.
    pub stages: Vec<(L, L)>,
    /// Crush force over the initial peak, N.
    pub peak_force_n: L,
    /// Stroke over which the initial peak acts, m.
    pub peak_stroke_m: L,
    /// The usable stroke, m.
    pub usable_stroke_m: L,
}

/// Everything the kernels hold fixed over a sweep.
///
/// Besides the parameters themselves it holds what the step would otherwise recompute
/// from them every time: reciprocals (the step multiplies by them instead of dividing)
/// and squared thresholds (compared with squared lengths, without a square root).
#[derive(Debug, Clone)]
#[allow(missing_docs)]
pub struct Params<L> {
    pub gravity_m_s2: L,
    /// `1 / mass`.
    pub inverse_mass_per_kg: L,
    pub inertia_kg_m2: Vec3<L>,
    /// `1 / inertia_kg_m2`, per axis.
    pub inverse_inertia: Vec3<L>,
    /// `((I_y - I_z) / I_x, (I_z - I_x) / I_y, (I_x - I_y) / I_z)`: Euler's equations are
    /// `dw_x/dt = M_x / I_x + gyroscopic_x w_y w_z` and cyclic (the reference's
    /// `rigid_body::gyroscopic`).
    pub gyroscopic: Vec3<L>,
    pub legs: Vec<LegParams<L>>,
    /// Edges of the support polygon (indices into `legs`).
    pub edges: Vec<[usize; 2]>,
    pub stiffness_n_per_m: L,
    pub damping_n_s_per_m: L,
    pub friction_coefficient: L,
    pub friction_stiffness_n_per_m: L,
    /// `1 / friction_stiffness_n_per_m`.
    pub friction_compliance_m_per_n: L,
    pub friction_damping_n_s_per_m: L,
    pub honeycomb: Option<HoneycombParams<L>>,
    pub terrain: Option<Terrain>,
    pub step_s: L,
    pub flight_step_max_s: L,
    /// Whether free flight may take steps longer than `step_s`.
    pub long_flight_steps: bool,
    pub t_max_s: L,
    pub leg_reach_m: L,
    /// `rest_speed_m_s^2`.
    pub rest_speed_squared: L,
    /// `rest_rate_rad_s^2`.
    pub rest_rate_squared: L,
    pub hold_time_s: L,
    pub bounce_clearance_m: L,
    /// `diverged_speed_m_s^2`.
    pub diverged_speed_squared: L,
    /// `diverged_rate_rad_s^2`.
    pub diverged_rate_squared: L,
    pub diverged_penetration_m: L,
    /// Whether `tipped` is decided at the point of no return, not only past 90 deg.
    pub early_tipping: bool,
    /// `(2 m g)^2`: a contact force within twice the weight means no impact is under way.
    pub quasi_static_force_squared: L,
    /// Legs that must touch for rest: three, or all when fewer.
    pub rest_contacts: L,
    /// Whether a steady slide is decided `sliding` early (the scenario asks for it, the
    /// surface is a plane and no damper can crush in a slide: the reference's
    /// `Model::slides_decidable`).
    pub early_sliding: bool,
    /// Whether a flight that cannot end before `t_max` is decided `bouncing` early.
    pub early_bouncing: bool,
    /// Number of legs.
    pub leg_count: L,
    /// `m g`.
    pub weight_n: L,
    /// The friction coefficient squared.
    pub friction_coefficient_squared: L,
    /// The least principal moment of inertia.
    pub inertia_min_kg_m2: L,
    /// `(I_min diverged_rate)^2`: the squared angular momentum of the divergence threshold.
    pub diverged_momentum_squared: L,
    /// Height of the terrain's highest point above the plane (0 for the plane), m.
    pub terrain_top_m: L,
    /// Whether the landers have a control loop (thrusters): the step then applies
    /// `Block::thrust` and stops at its events.
    pub thrust: bool,
}

/// Broadcasts a scalar, outside the kernels: through memory, with no SIMD instruction
/// (code outside the kernels is compiled for the baseline CPU, and an instruction of the
/// kernel's set there would be an out-of-line call that leaves the vector unit dirty).
#[inline]
#[must_use]
pub fn lane<L: Lane>(x: f64) -> L {
    let mut l = L::ZERO;
    for i in 0..L::LANES {
        l.set_lane(i, x);
    }
    l
}
