//! The command line: each command's raw flags (clap), checked into settings and handed to
//! the layers below; the program's entry, its error messages and exit codes.

pub mod animate;
pub mod boundary;
mod boundary_data;
pub mod compare;
pub mod envelope;
pub mod flags;
pub mod merge;
pub mod plot;
mod print;
pub mod report;
pub mod scenario;
pub mod sensitivity;
pub mod site;
pub mod study;
pub mod sweep;
pub mod trace;
pub mod view;

use clap::{Parser, Subcommand};

/// Monte Carlo touchdown simulation of legged landers on asteroids.
#[derive(Parser, Debug)]
#[command(name = "touchdown", version, about)]
pub struct Cli {
    /// The command to run.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Print the default scenario as a commented TOML file to edit.
    Scenario,
    /// Run one sample with the reference model and write its time history.
    Trace(trace::TraceArgs),
    /// Run a Monte Carlo sweep through the SIMD kernels and write one row per sample.
    Sweep(sweep::SweepArgs),
    /// Summarise a sweep file: outcomes with 95 % intervals, the allowable slope per
    /// azimuth sector, peak loads (Markdown on stdout).
    Report(report::ReportArgs),
    /// Compare two sweeps of the same seed sample by sample (paired: the same landers
    /// wherever the scenarios draw an input alike): outcome shares, their differences with
    /// 95 % intervals, and which samples changed outcome (Markdown on stdout).
    Compare(compare::CompareArgs),
    /// Sobol sensitivity indices of every input drawn at random, for P(stable), P(tipped),
    /// peak CG acceleration and longest damper stroke, from a sweep run with
    /// `design = "sobol-indices"` (Markdown on stdout).
    Sensitivity(sensitivity::SensitivityArgs),
    /// Run the sweep at each of several values of one scenario key (footpad radius, CG
    /// height, crush strength...) and tabulate outcome shares and the allowable slope per
    /// sector against it (Arrow, Markdown, PNG with the static limit).
    Study(study::StudyArgs),
    /// Join the shard files of one sweep (`sweep --shard K/N`) into the file the sweep
    /// writes when run in one process.
    Merge(merge::MergeArgs),
    /// Draw PNG pictures of a sweep file (stability map, tipped share per slope, load
    /// distributions) or of a trace file (CG and leg time histories, 3D path, shock along
    /// Z_B).
    Plot(plot::PlotArgs),
    /// Animate a trace file as a GIF: the lander in 3D on its slope, the CG's trail, the
    /// contact forces and thrust plumes, with time, tilt and outcome.
    Animate(animate::AnimateArgs),
    /// Write a trace file as one self-contained HTML page: the lander in 3D (drag to orbit,
    /// wheel to zoom), a time slider with play and pause, and the histories as charts.
    View(view::ViewArgs),
    /// Find the allowable slope per azimuth sector directly, by adaptive sampling.
    Boundary(boundary::BoundaryArgs),
    /// The touchdown envelope of a sweep file: outcome shares over the plane of two
    /// columns (the speeds along and towards the surface at the first contact), per slope
    /// band, with the 99 %-stable boundary of each row (PNG, CSV, Markdown on stdout).
    Envelope(envelope::EnvelopeArgs),
    /// A landing-site map of a small body from its shape model (a Wavefront OBJ file, or a
    /// vertex-facet plate file: PDS .tab, SBMT .plt): each facet's effective gravity (the
    /// constant-density polyhedron's attraction and the spin) and slope, and P(stable),
    /// P(tipped), ... of the lander there with 95 % intervals, from one sweep over the
    /// body's slopes and gravities (a table, a summary, a map picture and a 3D page).
    Site(site::SiteArgs),
}

/// The `touchdown` program: parses the command line, runs it, prints an error and returns
/// exit code 2 (or the code of an interruption) where it fails. A closed pipe on its output
/// ends it quietly with exit code 0, as the reader had what it wanted (`report | head -1`).
/// A program that embeds touchdown, to register laws of its own (`control::register_law`),
/// calls this from its `main`.
#[must_use]
pub fn main() -> std::process::ExitCode {
    crate::run::memory::one_malloc_arena();
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) if print::closed_pipe(&e) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            if let Some(i) = e.downcast_ref::<crate::run::Interrupted>() {
                print::tell(&format!("touchdown: {i}\n"));
                return std::process::ExitCode::from(i.code);
            }
            print::tell(&format!("touchdown: error: {e:#}\n"));
            std::process::ExitCode::from(2)
        }
    }
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    // A signal ends any command without leaving an unfinished file (a sweep, a study and
    // an animation take it over to stop cleanly).
    crate::run::end_on_signals()?;
    crate::output::inputs::declare(&inputs_of(&cli.command));
    // Standard output redirected into an input (`report s.arrow >> s.arrow`).
    crate::output::inputs::refuse_stdout_as_output()?;
    match cli.command {
        Command::Scenario => scenario::run(),
        Command::Trace(args) => trace::run(&args),
        Command::Sweep(args) => sweep::run(&args),
        Command::Study(args) => study::run(&args),
        Command::Boundary(args) => boundary::run(&args),
        Command::Report(args) => report::run(&args),
        Command::Sensitivity(args) => sensitivity::run(&args),
        Command::Compare(args) => compare::run(&args),
        Command::Plot(args) => plot::run(&args),
        Command::Animate(args) => animate::run(&args),
        Command::View(args) => view::run(&args),
        Command::Merge(args) => merge::run(&args),
        Command::Envelope(args) => envelope::run(&args),
        Command::Site(args) => site::run(&args),
    }
}

/// The files `command` reads, which none of its outputs may be (`output::inputs`).
fn inputs_of(command: &Command) -> Vec<&std::path::Path> {
    use std::path::Path;
    let given: Vec<Option<&Path>> = match command {
        Command::Scenario => vec![],
        Command::Trace(a) => vec![
            a.sweep.as_deref(),
            a.scenario.as_deref(),
            a.inputs.as_deref(),
        ],
        Command::Sweep(a) => vec![a.scenario.as_deref(), a.inputs.as_deref()],
        Command::Study(a) => vec![a.scenario.as_deref()],
        Command::Boundary(a) => vec![a.scenario.as_deref()],
        // A slope distribution may be given as a file.
        Command::Report(a) => vec![
            Some(&a.sweep),
            a.slope_distribution.as_deref().map(Path::new),
        ],
        Command::Sensitivity(a) => vec![Some(&a.sweep)],
        Command::Compare(a) => vec![Some(&a.a), Some(&a.b)],
        Command::Plot(a) => vec![Some(&a.file)],
        Command::Animate(a) => vec![Some(&a.trace)],
        Command::View(a) => vec![Some(&a.trace)],
        Command::Merge(a) => a.shards.iter().map(|p| Some(p.as_path())).collect(),
        Command::Envelope(a) => vec![Some(&a.sweep)],
        Command::Site(a) => vec![Some(&a.shape), a.scenario.as_deref()],
    };
    given.into_iter().flatten().collect()
}
