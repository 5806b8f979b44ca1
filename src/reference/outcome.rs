//! The outcome of a touchdown (MODEL.md section 8) and the per-sample summary (section 9),
//! gathered step by step.
//!
//! Decision rules, checked after every step in this order (MODEL.md section 8 gives the
//! reasons):
//! - `diverged`: a non-finite state, or speed, body rate or penetration beyond the
//!   thresholds of the scenario;
//! - `tipped`: the tilt of `Z_B` from the slope normal passes 90 deg (also in flight), or,
//!   with `early_tipping`, the point of no return: the lander pivots on one edge of the
//!   support polygon (both its footpads touch and stick, no other footpad touches, the
//!   contact force is at most twice the weight), with the CG beyond that edge seen along
//!   gravity and moving away from it;
//! - `stable`: for `hold_time_s` without a break, CG speed and body rate below the rest
//!   thresholds, at least three legs (all, with fewer) in contact or within `REST_GAP_M`
//!   (1 micrometre) of it, the CG inside every edge of the support polygon, and every
//!   footpad in contact sticking: its friction anchor within `REST_SLIP_M` (1 micrometre)
//!   of where it was after the first step of the rest;
//! - at `t_max`: `stable` if at rest since before the last step (its footpads seen to
//!   stick), else, if a leg touches the surface, `held` while the control loop is still
//!   powered (it may fire: the rest and slide rules do not apply) and `sliding` otherwise,
//!   else `bouncing`;
//! - with `early_sliding`, `sliding` before `t_max` in a steady slide down a plane steeper
//!   than the friction angle: every footpad slipping, the CG moving down, the body rate
//!   apart from its spin about the normal below the rest rate, the normal forces summing
//!   to the weight's normal share within `SLIDE_FORCE_BAND` and each leg bearing at least
//!   `SLIDE_LEG_SHARE` of the mean, the CG's foot on the plane inside every edge of the
//!   support polygon by `SLIDE_EDGE_MARGIN mu h`, and the speed bound to stay below the
//!   divergence threshold until `t_max`;
//! - with `early_bouncing`, `bouncing` before `t_max` in a flight that cannot end before
//!   it: no footpad touching, the CG higher above the terrain's top than any footpad
//!   reaches, now and at `t_max` on its ballistic arc (the arc is concave, so no lower in
//!   between), and the tilt too far from 90 deg to pass it at the fastest turn the angular
//!   momentum allows, `|L| / I_min`, with the margin `TURN_MARGIN`.

use super::model::Model;
use super::step::{State, StepReport};
use super::strut::{StrutPeaks, stroke_margin};
use super::touchdown::{Met, Touchdown};
use crate::scenario::Loads;
use crate::slope::Surface;
use glam::{DMat3, DVec3};
use kernels::outcome::{
    REST_GAP_M, REST_SLIP_M, SLIDE_EDGE_MARGIN, SLIDE_FORCE_BAND, SLIDE_LEG_SHARE, TURN_MARGIN,
};

/// How a touchdown ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Outcome {
    /// At rest and upright, in contact, for the hold time.
    Stable,
    /// Past 90 deg of tilt, or pivoting over an edge of the support polygon past the point
    /// of no return.
    Tipped,
    /// Upright and in contact at `t_max` but still moving, or in a steady slide that must
    /// last to `t_max`.
    Sliding,
    /// Airborne at `t_max`, or in a flight that cannot end before it.
    Bouncing,
    /// A non-finite or exploding state: a defect of the model or its parameters, reported,
    /// never dropped.
    Diverged,
    /// In contact at `t_max` with its control loop still powered (it may fire): held on
    /// the surface by thrust, or left undecided by it; what it does once the loop stops is
    /// not known. Only landers with a control loop end so.
    Held,
}

impl Outcome {
    /// All outcomes, in code order (`held`, the latest, last: the codes of the others
    /// stay those of files written before it).
    pub const ALL: [Outcome; 6] = [
        Outcome::Stable,
        Outcome::Tipped,
        Outcome::Sliding,
        Outcome::Bouncing,
        Outcome::Diverged,
        Outcome::Held,
    ];

    /// The outcomes a table of a sweep lists: all but `held` for a sweep without a control
    /// loop (`controlled` false), whose landers cannot end `held`.
    pub fn listed(controlled: bool) -> impl Iterator<Item = Outcome> {
        Outcome::ALL
            .into_iter()
            .filter(move |o| controlled || *o != Outcome::Held)
    }

    /// The name written to files and printed.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Outcome::Stable => "stable",
            Outcome::Tipped => "tipped",
            Outcome::Sliding => "sliding",
            Outcome::Bouncing => "bouncing",
            Outcome::Diverged => "diverged",
            Outcome::Held => "held",
        }
    }

    /// The outcome written as `name` in files, if any.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Outcome> {
        Outcome::ALL.into_iter().find(|o| o.name() == name)
    }
}

/// Per-leg results of a sample.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LegSummary {
    /// Largest normal force on the footpad over the sample.
    pub peak_normal_force_n: f64,
    /// Damper stroke at the end (crushing is permanent, so also the largest).
    pub stroke_m: f64,
    /// Energy the damper absorbed, `∫ F_c ds`.
    pub absorbed_j: f64,
    /// Peak axial strut load, compressive positive, N (0 if it never bore one).
    pub peak_axial_force_n: f64,
    /// Start of the step of that peak, s (None if it never bore a load).
    pub peak_axial_force_s: Option<f64>,
    /// Peak side load across the strut, N.
    pub peak_side_force_n: f64,
    /// Start of the step of that peak, s (None if it never bore a load).
    pub peak_side_force_s: Option<f64>,
    /// Usable stroke less the final stroke, m (0 once bottomed; None without dampers).
    pub stroke_margin_m: Option<f64>,
    /// Whether the damper used up its stroke (`strut::BOTTOMED_WITHIN`).
    pub bottomed: bool,
    /// On regolith: the depth of the footpad's last footprint, m (0 on the elastic plane).
    pub sinkage_m: f64,
    /// On regolith: the energy the soil absorbed under the footpad, J (0 on the plane).
    pub soil_absorbed_j: f64,
}

/// The results of one sample (MODEL.md section 9).
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// How the touchdown ended.
    pub outcome: Outcome,
    /// Time at which the outcome was decided (t_max for sliding and bouncing, unless an
    /// early rule decided them), s.
    pub decided_s: f64,
    /// Steps taken up to the decision.
    pub steps: u64,
    /// Tilt of `Z_B` from the slope normal at the decision.
    pub final_tilt_deg: f64,
    /// Largest tilt of `Z_B` from the slope normal over the sample.
    pub max_tilt_deg: f64,
    /// Distance the CG moved along the surface plane, m.
    pub displacement_m: f64,
    /// Peak magnitude of the contact acceleration (what an accelerometer at the CG reads), m/s^2.
    pub peak_acceleration_m_s2: f64,
    /// Peak magnitude of its component along Z_B (the instruments' shock), m/s^2.
    pub peak_acceleration_z_body_m_s2: f64,
    /// Lift-offs after the first contact.
    pub bounces: u32,
    /// Time of the first contact, s (None if it never touched).
    pub first_contact_s: Option<f64>,
    /// The state in which it met the surface (None if it never touched).
    pub touchdown: Option<Touchdown>,
    /// Deepest penetration of a footpad below the local surface (0 if it never touched), m.
    pub max_penetration_m: f64,
    /// Per-leg results by the user's number: `legs[k]` is the user's leg `k`
    /// (`Model::leg_index`).
    pub legs: Vec<LegSummary>,
    /// What the control loop did (scenarios with one; boxed, so that the rows of a passive
    /// sweep stay small: a window of them is in memory).
    pub control: Option<Box<crate::control::ControlSummary>>,
    /// The structural limits it broke (with `[limits]`; `Summary::judge`).
    pub limits_broken: Option<crate::scenario::Broken>,
}

impl Summary {
    /// The number of legs whose damper bottomed.
    #[must_use]
    pub fn legs_bottomed(&self) -> u32 {
        self.legs.iter().map(|l| u32::from(l.bottomed)).sum()
    }

    /// Finishes the summary of a sample of `model` (the reference's and the kernels'
    /// alike): each leg's stroke margin and whether it bottomed (with dampers), and the
    /// limits it broke (with `[limits]`).
    pub fn judge(&mut self, model: &Model) {
        if let Some(h) = &model.honeycomb {
            let usable = h.usable_stroke_m();
            for leg in &mut self.legs {
                let (margin, bottomed) = stroke_margin(usable, leg.stroke_m);
                leg.stroke_margin_m = Some(margin);
                leg.bottomed = bottomed;
            }
        }
        let legs = &self.legs;
        let most = |get: fn(&LegSummary) -> f64| legs.iter().map(get).fold(0.0, f64::max);
        let loads = Loads {
            axial_force_n: most(|l| l.peak_axial_force_n),
            side_force_n: most(|l| l.peak_side_force_n),
            acceleration_m_s2: self.peak_acceleration_m_s2,
            stroke_margin_m: legs
                .iter()
                .filter_map(|l| l.stroke_margin_m)
                .reduce(f64::min),
            bottomed: legs.iter().any(|l| l.bottomed),
        };
        self.limits_broken = model.limits.map(|limits| limits.broken(&loads));
    }
}

/// Collects the summary and decides the outcome, one step at a time.
#[derive(Debug, Clone)]
pub struct Tracker {
    start_m: DVec3,
    rest_s: f64,
    /// The friction anchor of every leg when the current rest began.
    rest_anchor_m: Vec<DVec3>,
    min_cos_tilt: f64,
    peak_acceleration: f64,
    peak_acceleration_z: f64,
    bounces: u32,
    touched_since_lift_off: bool,
    first_contact_s: Option<f64>,
    /// The state at the first contact.
    met: Option<Met>,
    max_penetration: f64,
    peak_normal: Vec<f64>,
    /// Every leg's strut-load peaks.
    struts: Vec<StrutPeaks>,
    steps: u64,
}

impl Tracker {
    /// A tracker for a sample starting at `start`.
    #[must_use]
    pub fn new(model: &Model, start: &State) -> Tracker {
        Tracker {
            start_m: start.body.position_m,
            rest_s: 0.0,
            rest_anchor_m: start.legs.iter().map(|l| l.anchor_m).collect(),
            min_cos_tilt: 1.0,
            peak_acceleration: 0.0,
            peak_acceleration_z: 0.0,
            bounces: 0,
            touched_since_lift_off: false,
            first_contact_s: None,
            met: None,
            max_penetration: 0.0,
            peak_normal: vec![0.0; model.legs.len()],
            struts: vec![StrutPeaks::NONE; model.legs.len()],
            steps: 0,
        }
    }

    /// Takes in one step (its report and the state after it); returns the outcome once
    /// decided.
    pub fn observe(
        &mut self,
        model: &Model,
        surface: &Surface,
        report: &StepReport,
        after: &State,
    ) -> Option<Outcome> {
        let th = &model.thresholds;
        self.steps += 1;
        let body = &report.body;
        let rotation = glam::DMat3::from_quat(body.attitude);
        // The specific force: contact and thrust, not gravity (what an accelerometer reads).
        let acceleration = report.specific_force_n() / model.mass_kg;
        self.peak_acceleration = self.peak_acceleration.max(acceleration.length());
        let z_body = rotation.z_axis;
        self.peak_acceleration_z = self.peak_acceleration_z.max(acceleration.dot(z_body).abs());
        let cos_tilt = z_body.dot(surface.normal);
        self.min_cos_tilt = self.min_cos_tilt.min(cos_tilt);

        let mut contacts = 0;
        let mut resting = 0;
        let mut deepest = f64::NEG_INFINITY;
        let legs = report.legs.iter().zip(&mut self.peak_normal);
        for ((leg, peak), strut) in legs.zip(&mut self.struts) {
            *peak = peak.max(leg.normal_n);
            strut.observe(leg, report.t_s);
            contacts += usize::from(leg.in_contact());
            resting += usize::from(leg.penetration_m > -REST_GAP_M);
            deepest = deepest.max(leg.penetration_m);
        }
        // From the second step of a rest on: every footpad on the surface still sticks where
        // it stuck when the rest began.
        let in_rest = self.rest_s > 0.0;
        let stuck = !in_rest
            || after.legs.iter().zip(&self.rest_anchor_m).all(|(l, a)| {
                !l.anchored || (l.anchor_m - *a).length_squared() <= REST_SLIP_M.powi(2)
            });
        self.max_penetration = self.max_penetration.max(deepest);
        if contacts > 0 {
            if self.first_contact_s.is_none() {
                self.met = Some(met(model, report));
            }
            self.first_contact_s.get_or_insert(report.t_s);
            self.touched_since_lift_off = true;
        } else if self.touched_since_lift_off && -deepest > th.bounce_clearance_m {
            self.bounces += 1;
            self.touched_since_lift_off = false;
        }

        let b = &after.body;
        // A NaN or infinite velocity or rate fails its bound (every compare with NaN is
        // false), so only the position and the attitude need the test of finiteness.
        let bounded = b.position_m.is_finite()
            && b.attitude.is_finite()
            && b.velocity_m_s.length_squared() <= th.diverged_speed_m_s.powi(2)
            && b.rate_rad_s.length_squared() <= th.diverged_rate_rad_s.powi(2);
        if !bounded || deepest > th.diverged_penetration_m {
            return Some(Outcome::Diverged);
        }

        // Support polygon, seen along gravity.
        let mut inside = true;
        let mut tipping = false;
        // No impact under way: the legs push with at most twice the weight.
        let weight_n = model.mass_kg * model.gravity_m_s2;
        let quasi_static = report.force_n.length_squared() <= (2.0 * weight_n).powi(2);
        if !model.edges.is_empty() {
            let centroid =
                report.legs.iter().map(|l| l.tip_m).sum::<DVec3>() / report.legs.len() as f64;
            for [i, j] in &model.edges {
                let (a, c) = (&report.legs[*i], &report.legs[*j]);
                let edge = c.tip_m - a.tip_m;
                let mut outward = DVec3::new(edge.y, -edge.x, 0.0);
                if outward.dot(centroid - a.tip_m) > 0.0 {
                    outward = -outward;
                }
                if outward.dot(body.position_m - a.tip_m) > 0.0 {
                    inside = false;
                    // Pivoting on this edge alone, its footpads held by friction.
                    let pivot = a.in_contact()
                        && c.in_contact()
                        && contacts == 2
                        && !a.slipping
                        && !c.slipping;
                    let away = outward.dot(body.velocity_m_s - a.tip_velocity_m_s) > 0.0;
                    tipping |= pivot && away && quasi_static;
                }
            }
        }
        // A lander whose control loop may still fire is not left to itself: no rest, and no
        // early rule, counts for it (MODEL.md section 8).
        let passive = !report.thrust.powered;
        if cos_tilt < 0.0 || (th.early_tipping && tipping && passive) {
            return Some(Outcome::Tipped);
        }

        let at_rest = passive
            && body.velocity_m_s.length_squared() < th.rest_speed_m_s.powi(2)
            && body.rate_rad_s.length_squared() < th.rest_rate_rad_s.powi(2)
            && resting >= model.legs.len().min(3)
            && stuck
            && inside;
        if at_rest && !in_rest {
            // A rest begins with this step: remember where the footpads stick.
            for (a, l) in self.rest_anchor_m.iter_mut().zip(&after.legs) {
                *a = l.anchor_m;
            }
        }
        self.rest_s = if at_rest {
            self.rest_s + report.dt_s
        } else {
            0.0
        };
        if self.rest_s >= th.hold_time_s {
            return Some(Outcome::Stable);
        }
        if after.t_s >= model.t_max_s {
            // At rest since before this step: its footpads were seen to stick (on the
            // first step of a rest they are not checked, and a slow slider would pass
            // every other step).
            return Some(if at_rest && in_rest {
                Outcome::Stable
            } else if contacts > 0 && !passive {
                Outcome::Held
            } else if contacts > 0 {
                Outcome::Sliding
            } else {
                Outcome::Bouncing
            });
        }
        let all_slipping = report.legs.iter().all(|l| l.slipping);
        if passive
            && all_slipping
            && model.slides_decidable()
            && steady_slide(model, surface, report, after)
        {
            return Some(Outcome::Sliding);
        }
        if passive && th.early_bouncing && contacts == 0 && cannot_return(model, surface, after) {
            return Some(Outcome::Bouncing);
        }
        None
    }

    /// The summary of a sample decided as `outcome` in state `last`.
    #[must_use]
    pub fn finish(
        &self,
        model: &Model,
        surface: &Surface,
        outcome: Outcome,
        last: &State,
    ) -> Summary {
        let cos_tilt = (last.body.attitude * DVec3::Z).dot(surface.normal);
        // The largest tilt over the states of every step and the final one, so that it is
        // never below the final tilt.
        let min_cos_tilt = self.min_cos_tilt.min(cos_tilt);
        let moved = last.body.position_m - self.start_m;
        let along = moved - surface.normal * surface.normal.dot(moved);
        let finite_or_zero = |x: f64| if x.is_finite() { x } else { 0.0 };
        Summary {
            outcome,
            decided_s: last.t_s,
            steps: self.steps,
            final_tilt_deg: finite_or_zero(libm::acos(cos_tilt.clamp(-1.0, 1.0)).to_degrees()),
            max_tilt_deg: libm::acos(min_cos_tilt.clamp(-1.0, 1.0)).to_degrees(),
            displacement_m: finite_or_zero(along.length()),
            peak_acceleration_m_s2: finite_or_zero(self.peak_acceleration),
            peak_acceleration_z_body_m_s2: finite_or_zero(self.peak_acceleration_z),
            bounces: self.bounces,
            first_contact_s: self.first_contact_s,
            touchdown: self
                .met
                .map(|m| Touchdown::of(&m, surface.normal, surface.tangent_u, surface.tangent_v)),
            max_penetration_m: finite_or_zero(self.max_penetration),
            legs: model
                .leg_index
                .iter()
                .map(|&i| {
                    let (p, l, strut) = (&self.peak_normal[i], &last.legs[i], &self.struts[i]);
                    let (sinkage_m, soil_absorbed_j) =
                        model.soil.as_ref().map_or((0.0, 0.0), |s| {
                            kernels::regolith::leg_results(
                                s.exponent,
                                s.unloading_n_per_m,
                                l.sinkage_max_m,
                                l.soil_force_max_n,
                                l.soil_absorbed_j,
                            )
                        });
                    LegSummary {
                        peak_normal_force_n: finite_or_zero(*p),
                        stroke_m: finite_or_zero(l.stroke_m),
                        absorbed_j: finite_or_zero(l.absorbed_j),
                        peak_axial_force_n: finite_or_zero(strut.axial_n),
                        peak_axial_force_s: (!strut.axial_s.is_nan()).then_some(strut.axial_s),
                        peak_side_force_n: finite_or_zero(strut.side_n),
                        peak_side_force_s: (!strut.side_s.is_nan()).then_some(strut.side_s),
                        stroke_margin_m: None,
                        bottomed: false,
                        sinkage_m: finite_or_zero(sinkage_m),
                        soil_absorbed_j: finite_or_zero(soil_absorbed_j),
                    }
                })
                .collect(),
            control: None,
            limits_broken: None,
        }
    }
}

/// The state at the start of the step `report` (its first contact), and its deepest leg
/// by the user's number (the lowest on a tie, as the kernels pick it).
fn met(model: &Model, report: &StepReport) -> Met {
    let (mut first_leg, mut deepest) = (0, f64::NEG_INFINITY);
    for (k, &i) in model.leg_index.iter().enumerate() {
        let leg = &report.legs[i];
        if leg.penetration_m > deepest {
            (first_leg, deepest) = (k, leg.penetration_m);
        }
    }
    let b = &report.body;
    let rotation = DMat3::from_quat(b.attitude);
    Met {
        velocity_m_s: b.velocity_m_s,
        rate_rad_s: b.rate_rad_s,
        x_body: rotation.x_axis,
        z_body: rotation.z_axis,
        first_leg,
    }
}

/// Whether the speed stays below the divergence threshold until `t_max`: `|v| + g T`,
/// bounded without a root by `(a + b)^2 <= 2 a^2 + 2 b^2`.
fn speed_bounded(model: &Model, after: &State) -> bool {
    let g_remaining = model.gravity_m_s2 * (model.t_max_s - after.t_s);
    2.0 * after.body.velocity_m_s.length_squared() + 2.0 * (g_remaining * g_remaining)
        < model.thresholds.diverged_speed_m_s.powi(2)
}

/// The early `sliding` rule (see the module's rules): a steady slide down a plane steeper
/// than the friction angle cannot stop (friction, at most `mu` times the normal force,
/// cannot hold the weight's share along the slope), lift off or tip (every leg bears its
/// share of a settled load, and the centre of pressure, `mu h` ahead of the CG's foot in
/// the direction of the slide, stays inside the support polygon whichever way the lander
/// turns about the normal) before `t_max`. The caller checks that every footpad slips.
fn steady_slide(model: &Model, surface: &Surface, report: &StepReport, after: &State) -> bool {
    let n = surface.normal;
    let mu = model.contact.friction_coefficient;
    // tan(slope) > mu, without the tangent: sin^2 > mu^2 cos^2.
    let steep = n.x * n.x + n.y * n.y > mu * mu * (n.z * n.z);
    // Not rocking: the body rate less its spin about the normal below the rest rate.
    let b = &after.body;
    let spin = b
        .rate_rad_s
        .dot(DMat3::from_quat(b.attitude).transpose() * n);
    let rocking_squared = b.rate_rad_s.length_squared() - spin * spin;
    let steady_attitude = rocking_squared < model.thresholds.rest_rate_rad_s.powi(2);
    let moving_down = b.velocity_m_s.z < 0.0;
    let weight_share = model.mass_kg * model.gravity_m_s2 * n.z;
    let total: f64 = report.legs.iter().map(|l| l.normal_n).sum();
    let settled = (total - weight_share).abs() <= SLIDE_FORCE_BAND * weight_share;
    let least = report
        .legs
        .iter()
        .map(|l| l.normal_n)
        .fold(f64::INFINITY, f64::min);
    let borne = least >= SLIDE_LEG_SHARE / report.legs.len() as f64 * total;
    steep
        && steady_attitude
        && moving_down
        && settled
        && borne
        && inside_by(model, surface, report)
        && speed_bounded(model, after)
}

/// Whether the CG's foot on the plane lies inside every edge of the support polygon by
/// more than `SLIDE_EDGE_MARGIN mu h` (`h` the CG's height above the plane), each edge
/// taken between the footpads of the step, in the plane.
fn inside_by(model: &Model, surface: &Surface, report: &StepReport) -> bool {
    let n = surface.normal;
    let x = report.body.position_m;
    let height = n.dot(x);
    let foot = x - n * height;
    let least = SLIDE_EDGE_MARGIN * model.contact.friction_coefficient * height;
    let centroid = report.legs.iter().map(|l| l.tip_m).sum::<DVec3>() / report.legs.len() as f64;
    model.edges.iter().all(|[i, j]| {
        let a = report.legs[*i].tip_m;
        let edge = report.legs[*j].tip_m - a;
        // Twice the signed area of (a, c, point): its distance from the edge times |edge|.
        let side = |p: DVec3| edge.cross(p - a).dot(n);
        let (foot_side, centroid_side) = (side(foot), side(centroid));
        foot_side * centroid_side > 0.0
            && foot_side * foot_side > least * least * edge.length_squared()
    }) && !model.edges.is_empty()
}

/// The early `bouncing` rule (see the module's rules), on the state after a step without
/// contact.
fn cannot_return(model: &Model, surface: &Surface, after: &State) -> bool {
    let b = &after.body;
    let n = surface.normal;
    let remaining = model.t_max_s - after.t_s;
    // The CG's height above the terrain's top, less the reach of any footpad: positive now
    // and, on the ballistic arc along the normal, at t_max.
    let height = n.dot(b.position_m) - model.terrain_top_m() - model.leg_reach_m();
    let fall = 0.5 * model.gravity_m_s2 * n.z * remaining;
    let height_at_end = height + remaining * (n.dot(b.velocity_m_s) - fall);
    let clear = height > 0.0 && height_at_end > 0.0;
    // Torque-free, the body rate is at most |L| / I_min; Z_B turns no faster. A tilt
    // `theta` stays below 90 deg for T if theta + |w| T < pi / 2, which cos(theta) > |w| T
    // implies (cos(theta) > x >= sin(x) = cos(pi / 2 - x)).
    let i = model.inertia_kg_m2;
    let momentum_squared = (i * b.rate_rad_s).length_squared();
    let i_min = i.min_element();
    let cos_tilt = DMat3::from_quat(b.attitude).z_axis.dot(n);
    let turn = TURN_MARGIN * remaining;
    let upright = cos_tilt > 0.0 && (cos_tilt * i_min).powi(2) > momentum_squared * (turn * turn);
    let turning_bounded = momentum_squared < (i_min * model.thresholds.diverged_rate_rad_s).powi(2);
    clear && upright && turning_bounded && speed_bounded(model, after)
}
