//! The scenario: every parameter of MODEL.md and the distribution of every sampled input,
//! read from TOML and validated before any work starts.
//!
//! Every key is optional; a missing key takes the default of MODEL.md. The default scenario
//! is the commented file `default.toml` beside this module, which `touchdown scenario`
//! prints and which a test proves equal to `Scenario::default()`.

mod reader;

use kernels::isa::Precision;
use reader::Reader;
use std::fmt;
use toml::Value;

/// The commented default scenario, as `touchdown scenario` prints it.
pub const DEFAULT_TOML: &str = include_str!("default.toml");

/// One pound per square inch in pascal.
pub const PSI_PA: f64 = 6_894.757_293_168_361;

/// A scenario that failed to read or validate. Every variant names what is wrong.
#[derive(Debug, Clone, PartialEq)]
pub enum ScenarioError {
    /// The file could not be read.
    Io { path: String, message: String },
    /// The text is not TOML.
    Syntax(String),
    /// A key with a value that is not allowed.
    Invalid {
        key: String,
        value: String,
        allowed: String,
    },
    /// A key that the scenario does not have.
    UnknownKey {
        key: String,
        hint: String,
        known: String,
    },
}

impl fmt::Display for ScenarioError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ScenarioError::Io { path, message } => {
                write!(f, "cannot read scenario file {path}: {message}")
            }
            ScenarioError::Syntax(m) => write!(f, "scenario is not valid TOML: {m}"),
            ScenarioError::Invalid {
                key,
                value,
                allowed,
            } => write!(
                f,
                "scenario key `{key}` = {value} is not allowed: expected {allowed}"
            ),
            ScenarioError::UnknownKey { key, hint, known } => write!(
                f,
                "scenario key `{key}` is unknown{hint}; this table knows: {known}"
            ),
        }
    }
}

impl std::error::Error for ScenarioError {}

/// How an input is drawn for each sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Dist {
    /// Always this value.
    Fixed(f64),
    /// Uniform on `[min, max]`.
    Uniform { min: f64, max: f64 },
    /// Normal, truncated to `[min, max]` (infinite bounds: not truncated).
    Normal {
        mean: f64,
        sd: f64,
        min: f64,
        max: f64,
    },
    /// `count` evenly spaced values from `min` to `max`; several grid inputs form their
    /// cartesian product, the last one varying fastest with the sample index.
    Grid { min: f64, max: f64, count: u64 },
}

impl Dist {
    /// The smallest and largest value the distribution can produce.
    #[must_use]
    pub fn support(&self) -> (f64, f64) {
        match *self {
            Dist::Fixed(x) => (x, x),
            Dist::Uniform { min, max } | Dist::Grid { min, max, .. } => (min, max),
            Dist::Normal { min, max, .. } => (min, max),
        }
    }
}

/// The inputs that every sample draws, in the order they are drawn and written.
/// `T` is `Dist` in a scenario and `f64` in a sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inputs<T> {
    /// Slope angle from horizontal, deg.
    pub slope_deg: T,
    /// Downhill direction, measured in the X_I Y_I plane from X_I (the lander's yaw is 0), deg.
    pub downhill_azimuth_deg: T,
    /// Height of the ballistic fall before touchdown, m (touchdown speed `sqrt(2 g0 h)`).
    pub release_height_m: T,
    /// Residual velocity error along X of the attitude reference frame, m/s.
    pub velocity_error_x_m_s: T,
    /// Residual velocity error along Y, m/s.
    pub velocity_error_y_m_s: T,
    /// Residual velocity error along Z, m/s.
    pub velocity_error_z_m_s: T,
    /// Roll error `phi`, deg.
    pub roll_deg: T,
    /// Pitch error `theta`, deg.
    pub pitch_deg: T,
    /// Yaw `psi`, deg.
    pub yaw_deg: T,
    /// Residual body rate about X_B, deg/s.
    pub rate_x_deg_s: T,
    /// Residual body rate about Y_B, deg/s.
    pub rate_y_deg_s: T,
    /// Residual body rate about Z_B, deg/s.
    pub rate_z_deg_s: T,
}

/// Names and units of the sampled inputs, in drawing order.
pub const INPUT_FIELDS: [(&str, &str); 12] = [
    ("slope_deg", "deg"),
    ("downhill_azimuth_deg", "deg"),
    ("release_height_m", "m"),
    ("velocity_error_x_m_s", "m/s"),
    ("velocity_error_y_m_s", "m/s"),
    ("velocity_error_z_m_s", "m/s"),
    ("roll_deg", "deg"),
    ("pitch_deg", "deg"),
    ("yaw_deg", "deg"),
    ("rate_x_deg_s", "deg/s"),
    ("rate_y_deg_s", "deg/s"),
    ("rate_z_deg_s", "deg/s"),
];

impl<T: Copy> Inputs<T> {
    /// The inputs in the order of `INPUT_FIELDS`.
    #[must_use]
    pub fn to_array(&self) -> [T; 12] {
        [
            self.slope_deg,
            self.downhill_azimuth_deg,
            self.release_height_m,
            self.velocity_error_x_m_s,
            self.velocity_error_y_m_s,
            self.velocity_error_z_m_s,
            self.roll_deg,
            self.pitch_deg,
            self.yaw_deg,
            self.rate_x_deg_s,
            self.rate_y_deg_s,
            self.rate_z_deg_s,
        ]
    }

    /// The inverse of `to_array`.
    #[must_use]
    pub fn from_array(a: [T; 12]) -> Self {
        Inputs {
            slope_deg: a[0],
            downhill_azimuth_deg: a[1],
            release_height_m: a[2],
            velocity_error_x_m_s: a[3],
            velocity_error_y_m_s: a[4],
            velocity_error_z_m_s: a[5],
            roll_deg: a[6],
            pitch_deg: a[7],
            yaw_deg: a[8],
            rate_x_deg_s: a[9],
            rate_y_deg_s: a[10],
            rate_z_deg_s: a[11],
        }
    }
}

/// Where the lander's legs are.
#[derive(Debug, Clone, PartialEq)]
pub enum Geometry {
    /// `legs` footpads evenly spaced on a circle of `footpad_radius_m` around Z_B,
    /// `cg_height_m` below the CG, the first at `first_leg_azimuth_deg` from X_B.
    Regular {
        legs: usize,
        footpad_radius_m: f64,
        cg_height_m: f64,
        first_leg_azimuth_deg: f64,
    },
    /// Explicit footpad positions in B, m.
    Tips(Vec<[f64; 3]>),
}

/// The lander (MODEL.md section 3).
#[derive(Debug, Clone, PartialEq)]
pub struct Lander {
    pub mass_kg: f64,
    /// Principal moments of inertia about X_B, Y_B, Z_B.
    pub inertia_kg_m2: [f64; 3],
    pub geometry: Geometry,
}

impl Lander {
    /// The footpads in B (CG at the origin) with the dampers uncrushed, m.
    #[must_use]
    pub fn tips_m(&self) -> Vec<[f64; 3]> {
        match &self.geometry {
            Geometry::Regular {
                legs,
                footpad_radius_m,
                cg_height_m,
                first_leg_azimuth_deg,
            } => (0..*legs)
                .map(|i| {
                    let az = first_leg_azimuth_deg.to_radians()
                        + std::f64::consts::TAU * i as f64 / *legs as f64;
                    [
                        footpad_radius_m * libm::cos(az),
                        footpad_radius_m * libm::sin(az),
                        -cg_height_m,
                    ]
                })
                .collect(),
            Geometry::Tips(t) => t.clone(),
        }
    }
}

/// Gaussian-smoothed random terrain (MODEL.md section 4).
#[derive(Debug, Clone, PartialEq)]
pub struct Roughness {
    /// RMS height of the field; 0 means a flat plane.
    pub rms_height_m: f64,
    pub node_spacing_m: f64,
    /// Standard deviation of the Gaussian smoothing kernel.
    pub smoothing_length_m: f64,
    /// Side of one square, periodic tile.
    pub tile_size_m: f64,
    /// Number of precomputed tiles; each sample draws one and a random offset.
    pub tiles: usize,
}

/// The surface and the contact law (MODEL.md sections 4, 5, 10).
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    pub stiffness_n_per_m: f64,
    pub damping_n_s_per_m: f64,
    pub friction_coefficient: f64,
    /// Stiffness of the stick-slip tangential spring.
    pub friction_stiffness_n_per_m: f64,
    /// Damping of the stick-slip tangential spring.
    pub friction_damping_n_s_per_m: f64,
    pub roughness: Roughness,
}

/// One stage of a crushable cartridge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stage {
    pub stroke_m: f64,
    pub crush_strength_psi: f64,
}

/// Crushable honeycomb dampers, one per leg (MODEL.md section 6).
#[derive(Debug, Clone, PartialEq)]
pub struct Damper {
    pub enabled: bool,
    /// Cartridge cross-section.
    pub area_cm2: f64,
    /// Stages from the first crushed to the last; one stage for a plain cartridge.
    pub stages: Vec<Stage>,
    pub pre_crushed: bool,
    /// Crush force over the first `initial_peak_stroke_m` of a cartridge that is not
    /// pre-crushed, as a multiple of the first stage's plateau.
    pub initial_peak_factor: f64,
    pub initial_peak_stroke_m: f64,
    /// Strut axis per leg (unit vector in B, from hip to footpad).
    pub strut_axes: StrutAxes,
}

/// The strut axis of every leg, or one per leg.
#[derive(Debug, Clone, PartialEq)]
pub enum StrutAxes {
    All([f64; 3]),
    PerLeg(Vec<[f64; 3]>),
}

/// Against what the attitude errors and the fall velocity are taken (MODEL.md section 8).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AttitudeReference {
    /// `Z_B` up along `Z_I`: on a slope the lander meets the surface tilted.
    Vertical,
    /// `Z_B` along the surface normal: a lander that aligned itself before release.
    Surface,
}

/// The initial state besides the sampled inputs.
#[derive(Debug, Clone, PartialEq)]
pub struct Initial {
    pub attitude_reference: AttitudeReference,
    /// Height of the lowest footpad above the surface at the start, m.
    pub clearance_m: f64,
}

/// Time stepping.
#[derive(Debug, Clone, PartialEq)]
pub struct Simulation {
    /// Step whenever a leg may touch the surface.
    pub step_s: f64,
    /// Longest step in free flight, taken only where no leg can reach the surface in it.
    pub flight_step_max_s: f64,
    pub t_max_s: f64,
    /// The lanes' precision: f64 (eight landers per lane value) or f32 (sixteen, faster;
    /// the shares a sweep reports agree with f64's within their sampling error, single
    /// samples near a decision threshold may end otherwise).
    pub precision: Precision,
}

/// Thresholds of the outcome classification (MODEL.md section 8).
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// CG speed below which the lander may count as at rest.
    pub rest_speed_m_s: f64,
    /// Body rate below which the lander may count as at rest.
    pub rest_rate_deg_s: f64,
    /// How long the lander must stay at rest, upright and statically stable to be `stable`.
    pub hold_time_s: f64,
    /// Height the lowest footpad must reach after a lift-off for it to count as a bounce.
    pub bounce_clearance_m: f64,
    pub diverged_speed_m_s: f64,
    pub diverged_rate_deg_s: f64,
    pub diverged_penetration_m: f64,
    /// Decide `tipped` at the point of no return (MODEL.md section 8) instead of only when
    /// the tilt passes 90 deg.
    pub early_tipping: bool,
    /// Decide `sliding` once the lander slides steadily down a plane steeper than the
    /// friction angle (MODEL.md section 8) instead of running on to t_max.
    pub early_sliding: bool,
    /// Decide `bouncing` once the lander flies clear and can neither come back to the
    /// surface nor turn past 90 deg before t_max.
    pub early_bouncing: bool,
}

/// A complete, validated scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct Scenario {
    pub seed: u64,
    /// Samples a sweep runs when the command line does not say.
    pub samples: u64,
    pub gravity_m_s2: f64,
    pub lander: Lander,
    pub surface: Surface,
    pub damper: Damper,
    pub inputs: Inputs<Dist>,
    pub initial: Initial,
    pub simulation: Simulation,
    pub outcome: Outcome,
}

impl Default for Scenario {
    fn default() -> Self {
        let normal = |sd| Dist::Normal {
            mean: 0.0,
            sd,
            min: f64::NEG_INFINITY,
            max: f64::INFINITY,
        };
        Scenario {
            seed: 1,
            samples: 1000,
            gravity_m_s2: 0.0168,
            lander: Lander {
                mass_kg: 100.0,
                inertia_kg_m2: [18.0, 18.0, 15.0],
                geometry: Geometry::Regular {
                    legs: 4,
                    footpad_radius_m: 0.6,
                    cg_height_m: 0.428936,
                    first_leg_azimuth_deg: 45.0,
                },
            },
            surface: Surface {
                stiffness_n_per_m: 5.0e4,
                damping_n_s_per_m: 1.1e3,
                friction_coefficient: 0.6,
                friction_stiffness_n_per_m: 5.0e4,
                friction_damping_n_s_per_m: 1.1e3,
                roughness: Roughness {
                    rms_height_m: 0.0,
                    node_spacing_m: 0.05,
                    smoothing_length_m: 0.15,
                    tile_size_m: 6.4,
                    tiles: 8,
                },
            },
            damper: Damper {
                enabled: false,
                area_cm2: 4.5,
                stages: vec![Stage {
                    stroke_m: 0.05,
                    crush_strength_psi: 50.0,
                }],
                pre_crushed: true,
                initial_peak_factor: 1.75,
                initial_peak_stroke_m: 0.002,
                strut_axes: StrutAxes::All([0.0, 0.0, -1.0]),
            },
            inputs: Inputs {
                slope_deg: Dist::Uniform {
                    min: 0.0,
                    max: 45.0,
                },
                downhill_azimuth_deg: Dist::Uniform {
                    min: 0.0,
                    max: 360.0,
                },
                release_height_m: Dist::Uniform {
                    min: 5.0,
                    max: 10.0,
                },
                velocity_error_x_m_s: normal(0.05),
                velocity_error_y_m_s: normal(0.05),
                velocity_error_z_m_s: normal(0.05),
                roll_deg: normal(2.0),
                pitch_deg: normal(2.0),
                yaw_deg: Dist::Fixed(0.0),
                rate_x_deg_s: normal(0.5),
                rate_y_deg_s: normal(0.5),
                rate_z_deg_s: normal(0.5),
            },
            initial: Initial {
                attitude_reference: AttitudeReference::Vertical,
                clearance_m: 0.001,
            },
            simulation: Simulation {
                step_s: 0.001,
                flight_step_max_s: 0.05,
                precision: Precision::F64,
                t_max_s: 120.0,
            },
            outcome: Outcome {
                rest_speed_m_s: 0.005,
                rest_rate_deg_s: 0.5,
                hold_time_s: 2.0,
                bounce_clearance_m: 0.001,
                diverged_speed_m_s: 100.0,
                diverged_rate_deg_s: 3600.0,
                diverged_penetration_m: 0.5,
                early_tipping: true,
                early_sliding: true,
                early_bouncing: true,
            },
        }
    }
}

/// The scenario text `text` with its top-level `seed` set to `seed` (replaced where the text
/// has one, added before its first key where not), so that a file stores the scenario that
/// ran, seed included. Comments and layout stay. The text must read as a scenario.
#[must_use]
pub fn with_seed(text: &str, seed: u64) -> String {
    if Scenario::from_toml(text).is_ok_and(|s| s.seed == seed) {
        return text.to_string();
    }
    let lines: Vec<&str> = text.lines().collect();
    let top_level = lines
        .iter()
        .position(|l| l.trim_start().starts_with('['))
        .unwrap_or(lines.len());
    let is_seed = |l: &str| {
        l.trim_start()
            .strip_prefix("seed")
            .is_some_and(|rest| rest.trim_start().starts_with('='))
    };
    let line = format!("seed = {seed}");
    let mut out: Vec<String> = lines.iter().map(ToString::to_string).collect();
    match lines[..top_level].iter().position(|l| is_seed(l)) {
        Some(i) => out[i] = line,
        None => {
            let first_key = lines
                .iter()
                .position(|l| {
                    let t = l.trim();
                    !t.is_empty() && !t.starts_with('#')
                })
                .unwrap_or(lines.len());
            out.insert(first_key, line);
        }
    }
    let mut edited = out.join("\n");
    if text.ends_with('\n') {
        edited.push('\n');
    }
    edited
}

impl Scenario {
    /// Reads a scenario file.
    pub fn from_file(path: &std::path::Path) -> Result<Scenario, ScenarioError> {
        let text = std::fs::read_to_string(path).map_err(|e| ScenarioError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        Scenario::from_toml(&text)
    }

    /// Reads and validates a scenario from TOML text; missing keys take their defaults.
    pub fn from_toml(text: &str) -> Result<Scenario, ScenarioError> {
        let table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
            ScenarioError::Syntax(e.to_string().trim().to_string())
        })?;
        let d = Scenario::default();
        let mut top = Reader::new("", table);
        let seed = top.integer("seed", d.seed as i64, 0, i64::MAX)? as u64;
        let samples = top.integer("samples", d.samples as i64, 1, i64::MAX)? as u64;
        let gravity_m_s2 = top.non_negative("gravity_m_s2", d.gravity_m_s2)?;
        let lander = read_lander(&mut top, &d.lander)?;
        let surface = read_surface(&mut top, &d.surface)?;
        let damper = read_damper(&mut top, &d.damper)?;
        let inputs = read_inputs(&mut top, &d.inputs)?;
        let initial = read_initial(&mut top, &d.initial)?;
        let simulation = read_simulation(&mut top, &d.simulation)?;
        let outcome = read_outcome(&mut top, &d.outcome)?;
        top.finish()?;
        let s = Scenario {
            seed,
            samples,
            gravity_m_s2,
            lander,
            surface,
            damper,
            inputs,
            initial,
            simulation,
            outcome,
        };
        s.check_leg_counts()?;
        s.check_can_land()?;
        Ok(s)
    }

    /// Number of legs of the lander.
    #[must_use]
    pub fn leg_count(&self) -> usize {
        match &self.lander.geometry {
            Geometry::Regular { legs, .. } => *legs,
            Geometry::Tips(t) => t.len(),
        }
    }

    /// Refuses set-ups that defeat themselves: a lander that cannot stand on its legs, dampers
    /// that can never stroke, a hold time no run can reach, no gravity, or a run too short
    /// for the lander to reach the surface.
    fn check_can_land(&self) -> Result<(), ScenarioError> {
        let invalid = |key: &str, value: String, allowed: String| ScenarioError::Invalid {
            key: key.to_string(),
            value,
            allowed,
        };
        let show = |v: [f64; 3]| format!("[{}, {}, {}]", v[0], v[1], v[2]);
        let tips = self.lander.tips_m();
        let tips_key = match self.lander.geometry {
            Geometry::Regular { .. } => "lander.cg_height_m",
            Geometry::Tips(_) => "lander.leg_tips_m",
        };
        if let Some((k, t)) = tips.iter().enumerate().find(|(_, t)| t[2] >= 0.0) {
            return Err(invalid(
                tips_key,
                format!("footpad {k} at {}", show(*t)),
                "every footpad below the CG (z < 0 in B, the CG at the origin): a lander \
                 cannot stand on footpads at or above its CG"
                    .into(),
            ));
        }
        let hull = crate::stability::support_polygon(&tips);
        let area: f64 = (0..hull.len())
            .map(|i| {
                let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
                0.5 * (a[0] * b[1] - a[1] * b[0])
            })
            .sum();
        let size = tips.iter().map(|t| t[0].hypot(t[1])).fold(0.0, f64::max);
        if hull.len() < 3 || area <= 1e-9 * size * size {
            return Err(invalid(
                tips_key,
                format!("{} footpads", tips.len()),
                "at least three footpads not on one line (seen along Z_B): otherwise the \
                 support polygon has no area and the lander cannot stand"
                    .into(),
            ));
        }
        if crate::stability::static_limit_deg(&tips, 0.0).is_none() {
            return Err(invalid(
                tips_key,
                format!("{} footpads", tips.len()),
                "footpads around the CG: the CG (the origin of B) must be above the inside of \
                 their support polygon, or the lander falls over even on level ground"
                    .into(),
            ));
        }
        if self.damper.enabled {
            let axes: Vec<[f64; 3]> = match &self.damper.strut_axes {
                StrutAxes::All(a) => vec![*a],
                StrutAxes::PerLeg(a) => a.clone(),
            };
            let limit = -kernels::honeycomb::MIN_STRUT_NORMAL;
            if let Some(a) = axes.iter().find(|a| a[2] >= limit) {
                return Err(invalid(
                    "damper.strut_axis",
                    show(*a),
                    format!(
                        "struts that point down, from the hip to the footpad (Z component \
                         below {limit} in B): along this one the load of a lander standing on \
                         its legs never compresses the cartridge, so the dampers would never \
                         stroke"
                    ),
                ));
            }
        }
        if self.outcome.hold_time_s > self.simulation.t_max_s {
            return Err(invalid(
                "outcome.hold_time_s",
                format!("{} s", self.outcome.hold_time_s),
                format!(
                    "at most simulation.t_max_s = {} s: no lander can be held at rest longer \
                     than the run lasts, so none could be stable",
                    self.simulation.t_max_s
                ),
            ));
        }
        if self.gravity_m_s2 <= 0.0 {
            return Err(invalid(
                "gravity_m_s2",
                self.gravity_m_s2.to_string(),
                "a gravity greater than 0: without it no lander comes to rest on its legs or \
                 tips over (the default is 0.0168 m/s^2)"
                    .into(),
            ));
        }
        // The nominal touchdown (the highest release, no velocity error) must reach the
        // surface from its starting gap before t_max: else (nearly) no sample ever touches.
        let height = self.inputs.release_height_m.support().1;
        let v = (2.0 * self.gravity_m_s2 * height).sqrt();
        let gap = self.initial.clearance_m;
        let reach_s = 2.0 * gap / (v + (v * v + 2.0 * self.gravity_m_s2 * gap).sqrt());
        if reach_s > self.simulation.t_max_s {
            return Err(invalid(
                "simulation.t_max_s",
                format!("{} s", self.simulation.t_max_s),
                format!(
                    "a run long enough to reach the surface: from initial.clearance_m = {gap} m \
                     at {v:.4} m/s (released from inputs.release_height_m up to {height} m in \
                     gravity_m_s2 = {g} m/s^2) the lander needs {reach_s:.3e} s, so no sample \
                     would ever touch it",
                    g = self.gravity_m_s2
                ),
            ));
        }
        Ok(())
    }

    fn check_leg_counts(&self) -> Result<(), ScenarioError> {
        if let StrutAxes::PerLeg(axes) = &self.damper.strut_axes
            && axes.len() != self.leg_count()
        {
            return Err(ScenarioError::Invalid {
                key: "damper.strut_axis".into(),
                value: format!("{} axes", axes.len()),
                allowed: format!(
                    "one axis for all legs or one per leg ({} legs)",
                    self.leg_count()
                ),
            });
        }
        Ok(())
    }
}

fn read_lander(top: &mut Reader, d: &Lander) -> Result<Lander, ScenarioError> {
    let Some(mut r) = top.table("lander")? else {
        return Ok(d.clone());
    };
    let mass_kg = r.positive("mass_kg", d.mass_kg)?;
    let inertia_kg_m2 = match r.take("inertia_kg_m2") {
        None => d.inertia_kg_m2,
        Some(v) => {
            let i = r.vec3("inertia_kg_m2", &v)?;
            if i.iter().any(|x| *x <= 0.0) {
                return Err(r.error(
                    "inertia_kg_m2",
                    &v,
                    "three principal moments greater than 0",
                ));
            }
            // A rigid body's principal moments obey the triangle inequality; equality is a
            // flat plate. The relative slack absorbs rounding in values typed from decimals.
            for k in 0..3 {
                let (a, b, c) = (i[k], i[(k + 1) % 3], i[(k + 2) % 3]);
                if a > (b + c) * (1.0 + 1e-12) {
                    return Err(r.error(
                        "inertia_kg_m2",
                        &v,
                        "principal moments of a rigid body: each at most the sum of the other two (triangle inequality)",
                    ));
                }
            }
            i
        }
    };
    let Geometry::Regular {
        legs: d_legs,
        footpad_radius_m: d_radius,
        cg_height_m: d_height,
        first_leg_azimuth_deg: d_az,
    } = d.geometry
    else {
        unreachable!("the default lander is regular")
    };
    let regular_keys = [
        "legs",
        "footpad_radius_m",
        "cg_height_m",
        "first_leg_azimuth_deg",
    ];
    let geometry = match r.take("leg_tips_m") {
        Some(v) => {
            if let Some(k) = regular_keys.iter().find(|k| r.has(k)) {
                return Err(r.error(
                    "leg_tips_m",
                    &v,
                    &format!("either `leg_tips_m` or `{k}` and its fellows, not both"),
                ));
            }
            let allowed = "a non-empty array of footpad positions [[x, y, z], ...] in m";
            let Value::Array(a) = &v else {
                return Err(r.error("leg_tips_m", &v, allowed));
            };
            if a.is_empty() {
                return Err(r.error("leg_tips_m", &v, allowed));
            }
            let tips = a
                .iter()
                .map(|t| r.vec3("leg_tips_m", t))
                .collect::<Result<Vec<_>, _>>()?;
            Geometry::Tips(tips)
        }
        None => Geometry::Regular {
            legs: r.integer("legs", d_legs as i64, 3, 64)? as usize,
            footpad_radius_m: r.positive("footpad_radius_m", d_radius)?,
            cg_height_m: r.positive("cg_height_m", d_height)?,
            first_leg_azimuth_deg: r.f64("first_leg_azimuth_deg", d_az)?,
        },
    };
    r.finish()?;
    Ok(Lander {
        mass_kg,
        inertia_kg_m2,
        geometry,
    })
}

fn read_surface(top: &mut Reader, d: &Surface) -> Result<Surface, ScenarioError> {
    let Some(mut r) = top.table("surface")? else {
        return Ok(d.clone());
    };
    let stiffness_n_per_m = r.positive("stiffness_n_per_m", d.stiffness_n_per_m)?;
    let damping_n_s_per_m = r.non_negative("damping_n_s_per_m", d.damping_n_s_per_m)?;
    let friction_coefficient = r.non_negative("friction_coefficient", d.friction_coefficient)?;
    let friction_stiffness_n_per_m =
        r.positive("friction_stiffness_n_per_m", d.friction_stiffness_n_per_m)?;
    let friction_damping_n_s_per_m =
        r.non_negative("friction_damping_n_s_per_m", d.friction_damping_n_s_per_m)?;
    let dr = &d.roughness;
    let roughness = match r.table("roughness")? {
        None => dr.clone(),
        Some(mut t) => {
            let rms_height_m = t.non_negative("rms_height_m", dr.rms_height_m)?;
            let node_spacing_m = t.positive("node_spacing_m", dr.node_spacing_m)?;
            let smoothing_length_m = t.non_negative("smoothing_length_m", dr.smoothing_length_m)?;
            let tile_size_m = t.f64_where(
                "tile_size_m",
                dr.tile_size_m,
                &format!(
                    "a tile of 4 to 4096 nodes per side at node_spacing_m = {node_spacing_m} m"
                ),
                |x| (4.0..=4096.0).contains(&(x / node_spacing_m).round()),
            )?;
            let tiles = t.integer("tiles", dr.tiles as i64, 1, 1024)? as usize;
            let nodes = (tile_size_m / node_spacing_m).round();
            if nodes * nodes * tiles as f64 > 64.0e6 {
                return Err(ScenarioError::Invalid {
                    key: "surface.roughness.tiles".into(),
                    value: tiles.to_string(),
                    allowed: format!(
                        "at most 64 million terrain nodes in all ({nodes} x {nodes} per tile)"
                    ),
                });
            }
            t.finish()?;
            Roughness {
                rms_height_m,
                node_spacing_m,
                smoothing_length_m,
                tile_size_m,
                tiles,
            }
        }
    };
    r.finish()?;
    Ok(Surface {
        stiffness_n_per_m,
        damping_n_s_per_m,
        friction_coefficient,
        friction_stiffness_n_per_m,
        friction_damping_n_s_per_m,
        roughness,
    })
}

fn read_damper(top: &mut Reader, d: &Damper) -> Result<Damper, ScenarioError> {
    let Some(mut r) = top.table("damper")? else {
        return Ok(d.clone());
    };
    let enabled = r.bool("enabled", d.enabled)?;
    let area_cm2 = r.positive("area_cm2", d.area_cm2)?;
    let stages = match r.take("stages") {
        Some(v) => {
            if let Some(k) = ["crush_strength_psi", "usable_stroke_m"]
                .iter()
                .find(|k| r.has(k))
            {
                return Err(r.error("stages", &v, &format!("either `stages` or `{k}`, not both")));
            }
            let allowed = "a non-empty array of { stroke_m = ..., crush_strength_psi = ... }";
            let Value::Array(a) = v.clone() else {
                return Err(r.error("stages", &v, allowed));
            };
            if a.is_empty() {
                return Err(r.error("stages", &v, allowed));
            }
            let mut stages = Vec::new();
            for (i, s) in a.into_iter().enumerate() {
                let Value::Table(t) = s else {
                    return Err(r.error("stages", &v, allowed));
                };
                let mut t = Reader::new(&format!("{}[{i}]", r.key_path("stages")), t);
                let stroke_m = t.positive("stroke_m", f64::NAN)?;
                let crush_strength_psi = t.positive("crush_strength_psi", f64::NAN)?;
                if stroke_m.is_nan() || crush_strength_psi.is_nan() {
                    return Err(r.error(
                        "stages",
                        &v,
                        "every stage to give both stroke_m and crush_strength_psi",
                    ));
                }
                t.finish()?;
                stages.push(Stage {
                    stroke_m,
                    crush_strength_psi,
                });
            }
            stages
        }
        None => vec![Stage {
            crush_strength_psi: r.positive("crush_strength_psi", d.stages[0].crush_strength_psi)?,
            stroke_m: r.positive("usable_stroke_m", d.stages[0].stroke_m)?,
        }],
    };
    let pre_crushed = r.bool("pre_crushed", d.pre_crushed)?;
    let initial_peak_factor = r.f64_where(
        "initial_peak_factor",
        d.initial_peak_factor,
        "a number of at least 1 (multiple of the plateau)",
        |x| x >= 1.0,
    )?;
    let initial_peak_stroke_m = r.positive("initial_peak_stroke_m", d.initial_peak_stroke_m)?;
    let strut_axes = match r.take("strut_axis") {
        None => d.strut_axes.clone(),
        Some(v) => {
            let unit = |a: [f64; 3]| {
                let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
                (n > 1e-9).then(|| [a[0] / n, a[1] / n, a[2] / n])
            };
            let allowed = "a non-zero vector [x, y, z] in B, or one per leg [[x, y, z], ...]";
            match &v {
                Value::Array(a) if a.iter().all(|x| matches!(x, Value::Array(_))) => {
                    let mut axes = Vec::new();
                    for x in a {
                        let u = unit(r.vec3("strut_axis", x)?)
                            .ok_or_else(|| r.error("strut_axis", &v, allowed))?;
                        axes.push(u);
                    }
                    StrutAxes::PerLeg(axes)
                }
                _ => StrutAxes::All(
                    unit(r.vec3("strut_axis", &v)?)
                        .ok_or_else(|| r.error("strut_axis", &v, allowed))?,
                ),
            }
        }
    };
    r.finish()?;
    Ok(Damper {
        enabled,
        area_cm2,
        stages,
        pre_crushed,
        initial_peak_factor,
        initial_peak_stroke_m,
        strut_axes,
    })
}

/// The range an input must stay in, for validation.
#[derive(Clone, Copy)]
struct Range {
    min: f64,
    max: f64,
    max_open: bool,
    text: &'static str,
}

impl Range {
    fn holds(&self, x: f64) -> bool {
        x >= self.min && (x < self.max || (!self.max_open && x <= self.max))
    }
}

const ANY: Range = Range {
    min: f64::NEG_INFINITY,
    max: f64::INFINITY,
    max_open: false,
    text: "any finite value",
};

fn read_inputs(top: &mut Reader, d: &Inputs<Dist>) -> Result<Inputs<Dist>, ScenarioError> {
    let Some(mut r) = top.table("inputs")? else {
        return Ok(*d);
    };
    let ranges = [
        Range {
            min: 0.0,
            max: 90.0,
            max_open: true,
            text: "values from 0 up to, not including, 90 deg",
        },
        ANY,
        Range {
            min: 0.0,
            max: f64::INFINITY,
            max_open: false,
            text: "values of at least 0 m",
        },
        ANY,
        ANY,
        ANY,
        ANY,
        ANY,
        ANY,
        ANY,
        ANY,
        ANY,
    ];
    let defaults = d.to_array();
    let mut out = defaults;
    for (i, (name, _)) in INPUT_FIELDS.iter().enumerate() {
        if let Some(v) = r.take(name) {
            out[i] = read_dist(&r, name, &v, &ranges[i])?;
        }
    }
    r.finish()?;
    Ok(Inputs::from_array(out))
}

/// Reads a number or a `{ dist = ..., ... }` table.
fn read_dist(r: &Reader, key: &str, v: &Value, range: &Range) -> Result<Dist, ScenarioError> {
    let allowed_forms = "a number, or { dist = \"fixed\", value = x }, { dist = \"uniform\", min = a, max = b }, \
        { dist = \"normal\", mean = m, sd = s } with optional min and max to truncate it, \
        or { dist = \"grid\", min = a, max = b, count = n }";
    let dist = match v {
        Value::Float(_) | Value::Integer(_) => Dist::Fixed(r.number(key, v)?),
        Value::Table(t) => {
            let mut t = Reader::new(&r.key_path(key), t.clone());
            let kind = t.word("dist", "", &["fixed", "uniform", "normal", "grid"])?;
            let need = |t: &mut Reader, k: &'static str| -> Result<f64, ScenarioError> {
                if !t.has(k) {
                    return Err(r.error(key, v, &format!("`{k}` in a {kind:?} distribution")));
                }
                t.f64(k, 0.0)
            };
            let dist = match kind {
                "fixed" => Dist::Fixed(need(&mut t, "value")?),
                "uniform" => {
                    let (min, max) = (need(&mut t, "min")?, need(&mut t, "max")?);
                    if min > max {
                        return Err(r.error(key, v, "min at most max"));
                    }
                    Dist::Uniform { min, max }
                }
                "normal" => {
                    let mean = need(&mut t, "mean")?;
                    let sd = need(&mut t, "sd")?;
                    if sd <= 0.0 {
                        return Err(r.error(key, v, "sd greater than 0"));
                    }
                    let min = t.f64("min", f64::NEG_INFINITY)?;
                    let max = t.f64("max", f64::INFINITY)?;
                    if min >= max {
                        return Err(r.error(key, v, "min below max"));
                    }
                    // Truncation by rejection: the interval must hold a fair share of the
                    // normal's mass, or drawing would take too long.
                    let phi =
                        |x: f64| 0.5 * libm::erfc(-(x - mean) / (sd * std::f64::consts::SQRT_2));
                    if phi(max) - phi(min) < 0.01 {
                        return Err(r.error(
                            key,
                            v,
                            "a truncation interval [min, max] that holds at least 1 % of the normal's probability",
                        ));
                    }
                    Dist::Normal { mean, sd, min, max }
                }
                "grid" => {
                    let (min, max) = (need(&mut t, "min")?, need(&mut t, "max")?);
                    if !t.has("count") {
                        return Err(r.error(key, v, "`count` in a \"grid\" distribution"));
                    }
                    let count = t.integer("count", 1, 1, i64::MAX)? as u64;
                    if min > max {
                        return Err(r.error(key, v, "min at most max"));
                    }
                    Dist::Grid { min, max, count }
                }
                _ => return Err(r.error(key, v, allowed_forms)),
            };
            t.finish()?;
            dist
        }
        _ => return Err(r.error(key, v, allowed_forms)),
    };
    let (lo, hi) = dist.support();
    if !(range.holds(lo) && range.holds(hi)) {
        let why = if lo.is_infinite() || hi.is_infinite() {
            format!(
                "{}; an untruncated normal reaches any value, so give min and max",
                range.text
            )
        } else {
            range.text.to_string()
        };
        return Err(r.error(key, v, &why));
    }
    Ok(dist)
}

fn read_initial(top: &mut Reader, d: &Initial) -> Result<Initial, ScenarioError> {
    let Some(mut r) = top.table("initial")? else {
        return Ok(d.clone());
    };
    let reference = match d.attitude_reference {
        AttitudeReference::Vertical => "vertical",
        AttitudeReference::Surface => "surface",
    };
    let attitude_reference =
        match r.word("attitude_reference", reference, &["vertical", "surface"])? {
            "surface" => AttitudeReference::Surface,
            _ => AttitudeReference::Vertical,
        };
    let clearance_m = r.non_negative("clearance_m", d.clearance_m)?;
    r.finish()?;
    Ok(Initial {
        attitude_reference,
        clearance_m,
    })
}

fn read_simulation(top: &mut Reader, d: &Simulation) -> Result<Simulation, ScenarioError> {
    let Some(mut r) = top.table("simulation")? else {
        return Ok(d.clone());
    };
    let step_s = r.f64_where(
        "step_s",
        d.step_s,
        "a step greater than 0 and at most 0.01 s (the contact springs need small steps)",
        |x| x > 0.0 && x <= 0.01,
    )?;
    let flight_step_max_s = r.f64_where(
        "flight_step_max_s",
        d.flight_step_max_s.max(step_s),
        &format!("a step of at least step_s = {step_s} s and at most 1 s"),
        |x| x >= step_s && x <= 1.0,
    )?;
    let t_max_s = r.f64_where(
        "t_max_s",
        d.t_max_s,
        &format!("a time of at least step_s = {step_s} s and at most 1e6 s"),
        |x| x >= step_s && x <= 1e6,
    )?;
    let keys: Vec<&str> = Precision::ALL.iter().map(|p| p.key()).collect();
    let precision = Precision::from_key(r.word("precision", d.precision.key(), &keys)?)
        .unwrap_or(Precision::F64);
    r.finish()?;
    Ok(Simulation {
        step_s,
        flight_step_max_s,
        t_max_s,
        precision,
    })
}

fn read_outcome(top: &mut Reader, d: &Outcome) -> Result<Outcome, ScenarioError> {
    let Some(mut r) = top.table("outcome")? else {
        return Ok(d.clone());
    };
    let o = Outcome {
        rest_speed_m_s: r.positive("rest_speed_m_s", d.rest_speed_m_s)?,
        rest_rate_deg_s: r.positive("rest_rate_deg_s", d.rest_rate_deg_s)?,
        hold_time_s: r.positive("hold_time_s", d.hold_time_s)?,
        bounce_clearance_m: r.non_negative("bounce_clearance_m", d.bounce_clearance_m)?,
        diverged_speed_m_s: r.positive("diverged_speed_m_s", d.diverged_speed_m_s)?,
        diverged_rate_deg_s: r.positive("diverged_rate_deg_s", d.diverged_rate_deg_s)?,
        diverged_penetration_m: r.positive("diverged_penetration_m", d.diverged_penetration_m)?,
        early_tipping: r.bool("early_tipping", d.early_tipping)?,
        early_sliding: r.bool("early_sliding", d.early_sliding)?,
        early_bouncing: r.bool("early_bouncing", d.early_bouncing)?,
    };
    r.finish()?;
    Ok(o)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_file_is_the_default_scenario() {
        assert_eq!(
            Scenario::from_toml(DEFAULT_TOML).unwrap(),
            Scenario::default()
        );
    }

    #[test]
    fn empty_file_is_the_default_scenario() {
        assert_eq!(Scenario::from_toml("").unwrap(), Scenario::default());
    }

    #[test]
    fn the_stored_text_carries_the_seed_that_ran() {
        let with = |text: &str, seed| {
            let edited = with_seed(text, seed);
            let s = Scenario::from_toml(&edited).unwrap();
            let mut expected = Scenario::from_toml(text).unwrap();
            expected.seed = seed;
            assert_eq!(s, expected, "{edited}");
            edited
        };
        // Replaced in place, comments kept.
        let text = "# study\nseed = 1   # the seed\nsamples = 10\n[lander]\nmass_kg = 90.0\n";
        assert_eq!(
            with(text, 7),
            "# study\nseed = 7\nsamples = 10\n[lander]\nmass_kg = 90.0\n"
        );
        // Added before the first key (a table header here), after the opening comments.
        let text = "# study\n\n[lander]\nmass_kg = 90.0\n";
        assert_eq!(
            with(text, 7),
            "# study\n\nseed = 7\n[lander]\nmass_kg = 90.0\n"
        );
        // A `seed` key inside a table is not the scenario's seed; unchanged when it agrees.
        let text = "[lander]\nmass_kg = 90.0\n";
        assert!(with(text, 3).starts_with("seed = 3\n"));
        assert_eq!(with(DEFAULT_TOML, 1), DEFAULT_TOML);
        let default = with(DEFAULT_TOML, 42);
        assert!(default.contains("\nseed = 42\n") && !default.contains("\nseed = 1\n"));
    }

    #[test]
    fn distributions_parse() {
        let s = Scenario::from_toml(
            r#"[inputs]
            slope_deg = { dist = "grid", min = 0, max = 40, count = 5 }
            roll_deg = { dist = "normal", mean = 0.0, sd = 2.0, min = -5.0, max = 5.0 }
            yaw_deg = 30
            pitch_deg = { dist = "fixed", value = 1.5 }"#,
        )
        .unwrap();
        assert_eq!(
            s.inputs.slope_deg,
            Dist::Grid {
                min: 0.0,
                max: 40.0,
                count: 5
            }
        );
        assert_eq!(s.inputs.yaw_deg, Dist::Fixed(30.0));
        assert_eq!(s.inputs.pitch_deg, Dist::Fixed(1.5));
        assert!(matches!(s.inputs.roll_deg, Dist::Normal { min, .. } if min == -5.0));
    }
}
