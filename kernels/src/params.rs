//! Parameters of a sweep, broadcast to lanes once so that the step loads nothing twice.

use crate::lane::Lane;
use crate::rocks::Rocks;
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

/// The soil under the footpads (the reference's `regolith::Soil`, per lane).
#[derive(Debug, Clone, Copy)]
#[allow(missing_docs)]
pub struct SoilParams<L> {
    /// `A (k_c / b + k_phi)`: the loading curve is `F = virgin_n z^n`.
    pub virgin_n: L,
    pub exponent: L,
    /// `A k_u`, N/m.
    pub unloading_n_per_m: L,
    pub passive_linear_n_per_m: L,
    pub passive_quadratic_n_per_m2: L,
    pub pad_radius_m: L,
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
    /// The index in `legs` of the user's leg `k` (the reference's `Model::leg_index`): the
    /// first leg to touch is reported by the user's number.
    pub leg_index: Vec<usize>,
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
    /// Regolith under the footpads (`None`: the elastic plane).
    pub soil: Option<SoilParams<L>>,
    pub terrain: Option<Terrain>,
    /// Rocks on the ground (`None`: none), each lane at its own abundance.
    pub rocks: Option<Rocks>,
    pub rock_abundance: L,
    /// The footpads' radius (their sphere's among rocks).
    pub pad_radius_m: L,
    pub step_s: L,
    /// Whether the contact step follows its error estimate (`step::control_step`): the
    /// reference's `Model::step_control`, with its tolerance squared and its bounds.
    pub step_control: bool,
    pub tolerance_squared: L,
    pub step_min_s: L,
    pub step_max_s: L,
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
    /// The same, rocks aside: the ground's highest point (`step::step_size`), m.
    pub ground_top_m: L,
    /// The factor on the terrain's heights of each lane's sample (`Terrain::scale`).
    pub terrain_scale: L,
    /// Whether the landers have a control loop (thrusters): the step then applies
    /// `Block::thrust` and stops at its events.
    pub thrust: bool,
    /// Whether every strut axis is `-Z_B` (the default): the strut's direction from the
    /// footpad to the hip in I is then `Z_B`, the rotation's third column, with the same
    /// bits as the product `-R u` gives, and the step skips that product.
    pub struts_along_z: bool,
}

impl<L: Lane> Params<L> {
    /// Sets lane `i` of every per-lane parameter to lane `i` of `from`: a lane takes the
    /// parameters of its own sample where a scenario draws them per sample (mass, CG
    /// height, contact law, crush strength). The structure (legs, edges, stages, terrain,
    /// the flags) must be the same in both: it is the sweep's, not the sample's.
    ///
    /// # Panics
    /// If `from` has other legs or damper stages than `self`.
    pub fn copy_lane(&mut self, i: usize, from: &Params<L>) {
        fn one<L: Lane>(to: &mut L, from: &L, i: usize) {
            to.set_lane(i, from.lane(i));
        }
        fn three<L: Lane>(to: &mut Vec3<L>, from: &Vec3<L>, i: usize) {
            to.set_lane(i, from.lane(i));
        }
        assert!(self.legs.len() == from.legs.len(), "the same legs");
        one(&mut self.gravity_m_s2, &from.gravity_m_s2, i);
        one(&mut self.inverse_mass_per_kg, &from.inverse_mass_per_kg, i);
        three(&mut self.inertia_kg_m2, &from.inertia_kg_m2, i);
        three(&mut self.inverse_inertia, &from.inverse_inertia, i);
        three(&mut self.gyroscopic, &from.gyroscopic, i);
        for (to, from) in self.legs.iter_mut().zip(&from.legs) {
            three(&mut to.tip_m, &from.tip_m, i);
            three(&mut to.strut_axis, &from.strut_axis, i);
        }
        one(&mut self.stiffness_n_per_m, &from.stiffness_n_per_m, i);
        one(&mut self.damping_n_s_per_m, &from.damping_n_s_per_m, i);
        one(
            &mut self.friction_coefficient,
            &from.friction_coefficient,
            i,
        );
        one(
            &mut self.friction_stiffness_n_per_m,
            &from.friction_stiffness_n_per_m,
            i,
        );
        one(
            &mut self.friction_compliance_m_per_n,
            &from.friction_compliance_m_per_n,
            i,
        );
        one(
            &mut self.friction_damping_n_s_per_m,
            &from.friction_damping_n_s_per_m,
            i,
        );
        match (&mut self.honeycomb, &from.honeycomb) {
            (Some(to), Some(from)) => {
                assert!(to.stages.len() == from.stages.len(), "the same stages");
                for (t, f) in to.stages.iter_mut().zip(&from.stages) {
                    one(&mut t.0, &f.0, i);
                    one(&mut t.1, &f.1, i);
                }
                one(&mut to.peak_force_n, &from.peak_force_n, i);
                one(&mut to.peak_stroke_m, &from.peak_stroke_m, i);
                one(&mut to.usable_stroke_m, &from.usable_stroke_m, i);
            }
            (None, None) => {}
            _ => panic!("dampers in both or neither"),
        }
        match (&mut self.soil, &from.soil) {
            (Some(to), Some(from)) => {
                one(&mut to.virgin_n, &from.virgin_n, i);
                one(&mut to.exponent, &from.exponent, i);
                one(&mut to.unloading_n_per_m, &from.unloading_n_per_m, i);
                one(
                    &mut to.passive_linear_n_per_m,
                    &from.passive_linear_n_per_m,
                    i,
                );
                one(
                    &mut to.passive_quadratic_n_per_m2,
                    &from.passive_quadratic_n_per_m2,
                    i,
                );
                one(&mut to.pad_radius_m, &from.pad_radius_m, i);
            }
            (None, None) => {}
            _ => panic!("regolith in both or neither"),
        }
        one(&mut self.rock_abundance, &from.rock_abundance, i);
        one(&mut self.pad_radius_m, &from.pad_radius_m, i);
        one(&mut self.step_s, &from.step_s, i);
        one(&mut self.tolerance_squared, &from.tolerance_squared, i);
        one(&mut self.step_min_s, &from.step_min_s, i);
        one(&mut self.step_max_s, &from.step_max_s, i);
        one(&mut self.flight_step_max_s, &from.flight_step_max_s, i);
        one(&mut self.t_max_s, &from.t_max_s, i);
        one(&mut self.leg_reach_m, &from.leg_reach_m, i);
        one(&mut self.rest_speed_squared, &from.rest_speed_squared, i);
        one(&mut self.rest_rate_squared, &from.rest_rate_squared, i);
        one(&mut self.hold_time_s, &from.hold_time_s, i);
        one(&mut self.bounce_clearance_m, &from.bounce_clearance_m, i);
        one(
            &mut self.diverged_speed_squared,
            &from.diverged_speed_squared,
            i,
        );
        one(
            &mut self.diverged_rate_squared,
            &from.diverged_rate_squared,
            i,
        );
        one(
            &mut self.diverged_penetration_m,
            &from.diverged_penetration_m,
            i,
        );
        one(
            &mut self.quasi_static_force_squared,
            &from.quasi_static_force_squared,
            i,
        );
        one(&mut self.rest_contacts, &from.rest_contacts, i);
        one(&mut self.leg_count, &from.leg_count, i);
        one(&mut self.weight_n, &from.weight_n, i);
        one(
            &mut self.friction_coefficient_squared,
            &from.friction_coefficient_squared,
            i,
        );
        one(&mut self.inertia_min_kg_m2, &from.inertia_min_kg_m2, i);
        one(
            &mut self.diverged_momentum_squared,
            &from.diverged_momentum_squared,
            i,
        );
        one(&mut self.terrain_top_m, &from.terrain_top_m, i);
        one(&mut self.ground_top_m, &from.ground_top_m, i);
        one(&mut self.terrain_scale, &from.terrain_scale, i);
    }
}
