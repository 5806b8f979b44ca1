//! What stays fixed over a sweep (`Model`, derived once from the scenario) and what a
//! sample fixes (`Surface`, the slope plane and terrain tile it lands on).

use super::regolith::Soil;
use crate::scenario::Sample;
use crate::scenario::{PARAMETERS, PSI_PA, Parameter, Sampled, Scenario, StrutAxes};
use glam::DVec3;
use kernels::terrain::Terrain;
use std::borrow::Cow;

/// One leg: its footpad in B with the damper uncrushed, and its strut axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Leg {
    /// Footpad position in B at zero stroke, m.
    pub tip_m: DVec3,
    /// Unit strut axis in B, from hip to footpad; a stroke `s` moves the footpad by `-s u`.
    pub strut_axis: DVec3,
}

/// Contact law parameters (MODEL.md section 5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Normal spring stiffness `k` per leg: `F_N = max(0, k d - c (n . v))`.
    pub stiffness_n_per_m: f64,
    /// Normal damping `c` per leg; 0 is the completely elastic surface.
    pub damping_n_s_per_m: f64,
    /// Coulomb friction coefficient `mu`: friction is capped at `mu F_N`.
    pub friction_coefficient: f64,
    /// Stiffness of the stick-slip tangential spring from the footpad to its anchor.
    pub friction_stiffness_n_per_m: f64,
    /// Damping of the stick-slip tangential spring, on the tangential footpad velocity.
    pub friction_damping_n_s_per_m: f64,
}

/// A crushable honeycomb cartridge (MODEL.md section 6), the same in every leg.
#[derive(Debug, Clone, PartialEq)]
pub struct Honeycomb {
    /// Stroke at the end of each stage and the crush force within it, first stage first, N.
    pub stages: Vec<(f64, f64)>,
    /// Crush force of a cartridge that is not pre-crushed over its first millimetres, N
    /// (equal to the first plateau when pre-crushed).
    pub peak_force_n: f64,
    /// Stroke over which the initial peak acts, m (0 when pre-crushed).
    pub peak_stroke_m: f64,
    /// Cross-section of the cartridge, m^2: a crush strength drawn per sample gives the
    /// first stage's force (`Model::for_sample`).
    pub area_m2: f64,
    /// The initial peak's factor over the first plateau (`None` when pre-crushed).
    pub initial_peak_factor: Option<f64>,
}

impl Honeycomb {
    /// The usable stroke: the cartridge is rigid again beyond it.
    #[must_use]
    pub fn usable_stroke_m(&self) -> f64 {
        self.stages.last().map_or(0.0, |s| s.0)
    }
}

/// The error control of the contact step (MODEL.md section 2.1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepControl {
    /// The error a contact step may add to a footpad's velocity, m/s.
    pub tolerance_m_s: f64,
    /// The shortest contact step, s.
    pub step_min_s: f64,
    /// The longest contact step, s.
    pub step_max_s: f64,
}

/// Outcome thresholds in SI units (rad, not deg).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thresholds {
    /// CG speed below which the lander may count as at rest.
    pub rest_speed_m_s: f64,
    /// Body rate below which the lander may count as at rest.
    pub rest_rate_rad_s: f64,
    /// How long a rest must last without a break for `stable`.
    pub hold_time_s: f64,
    /// Clearance the lowest footpad must reach after a lift-off for a bounce to count.
    pub bounce_clearance_m: f64,
    /// CG speed beyond which the state counts as `diverged`.
    pub diverged_speed_m_s: f64,
    /// Body rate beyond which the state counts as `diverged`.
    pub diverged_rate_rad_s: f64,
    /// Footpad penetration beyond which the state counts as `diverged`.
    pub diverged_penetration_m: f64,
    /// Decide `tipped` at the point of no return, not only past 90 deg of tilt.
    pub early_tipping: bool,
    /// Decide `sliding` in a steady slide before `t_max` (where `Model::slides_decidable`
    /// allows it); `Model::new` clears it if the rule fails at the worst corner of the
    /// parameters the scenario draws.
    pub early_sliding: bool,
    /// Decide `bouncing` in a flight that cannot end before `t_max`.
    pub early_bouncing: bool,
}

/// Everything a sweep holds fixed, in the units the physics uses.
#[derive(Debug, Clone)]
pub struct Model {
    /// Gravity `g0`, along `-Z_I`.
    pub gravity_m_s2: f64,
    /// Lander mass (not reduced by the propellant burnt, MODEL.md section 7).
    pub mass_kg: f64,
    /// Principal moments of inertia about X_B, Y_B, Z_B.
    pub inertia_kg_m2: DVec3,
    /// The legs in the engine's order: counter-clockwise about Z_B by azimuth from -X_B
    /// (`engine_order`), the order in which the reference and the kernels visit them and
    /// sum their forces, so that a sample's numbers do not depend on the order in which a
    /// scenario lists its legs. Outputs number legs as the user does (`leg_index`; MODEL.md
    /// section 3).
    pub legs: Vec<Leg>,
    /// The index in `legs` of the user's leg `k`: the `k`-th of `lander.leg_tips_m`, or
    /// with the layout keys the `k`-th counter-clockwise from `first_leg_azimuth_deg`.
    pub leg_index: Vec<usize>,
    /// Edges of the support polygon, as pairs of indices into `legs`: the convex hull of the
    /// footpads seen along Z_B, counter-clockwise (`support_edges`). A footpad inside the
    /// hull is on no edge.
    pub edges: Vec<[usize; 2]>,
    /// The leg-surface contact law, the same for every leg.
    pub contact: Contact,
    /// The damper in every leg's strut (`None`: rigid legs).
    pub honeycomb: Option<Honeycomb>,
    /// Area of each footpad's sole, m^2.
    pub footpad_area_m2: f64,
    /// The scenario's regolith (`None`: the elastic plane), whose values a sample may draw.
    pub regolith: Option<crate::scenario::Regolith>,
    /// The soil under the footpads, derived from `regolith` (`None`: the elastic plane).
    pub soil: Option<Soil>,
    /// The rock tiles, built for the largest abundance of any sample (`None`: no rocks).
    pub rocks: Option<kernels::rocks::Rocks>,
    /// The sample's rock abundance `k` (the median where drawn, until `for_sample`).
    pub rock_abundance: f64,
    /// The rough-terrain tiles (`None`: the bare slope plane).
    pub terrain: Option<Terrain>,
    /// Step whenever a footpad may touch the surface within it: fixed, or with a
    /// `step_control`, the longest such step out of contact (the control sets those in
    /// contact).
    pub step_s: f64,
    /// The contact step's error control (`None`: every contact step is `step_s`).
    pub step_control: Option<StepControl>,
    /// Longest step in free flight, taken only where no footpad can reach the surface.
    pub flight_step_max_s: f64,
    /// End of a sample: what is undecided by then is decided by the rules at `t_max`.
    pub t_max_s: f64,
    /// The outcome rules' thresholds.
    pub thresholds: Thresholds,
    /// Attitude and fall velocity are taken against the surface normal, not the local
    /// vertical (a lander that aligned itself with the surface before release).
    pub attitude_surface: bool,
    /// Height of the lowest footpad above the terrain at the start of a sample.
    pub clearance_m: f64,
    /// Where a sample starts (a descent's start from its drawn descent,
    /// `ControlModel::descent_draw`).
    pub start: crate::scenario::Start,
    /// The control loop and its thrusters, if any.
    pub control: Option<crate::control::ControlModel>,
    /// The parameters each sample draws (`Scenario::sampled`): `for_sample` puts a
    /// sample's values in their place.
    pub sampled: Sampled,
    /// The structural limits (`[limits]`), if any: a summary then says which it broke.
    pub limits: Option<crate::scenario::Limits>,
}

impl Model {
    /// Derives the model of a validated scenario (terrain tiles included).
    #[must_use]
    pub fn new(s: &Scenario) -> Model {
        let tips: Vec<DVec3> = s
            .lander
            .tips_m()
            .into_iter()
            .map(DVec3::from_array)
            .collect();
        let axes: Vec<DVec3> = match &s.damper.strut_axes {
            StrutAxes::All(a) => vec![DVec3::from_array(*a); tips.len()],
            StrutAxes::PerLeg(a) => a.iter().map(|p| DVec3::from_array(*p)).collect(),
        };
        let legs: Vec<Leg> = tips
            .iter()
            .zip(&axes)
            .map(|(t, u)| Leg {
                tip_m: *t,
                strut_axis: *u,
            })
            .collect();
        // The engine's order (the user's numbers in it), and the way back (`Model::legs`).
        let numbers = engine_order(&legs);
        let mut leg_index = vec![0; legs.len()];
        for (i, &k) in numbers.iter().enumerate() {
            leg_index[k] = i;
        }
        let legs: Vec<Leg> = numbers.iter().map(|&k| legs[k]).collect();
        let edges = support_edges(&legs);
        let d = &s.damper;
        let area_m2 = d.area_cm2 * 1e-4;
        let honeycomb = d.enabled.then(|| {
            let mut end = 0.0;
            let stages: Vec<(f64, f64)> = d
                .stages
                .iter()
                .map(|st| {
                    end += st.stroke_m;
                    (end, st.crush_strength_psi * PSI_PA * area_m2)
                })
                .collect();
            let plateau = stages[0].1;
            let (peak_force_n, peak_stroke_m) = if d.pre_crushed {
                (plateau, 0.0)
            } else {
                (plateau * d.initial_peak_factor, d.initial_peak_stroke_m)
            };
            Honeycomb {
                stages,
                peak_force_n,
                peak_stroke_m,
                area_m2,
                initial_peak_factor: (!d.pre_crushed).then_some(d.initial_peak_factor),
            }
        });
        let o = &s.outcome;
        let leg_reach_m = legs.iter().map(|l| l.tip_m.length()).fold(0.0, f64::max);
        let footpad_depth_m = legs.iter().map(|l| -l.tip_m.z).fold(0.0, f64::max);
        let mut model = Model {
            gravity_m_s2: s.gravity_m_s2,
            mass_kg: s.lander.mass_kg,
            inertia_kg_m2: DVec3::from_array(s.lander.inertia_kg_m2),
            legs,
            leg_index,
            edges,
            contact: Contact {
                stiffness_n_per_m: s.surface.stiffness_n_per_m,
                damping_n_s_per_m: s.surface.damping_n_s_per_m,
                friction_coefficient: s.surface.friction_coefficient,
                friction_stiffness_n_per_m: s.surface.friction_stiffness_n_per_m,
                friction_damping_n_s_per_m: s.surface.friction_damping_n_s_per_m,
            },
            honeycomb,
            footpad_area_m2: s.lander.footpad_area_m2,
            regolith: s.surface.regolith,
            soil: s
                .surface
                .regolith
                .map(|r| Soil::of(&r, s.lander.footpad_area_m2, s.gravity_m_s2)),
            rocks: crate::rocks::build(
                &crate::scenario::Rocks {
                    abundance: s.rock_abundance_max(),
                    ..s.surface.rocks.clone()
                },
                s.seed,
            ),
            rock_abundance: s.surface.rocks.abundance,
            // A drawn roughness: the tiles of the largest, scaled to the median here and to
            // each sample's own value by `for_sample`.
            terrain: {
                let largest = s.rms_height_max_m();
                let rough = crate::scenario::Roughness {
                    rms_height_m: largest,
                    ..s.surface.roughness.clone()
                };
                crate::terrain::build(&rough, s.seed).map(|t| {
                    if s.sampled[Parameter::RmsHeightM as usize].is_some() {
                        t.scaled(s.surface.roughness.rms_height_m / largest)
                    } else {
                        t
                    }
                })
            },
            step_s: s.simulation.step_s,
            step_control: s.simulation.tolerance_m_s.map(|tolerance_m_s| StepControl {
                tolerance_m_s,
                step_min_s: s.simulation.step_min_s,
                step_max_s: s.simulation.step_max_s,
            }),
            flight_step_max_s: s.simulation.flight_step_max_s,
            t_max_s: s.simulation.t_max_s,
            thresholds: Thresholds {
                rest_speed_m_s: o.rest_speed_m_s,
                rest_rate_rad_s: o.rest_rate_deg_s.to_radians(),
                hold_time_s: o.hold_time_s,
                bounce_clearance_m: o.bounce_clearance_m,
                diverged_speed_m_s: o.diverged_speed_m_s,
                diverged_rate_rad_s: o.diverged_rate_deg_s.to_radians(),
                diverged_penetration_m: o.diverged_penetration_m,
                early_tipping: o.early_tipping,
                early_sliding: o.early_sliding,
                early_bouncing: o.early_bouncing,
            },
            attitude_surface: s.initial.attitude_reference
                == crate::scenario::AttitudeReference::Surface,
            clearance_m: s.initial.clearance_m,
            start: s.initial.start,
            control: crate::control::ControlModel::of(s, leg_reach_m, footpad_depth_m),
            sampled: s.sampled,
            limits: s.limits,
        };
        // A steady slide is decided early in all lanes of a sweep or in none: where the
        // parameters it depends on are drawn, only if it may be for every draw (the
        // heaviest lander with the most friction on the weakest cartridge).
        if s.sampled.iter().any(Option::is_some) {
            let mut corner = [0.0; PARAMETERS];
            for p in Parameter::ALL {
                corner[p as usize] = match (p, s.sampled[p as usize]) {
                    (_, None) => s.parameter(p),
                    (Parameter::CrushStrengthPsi, Some(d)) => d.support().0,
                    (_, Some(d)) => d.support().1,
                };
            }
            let worst = model.with_parameters(&corner);
            model.thresholds.early_sliding = worst.slides_decidable();
        }
        model
    }

    /// The model of one sample: this one, with the sample's values of the parameters the
    /// scenario draws (`Scenario::sampled`) in their place; this one itself where it draws
    /// none.
    #[must_use]
    pub fn for_sample(&self, sample: &Sample) -> Cow<'_, Model> {
        if self.sampled.iter().all(Option::is_none) {
            Cow::Borrowed(self)
        } else {
            Cow::Owned(self.with_parameters(&sample.parameters))
        }
    }

    /// This model with `values` (indexed by `Parameter`) for the parameters it draws, each
    /// set as `new` sets it from a scenario that fixes it: the same bits.
    fn with_parameters(&self, values: &[f64; PARAMETERS]) -> Model {
        let mut m = self.clone();
        for p in Parameter::ALL {
            if self.sampled[p as usize].is_none() {
                continue;
            }
            let x = values[p as usize];
            match p {
                Parameter::MassKg => m.mass_kg = x,
                Parameter::CgHeightM => {
                    for leg in &mut m.legs {
                        leg.tip_m.z = -x;
                    }
                }
                Parameter::StiffnessNPerM => m.contact.stiffness_n_per_m = x,
                Parameter::DampingNSPerM => m.contact.damping_n_s_per_m = x,
                Parameter::FrictionCoefficient => m.contact.friction_coefficient = x,
                Parameter::CrushStrengthPsi => {
                    if let Some(h) = &mut m.honeycomb {
                        let plateau = x * PSI_PA * h.area_m2;
                        h.stages[0].1 = plateau;
                        h.peak_force_n = h.initial_peak_factor.map_or(plateau, |f| plateau * f);
                    }
                }
                Parameter::RmsHeightM => {
                    let largest = self.sampled[p as usize].map_or(x, |d| d.support().1);
                    if let Some(t) = &mut m.terrain {
                        *t = t.scaled(x / largest);
                    }
                }
                Parameter::FootpadAreaM2 => m.footpad_area_m2 = x,
                Parameter::RockAbundance => m.rock_abundance = x,
                Parameter::GravityMS2 => m.gravity_m_s2 = x,
                Parameter::BekkerKC => set_soil(&mut m, |r| r.bekker_k_c = x),
                Parameter::BekkerKPhi => set_soil(&mut m, |r| r.bekker_k_phi = x),
                Parameter::BekkerN => set_soil(&mut m, |r| r.bekker_n = x),
                Parameter::UnloadingModulusPaPerM => {
                    set_soil(&mut m, |r| r.unloading_modulus_pa_per_m = x);
                }
                Parameter::CohesionPa => set_soil(&mut m, |r| r.cohesion_pa = x),
                Parameter::FrictionAngleDeg => set_soil(&mut m, |r| r.friction_angle_deg = x),
                Parameter::BulkDensityKgM3 => set_soil(&mut m, |r| r.bulk_density_kg_m3 = x),
            }
        }
        m.soil = m
            .regolith
            .map(|r| Soil::of(&r, m.footpad_area_m2, m.gravity_m_s2));
        m
    }

    /// Whether a steady slide may be decided `sliding` early (MODEL.md section 8): on a
    /// plane of the elastic kind (a rough terrain changes under a sliding lander; a sunk
    /// footpad ploughs), and with dampers, if any,
    /// that no leg of a steady slide can crush. A leg then bears at most the settled normal
    /// force, `(1 + SLIDE_FORCE_BAND) m g`, with its friction: below `(1 + mu)` times that.
    #[must_use]
    pub fn slides_decidable(&self) -> bool {
        let band = 1.0 + kernels::outcome::SLIDE_FORCE_BAND;
        let slide_load =
            (1.0 + self.contact.friction_coefficient) * band * self.mass_kg * self.gravity_m_s2;
        let crush_least = self.honeycomb.as_ref().map_or(f64::INFINITY, |h| {
            h.stages.iter().map(|s| s.1).fold(h.peak_force_n, f64::min)
        });
        self.thresholds.early_sliding
            && self.terrain.is_none()
            && self.soil.is_none()
            && self.rocks.is_none()
            && crush_least > slide_load
    }

    /// Height of the highest point of the terrain above the plane (0 for the plane), m: the
    /// terrain's highest node, and the highest rock on it.
    #[must_use]
    pub fn terrain_top_m(&self) -> f64 {
        self.ground_top_m()
            + self
                .rocks
                .as_ref()
                .map_or(0.0, kernels::rocks::Rocks::top_m)
    }

    /// Height of the highest point of the ground above the plane, rocks aside (0 for the
    /// plane), m: the terrain's highest node.
    #[must_use]
    pub fn ground_top_m(&self) -> f64 {
        self.terrain.as_ref().map_or(0.0, |t| t.height_max_m())
    }

    /// The radius of a footpad, `sqrt(A / pi)`, m (its bearing radius on regolith, its
    /// sphere's among rocks).
    #[must_use]
    pub fn pad_radius_m(&self) -> f64 {
        (self.footpad_area_m2 / std::f64::consts::PI).sqrt()
    }

    /// The rocks a footpad of this model meets (`None` without rocks).
    #[must_use]
    pub fn rock_field(&self) -> Option<crate::slope::RockField<'_>> {
        self.rocks.as_ref().map(|rocks| crate::slope::RockField {
            rocks,
            abundance: self.rock_abundance,
            pad_radius_m: self.pad_radius_m(),
        })
    }

    /// Largest distance of a footpad from the CG, m.
    #[must_use]
    pub fn leg_reach_m(&self) -> f64 {
        self.legs
            .iter()
            .map(|l| l.tip_m.length())
            .fold(0.0, f64::max)
    }
}

/// The engine's order of `legs` (given in the user's order): the user's numbers, sorted by
/// the footpad's azimuth about Z_B, `atan2(y, x)` in (-180, 180] deg, then by its
/// coordinates and its strut axis, so that the order depends on the legs alone and not on
/// how they are listed (legs equal in all of these are interchangeable).
fn engine_order(legs: &[Leg]) -> Vec<usize> {
    let key = |l: &Leg| {
        [
            libm::atan2(l.tip_m.y, l.tip_m.x),
            l.tip_m.x,
            l.tip_m.y,
            l.tip_m.z,
            l.strut_axis.x,
            l.strut_axis.y,
            l.strut_axis.z,
        ]
    };
    let mut order: Vec<usize> = (0..legs.len()).collect();
    order.sort_by(|&a, &b| {
        let (a, b) = (key(&legs[a]), key(&legs[b]));
        a.iter()
            .zip(&b)
            .map(|(x, y)| x.total_cmp(y))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    order
}

/// The edges of the support polygon of `legs`: the convex hull of their footpads seen along
/// Z_B (`stability::support_hull`), counter-clockwise, each edge a pair of indices into
/// `legs`, starting at the lowest index on the hull; none for fewer than three footpads
/// off one line.
fn support_edges(legs: &[Leg]) -> Vec<[usize; 2]> {
    let tips: Vec<[f64; 3]> = legs.iter().map(|l| l.tip_m.to_array()).collect();
    let mut hull = crate::stability::support_hull(&tips);
    if hull.len() < 3 {
        return Vec::new();
    }
    let first = (0..hull.len()).min_by_key(|&i| hull[i]).unwrap_or(0);
    hull.rotate_left(first);
    (0..hull.len())
        .map(|i| [hull[i], hull[(i + 1) % hull.len()]])
        .collect()
}

/// Sets a value of the model's regolith (there is one where a sample draws its values).
fn set_soil(m: &mut Model, set: impl FnOnce(&mut crate::scenario::Regolith)) {
    if let Some(r) = &mut m.regolith {
        set(r);
    }
}
