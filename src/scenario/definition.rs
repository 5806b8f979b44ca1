//! The `Scenario` type: a complete, validated scenario, every section of it, and what it
//! fixes. Reading and checking it is `read`'s.

use super::control::Control;
use super::damper::{Damper, Stage, StrutAxes};
use super::initial::{AttitudeReference, Initial, Start};
use super::inputs::{Dist, Inputs, PARAMETERS, Parameter, Sampled};
use super::lander::{Geometry, Lander};
use super::outcome::Outcome;
use super::simulation::Simulation;
use super::surface::{Roughness, Surface};
use super::table::InputTable;
use super::thrusters::{Propulsion, Thruster};
use kernels::isa::Precision;

/// How the samples of a sweep draw their inputs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Design {
    /// Every sample draws every input independently (the default).
    Independent,
    /// Saltelli's design for Sobol sensitivity indices: with `d` inputs drawn at random,
    /// blocks of `d + 2` samples share a base point; see `sampling::sample`.
    SobolIndices,
    /// Quasi-random: the inputs drawn from a distribution take the coordinates of an
    /// Owen-scrambled Sobol sequence (`qmc`) through their inverse CDFs, instead of
    /// independent draws.
    SobolSequence,
}

/// A complete, validated scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct Scenario {
    pub seed: u64,
    /// How samples draw their inputs.
    pub design: Design,
    /// Samples a sweep runs when the command line does not say.
    pub samples: u64,
    pub gravity_m_s2: f64,
    pub lander: Lander,
    pub surface: Surface,
    pub damper: Damper,
    pub inputs: Inputs<Dist>,
    /// The parameters drawn per sample (`Parameter`): their distributions, `None` for those
    /// the scenario fixes. A drawn parameter's own field (`lander.mass_kg`, ...) holds its
    /// distribution's median.
    pub sampled: Sampled,
    pub initial: Initial,
    pub simulation: Simulation,
    pub outcome: Outcome,
    /// The thrusters (none by default: a passive lander).
    pub thrusters: Vec<Thruster>,
    pub propulsion: Propulsion,
    /// The control loop that fires them, if any.
    pub control: Option<Control>,
    /// The table of the user's own inputs (`sweep --inputs`): row `i` gives sample `i` the
    /// values of its columns (`crate::table::attach`); none in a scenario file.
    pub table: Option<std::sync::Arc<InputTable>>,
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
            design: Design::Independent,
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
            sampled: [None; PARAMETERS],
            initial: Initial {
                attitude_reference: AttitudeReference::Vertical,
                clearance_m: 0.001,
                start: Start::Touchdown,
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
            thrusters: Vec::new(),
            propulsion: Propulsion {
                isp_s: 220.0,
                thrust_error_sd: 0.0,
                misalignment_sd_deg: 0.0,
            },
            control: None,
            table: None,
        }
    }
}

impl Scenario {
    /// The value of parameter `p` where the scenario fixes it (its field; for a drawn one,
    /// the median of its distribution).
    #[must_use]
    pub fn parameter(&self, p: Parameter) -> f64 {
        match p {
            Parameter::MassKg => self.lander.mass_kg,
            Parameter::CgHeightM => match self.lander.geometry {
                Geometry::Regular { cg_height_m, .. } => cg_height_m,
                Geometry::Tips(_) => f64::NAN,
            },
            Parameter::StiffnessNPerM => self.surface.stiffness_n_per_m,
            Parameter::DampingNSPerM => self.surface.damping_n_s_per_m,
            Parameter::FrictionCoefficient => self.surface.friction_coefficient,
            Parameter::CrushStrengthPsi => self.damper.stages[0].crush_strength_psi,
            Parameter::RmsHeightM => self.surface.roughness.rms_height_m,
        }
    }

    /// The largest terrain roughness of any sample (the drawn one's largest value): the
    /// terrain tiles are built for it, and a sample lands on a tile where it is above 0.
    #[must_use]
    pub fn rms_height_max_m(&self) -> f64 {
        self.sampled[Parameter::RmsHeightM as usize]
            .map_or(self.surface.roughness.rms_height_m, |d| d.support().1)
    }

    /// Number of legs of the lander.
    #[must_use]
    pub fn leg_count(&self) -> usize {
        match &self.lander.geometry {
            Geometry::Regular { legs, .. } => *legs,
            Geometry::Tips(t) => t.len(),
        }
    }
}
