//! The `Scenario` type: a complete, validated scenario, every section of it, and what it
//! fixes. Reading and checking it is `read`'s.

use super::control::{Control, read_control};
use super::damper::{Damper, read_damper};
use super::initial::{Initial, read_initial};
use super::inputs::{Dist, Inputs, PARAMETERS, Parameter, Sampled, read_inputs, read_parameter};
use super::lander::{Geometry, Lander, read_lander};
use super::limits::{Limits, read_limits};
use super::outcome::{Outcome, read_outcome};
use super::reader::table;
use super::simulation::{Simulation, read_simulation};
use super::surface::{Surface, read_surface};
use super::table::InputTable;
use super::thrusters::{Propulsion, Thruster, read_propulsion, read_thrusters};

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

impl Design {
    /// The word of each design in a scenario file.
    pub const WORDS: [(&'static str, Design); 3] = [
        ("independent", Design::Independent),
        ("sobol-indices", Design::SobolIndices),
        ("sobol-sequence", Design::SobolSequence),
    ];

    /// Its word in a scenario file, quoted as TOML writes it.
    #[must_use]
    pub fn toml(self) -> String {
        let (word, _) = Design::WORDS
            .into_iter()
            .find(|(_, d)| *d == self)
            .expect("a design");
        format!("\"{word}\"")
    }
}

table! {
    /// A complete, validated scenario.
    #[derive(Debug, Clone, PartialEq)]
    pub struct Scenario;
    /// Reads every key of a scenario file (`Scenario::from_toml` then checks across tables).
    fn read_scenario(r) with key {
        /// Seed of the whole sweep: sample i draws its inputs from (seed, i) alone.
        seed: u64 = r.integer(key, 0, i64::MAX)?,
        /// How samples draw their inputs.
        design: Design = r.word(key, &Design::WORDS)?,
        /// Samples a sweep runs when the command line does not say.
        samples: u64 = r.integer(key, 1, i64::MAX)?,
        /// The parameters drawn per sample (`Parameter`): their distributions, `None` for
        /// those the scenario fixes. A drawn parameter's own field (`lander.mass_kg`, ...)
        /// holds its distribution's median. Not a key: the keys below fill it.
        sampled: Sampled = [None; PARAMETERS],
        /// Gravity, along -Z_I (may be drawn per sample).
        gravity_m_s2: f64 = read_parameter(r, key, &mut sampled)?,
        /// `[lander]`.
        lander: Lander = r.section(key, |t| read_lander(t, &mut sampled))?,
        /// `[surface]`.
        surface: Surface = r.section(key, |t| read_surface(t, &mut sampled))?,
        /// `[damper]`.
        damper: Damper = r.section(key, |t| read_damper(t, &mut sampled))?,
        /// `[inputs]`.
        inputs: Inputs<Dist> = r.section(key, read_inputs)?,
        /// `[initial]`.
        initial: Initial = r.section(key, read_initial)?,
        /// `[simulation]`.
        simulation: Simulation = r.section(key, read_simulation)?,
        /// `[outcome]`.
        outcome: Outcome = r.section(key, read_outcome)?,
        /// The thrusters, `[[thrusters]]` (none by default: a passive lander).
        thrusters: Vec<Thruster> = read_thrusters(r)?,
        /// `[propulsion]`.
        propulsion: Propulsion = r.section(key, read_propulsion)?,
        /// The control loop that fires the thrusters, `[control]`, if any.
        control: Option<Control> = r.optional(key, read_control)?,
        /// The structural limits, `[limits]`, if any.
        limits: Option<Limits> = r.optional(key, read_limits)?,
        /// The table of the user's own inputs (`sweep --inputs`): row `i` gives sample `i`
        /// the values of its columns (`crate::table::attach`); none in a scenario file.
        table: Option<std::sync::Arc<InputTable>> = None,
    }
}

impl Scenario {
    /// The value of parameter `p` where the scenario fixes it (its field; for a drawn one,
    /// the median of its distribution; 0 for the soil's and the rocks' without them).
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
            Parameter::FootpadAreaM2 => self.lander.footpad_area_m2,
            // 0 where the scenario has no rocks or no regolith: a sample compares equal
            // to itself (no NaN), and a trace of it records none of them (`uses`).
            Parameter::RockAbundance => self.surface.rocks.abundance,
            Parameter::GravityMS2 => self.gravity_m_s2,
            p => self.surface.regolith.map_or(0.0, |r| r.parameter(p)),
        }
    }

    /// Whether parameter `p` plays a part in this scenario: the lander's and the contact
    /// law's always, the footpad's area and the soil's on regolith, the rock abundance
    /// with rocks. (A trace records those that do.)
    #[must_use]
    pub fn uses(&self, p: Parameter) -> bool {
        match p {
            Parameter::MassKg
            | Parameter::CgHeightM
            | Parameter::StiffnessNPerM
            | Parameter::DampingNSPerM
            | Parameter::FrictionCoefficient
            | Parameter::CrushStrengthPsi
            | Parameter::RmsHeightM => true,
            Parameter::RockAbundance => self.rock_abundance_max() > 0.0,
            // Recorded where drawn: a fixed gravity is the scenario's own (its text says it).
            Parameter::GravityMS2 => self.sampled[p as usize].is_some(),
            Parameter::FootpadAreaM2 => {
                self.surface.regolith.is_some() || self.rock_abundance_max() > 0.0
            }
            _ => self.surface.regolith.is_some(),
        }
    }

    /// The largest rock abundance of any sample (the drawn one's largest value): the rock
    /// tiles are built for it, and a sample meets rocks where it is above 0.
    #[must_use]
    pub fn rock_abundance_max(&self) -> f64 {
        self.sampled[Parameter::RockAbundance as usize]
            .map_or(self.surface.rocks.abundance, |d| d.support().1)
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
