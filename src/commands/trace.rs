//! `touchdown trace`: one sample run with the reference model, its time history written,
//! and its inputs and summary told.

use super::flags::{parse_count, parse_every, parse_seed};
use super::print::{say, shown};
use crate::output::sweep::control_columns;
use crate::output::trace::control_values;
use crate::reference::Summary;
use crate::run::trace::{TraceSettings, trace};
use crate::scenario::Sample;
use crate::scenario::{INPUT_FIELDS, Scenario};
use std::path::PathBuf;

/// Flags of `touchdown trace`.
#[derive(clap::Args, Debug)]
pub struct TraceArgs {
    /// A sweep or shard file (Arrow or Parquet): trace its sample I, with the scenario and
    /// seed it ran with (stored in the file), exactly as its row was computed.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["scenario", "seed"])]
    pub sweep: Option<PathBuf>,
    /// Scenario file (TOML); without it (and without --sweep), the default sweep of
    /// MODEL.md section 11.
    #[arg(long, value_name = "FILE")]
    pub scenario: Option<PathBuf>,
    /// Seed of the sweep (overrides the scenario's `seed`).
    #[arg(long, value_name = "S", value_parser = parse_seed, allow_negative_numbers = true)]
    pub seed: Option<u64>,
    /// The table of inputs the sweep ran (`sweep --inputs`), where it is no longer where
    /// the sweep file says; with --scenario, row I of this table is the sample.
    #[arg(long, value_name = "TABLE")]
    pub inputs: Option<PathBuf>,
    /// Index of the sample to run, as in the sweep's `sample` column (accepts 1e6, 250000,
    /// 2.5e5).
    #[arg(long, value_name = "I", default_value = "0", value_parser = parse_count, allow_negative_numbers = true)]
    pub sample: u64,
    /// Arrow IPC file to write the time history to; `-` writes an IPC stream to standard
    /// output, and a device or FIFO is written into, never replaced.
    #[arg(long, value_name = "PATH", default_value = "trace.arrow")]
    pub out: PathBuf,
    /// Write one row every N steps.
    #[arg(long, value_name = "N", default_value = "1", value_parser = parse_every, allow_negative_numbers = true)]
    pub every: u64,
}

/// Runs `touchdown trace`.
pub fn run(args: &TraceArgs) -> anyhow::Result<()> {
    let settings = TraceSettings {
        sweep: args.sweep.clone(),
        scenario: args.scenario.clone(),
        scenario_toml: None,
        seed: args.seed,
        inputs: args.inputs.clone(),
        sample: args.sample,
        out: Some(args.out.clone()),
        every: args.every,
    };
    let done = trace(&settings)?;
    let mut text = describe(&done.scenario, &done.sample, &done.summary);
    text.push_str(&format!(
        "\nwrote {}: {} rows (every {} of {} steps, and the state at the decision)\n",
        shown(&args.out),
        done.rows,
        args.every,
        done.summary.steps
    ));
    say("the trace's summary", &text, &args.out)
}

/// The inputs and summary of a sample, for people.
#[must_use]
pub fn describe(scenario: &Scenario, sample: &Sample, s: &Summary) -> String {
    let mut t = format!(
        "sample {} of seed {} (sample seed {:#018x})\n\ninputs\n",
        sample.index, scenario.seed, sample.seed
    );
    if let Some(table) = &scenario.table {
        t.insert_str(
            t.find('\n').unwrap_or(t.len()),
            &format!(
                ", row {} of the table of inputs {} (columns: {})",
                sample.index,
                table.path.display(),
                table.columns.join(", ")
            ),
        );
    }
    for ((name, unit), value) in INPUT_FIELDS.iter().zip(sample.inputs.to_array()) {
        t.push_str(&format!("  {name:<24} {value:>12.6} {unit}\n"));
    }
    for ((name, unit), p) in crate::scenario::PARAMETER_FIELDS
        .iter()
        .zip(crate::scenario::Parameter::ALL)
    {
        if scenario.sampled[p as usize].is_some() {
            let value = sample.parameters[p as usize];
            t.push_str(&format!("  {name:<24} {value:>12.6} {unit} (drawn)\n"));
        }
    }
    if let Some(state) = scenario.initial.touchdown {
        for (((name, unit), dist), value) in crate::scenario::INITIAL_FIELDS
            .iter()
            .zip(state)
            .zip(sample.touchdown)
        {
            let drawn = if matches!(dist, crate::scenario::Dist::Fixed(_)) {
                ""
            } else {
                " (drawn)"
            };
            t.push_str(&format!("  {name:<24} {value:>12.6} {unit}{drawn}\n"));
        }
    }
    if scenario.rms_height_max_m() > 0.0 {
        t.push_str(&format!(
            "  {:<24} {:>12} (offset {:.3} m, {:.3} m)\n",
            "terrain_tile",
            sample.terrain_tile,
            sample.terrain_offset_m[0],
            sample.terrain_offset_m[1]
        ));
    }
    let first = s
        .first_contact_s
        .map_or("never".to_string(), |t| format!("{t:.3} s"));
    t.push_str(&format!(
        "\nsummary\n  {:<24} {} at {:.3} s ({} steps)\n  {:<24} {first}\n  {:<24} {}\n  {:<24} {:.2} deg (final {:.2} deg)\n  {:<24} {:.4} m\n  {:<24} {:.3} m/s^2 (along Z_B {:.3} m/s^2)\n  {:<24} {:.2} mm\n",
        "outcome", s.outcome.name(), s.decided_s, s.steps,
        "first contact",
        "bounces", s.bounces,
        "max tilt from normal", s.max_tilt_deg, s.final_tilt_deg,
        "displacement on surface", s.displacement_m,
        "peak acceleration", s.peak_acceleration_m_s2, s.peak_acceleration_z_body_m_s2,
        "max penetration", s.max_penetration_m * 1e3,
    ));
    // On regolith two more columns: the footprint's depth and the soil's energy, as the
    // sweep's `leg{k}_sinkage_m` and `leg{k}_soil_absorbed_j`.
    let soil = scenario.surface.regolith.is_some();
    t.push_str("\n  leg  peak normal force N   stroke mm   absorbed J");
    t.push_str(if soil {
        "   footprint mm   soil kept J\n"
    } else {
        "\n"
    });
    for (k, l) in s.legs.iter().enumerate() {
        t.push_str(&format!(
            "  {k:>3}  {:>19.2}   {:>9.3}   {:>10.4}",
            l.peak_normal_force_n,
            l.stroke_m * 1e3,
            l.absorbed_j
        ));
        if soil {
            t.push_str(&format!(
                "   {:>12.3}   {:>11.4}",
                l.sinkage_m * 1e3,
                l.soil_absorbed_j
            ));
        }
        t.push('\n');
    }
    t.push_str(&struts(s));
    t.push_str(&flown(scenario, s));
    t
}

/// Each leg's strut-load peaks with their times and, with dampers, its stroke margin at the
/// end, as the sweep's `leg{k}_peak_axial_force_n` ... `leg{k}_stroke_margin_m`; with
/// `[limits]`, the limits the sample broke, as its `limits_broken`.
fn struts(s: &Summary) -> String {
    let dampers = s.legs.iter().any(|l| l.stroke_margin_m.is_some());
    let mut t = String::from("\n  leg  peak axial load N     at s   peak side load N     at s");
    t.push_str(if dampers {
        "   stroke margin mm\n"
    } else {
        "\n"
    });
    let at = |time: Option<f64>| time.map_or("never".to_string(), |x| format!("{x:.3}"));
    for (k, l) in s.legs.iter().enumerate() {
        t.push_str(&format!(
            "  {k:>3}  {:>17.2}   {:>6}   {:>16.2}   {:>6}",
            l.peak_axial_force_n,
            at(l.peak_axial_force_s),
            l.peak_side_force_n,
            at(l.peak_side_force_s)
        ));
        if let Some(margin) = l.stroke_margin_m {
            t.push_str(&format!("   {:>16.3}", margin * 1e3));
            if l.bottomed {
                t.push_str(" (bottomed)");
            }
        }
        t.push('\n');
    }
    if let Some(broken) = s.limits_broken {
        let names = broken.names();
        let names = if names.is_empty() { "none" } else { &names };
        t.push_str(&format!("\n  {:<24} {names}\n", "limits broken"));
    }
    t
}

/// What the control loop flew, as the sweep's columns of that name have it: the drawn law
/// parameters, the propellant, firings and hold-down impulse, and a descent's release
/// state (empty without a control loop).
fn flown(scenario: &Scenario, s: &Summary) -> String {
    let values = control_values(&control_columns(scenario), s);
    if values.is_empty() {
        return String::new();
    }
    let mut t = String::from("\ncontrol loop (as the sweep's columns of these names)\n");
    let released = values
        .iter()
        .find(|(name, ..)| *name == "release_time_s")
        .is_none_or(|(.., time)| !time.is_nan());
    for (name, unit, value) in values {
        if name == "release_time_s" && !released {
            t.push_str(&format!("  {name:<28} never: contact came first\n"));
        } else if unit == "1" {
            t.push_str(&format!("  {name:<28} {value:>12}\n"));
        } else if released || !name.starts_with("release_") {
            t.push_str(&format!("  {name:<28} {value:>12.6} {unit}\n"));
        }
    }
    t
}
