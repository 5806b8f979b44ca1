//! Running a plan: the writer, the banner, the rows an interrupted run kept, the workers
//! with their progress bar, and the file finished or left valid when a signal stops it.

use super::plan::SweepPlan;
use super::workers::{Interrupted, shown, tell};
use crate::output::format::BATCH_ROWS;
use crate::output::sweep::{Made, SweepInfo, SweepWriter};
use crate::reference::{Model, Outcome};
use crate::report::LimitCounts;
use crate::scenario::{Broken, Scenario};
use crate::sweep::Stretches;
use std::ops::Range;

/// How `execute` runs a plan: on which pool, stopped by which signal flag
/// (`stop_on_signals`), and what it shows on stderr.
pub struct RunOptions<'a> {
    /// The worker threads (`worker_pool`).
    pub pool: &'a rayon::ThreadPool,
    /// The signal that asks the run to stop, 0 before one arrives (`stop_on_signals`).
    pub stop: &'a std::sync::Arc<std::sync::atomic::AtomicUsize>,
    /// A progress bar (when stderr is a terminal).
    pub progress: bool,
    /// The line naming the samples, seed, kernel and threads.
    pub banner: bool,
    /// Whether the kernel is the widest the CPU runs (`--kernel auto`), for the banner.
    pub auto_kernel: bool,
    /// Keep the batches written (`Executed::batches`): a sweep handed over in memory, with
    /// its file or without one (a plan with no `out`).
    pub keep: bool,
    /// Counts the samples computed as they are done, for a caller's own progress display.
    pub counter: Option<&'a std::sync::atomic::AtomicU64>,
}

/// What `execute` did.
pub struct Executed {
    /// Rows in the file (kept from an interrupted run and computed now).
    pub rows: u64,
    /// Samples computed by this run.
    pub computed: u64,
    /// Wall-clock time of this run, s.
    pub wall_s: f64,
    /// How busy the kernel's lanes were.
    pub stats: crate::sweep::LaneStats,
    /// The share of the run's CPU time spent on the one thread that hands the batches to
    /// the file (the run's serial part; `Ran::serial_share`).
    pub serial_share: f64,
    /// Rows per outcome, in the order of `Outcome::ALL`.
    pub counts: [u64; Outcome::ALL.len()],
    /// With `[limits]`: the rows within them and the rows that broke each (boxed, so that
    /// a run without limits carries one pointer).
    pub limits: Option<Box<LimitCounts>>,
    /// Time steps summed over the rows in the file (kept and computed).
    pub steps: u64,
    /// Samples of this run that never touched the surface.
    pub untouched: u64,
    /// Of those, the samples that tipped in flight (turned past 90 deg before touching).
    pub untouched_tipped: u64,
    /// The gentlest slope among those (deg; infinite where there is none).
    pub untouched_tipped_slope_deg: f64,
    /// Of those, the samples still in their powered descent at the end (never released).
    pub untouched_descending: u64,
    /// The batches written, in order, where `RunOptions::keep` asked for them.
    pub batches: Vec<arrow_array::RecordBatch>,
}

/// Runs `plan` and writes its file. A signal (`run.stop`) ends it with an `Interrupted`
/// error whose message says how to continue (`plan.continue_with`).
pub fn execute(plan: &SweepPlan, run: &RunOptions<'_>) -> anyhow::Result<Executed> {
    let (scenario, samples) = (&plan.scenario, plan.samples);
    let threads = run.pool.current_num_threads();
    let model = Model::new(scenario);
    let range = plan.shard.map_or(0..samples, |s| s.range(samples));
    let kept = plan.resume.as_ref().map_or(0, |r| r.kept_rows());
    let mut writer = create_writer(plan, &model, run.keep)?;
    if run.banner {
        tell(&format!(
            "{}\n",
            banner(plan, &range, kept, threads, run.auto_kernel)
        ));
    }
    let stale = plan.out.as_deref().map(crate::output::interrupted_path);
    if let (None, Some(stale), Some(out)) = (&plan.resume, &stale, &plan.out)
        && stale.exists()
    {
        tell(&format!(
            "touchdown: note: {} holds an interrupted sweep to {}; this run replaces it when \
             it ends (to continue that one instead, stop this run and use {})\n",
            stale.display(),
            out.display(),
            plan.continue_with
        ));
    }
    let mut counts = [0u64; Outcome::ALL.len()];
    let mut limits = scenario.limits.map(|_| Box::new(LimitCounts::default()));
    let mut steps = 0u64;
    if let Some(from) = &plan.resume {
        let (kept_counts, kept_steps) = from.copy_kept_rows(range.start, &mut writer)?;
        for ((outcome, broken), &n) in &kept_counts {
            if let Some(o) = Outcome::from_name(outcome) {
                counts[o as usize] += n;
                if let Some(l) = &mut limits {
                    l.add(o, Broken::parse(broken), n);
                }
            }
        }
        steps += kept_steps;
    }
    let todo = (range.start + kept)..range.end;
    let bar = progress_bar(todo.end - todo.start, run.progress, "samples");
    let mut eta = super::eta::Eta::start(todo.end - todo.start, threads);
    let start = std::time::Instant::now();
    let mut tally = Tally::default();
    let maker = writer.maker();
    // Each stretch of rows becomes a batch of the file (and its tally) on the worker that
    // finished it; this thread only appends the batches in order.
    let make = |rows: Vec<crate::sweep::Row>| -> anyhow::Result<(Tally, Made)> {
        Ok((Tally::of(&rows), maker.make(&rows)?))
    };
    let stretches = Stretches {
        first: writer.room() as u64,
        len: BATCH_ROWS as u64,
    };
    let ran = run.pool.install(|| {
        crate::sweep::pipeline(
            scenario,
            &model,
            plan.kernel.isa,
            todo.clone(),
            stretches,
            run.stop,
            &make,
            |(t, made)| {
                tally.add(&t);
                if let Some(counter) = run.counter {
                    counter.store(tally.rows, std::sync::atomic::Ordering::Relaxed);
                }
                eta.done(tally.rows);
                bar.inc(t.rows);
                writer.push_made(made)
            },
        )
    })?;
    bar.finish_and_clear();
    // A stop asked for after the last rows still stops: the file is not finished.
    if ran.end < todo.end || run.stop.load(std::sync::atomic::Ordering::Relaxed) != 0 {
        return Err(interrupted(plan, writer, run, &range)?);
    }
    // Finishing removes the interrupted run's file it continued (or made obsolete).
    let (rows, batches) = writer.finish_kept()?;
    for (c, t) in counts.iter_mut().zip(tally.counts) {
        *c += t;
    }
    if let Some(l) = &mut limits {
        l.merge(&tally.limits);
    }
    Ok(Executed {
        rows,
        computed: tally.rows,
        wall_s: start.elapsed().as_secs_f64(),
        stats: ran.stats,
        serial_share: ran.serial_share(),
        counts,
        limits,
        steps: steps + tally.steps,
        untouched: tally.untouched,
        untouched_tipped: tally.untouched_tipped,
        untouched_tipped_slope_deg: tally.untouched_tipped_slope_deg,
        untouched_descending: tally.untouched_descending,
        batches,
    })
}

/// What the summary counts of a stretch of rows.
#[derive(Debug, Clone, Copy)]
struct Tally {
    rows: u64,
    /// Rows per outcome, in the order of `Outcome::ALL`.
    counts: [u64; Outcome::ALL.len()],
    steps: u64,
    /// Samples that never touched the surface; of those, the ones that tipped in flight
    /// (and the gentlest slope among them, deg) and the ones still in their powered
    /// descent at the end.
    untouched: u64,
    untouched_tipped: u64,
    untouched_tipped_slope_deg: f64,
    untouched_descending: u64,
    /// The stable rows within `[limits]` and the rows that broke each (where the scenario
    /// has limits).
    limits: LimitCounts,
}

impl Default for Tally {
    fn default() -> Tally {
        Tally {
            rows: 0,
            counts: [0; Outcome::ALL.len()],
            steps: 0,
            untouched: 0,
            untouched_tipped: 0,
            untouched_tipped_slope_deg: f64::INFINITY,
            untouched_descending: 0,
            limits: LimitCounts::default(),
        }
    }
}

impl Tally {
    /// The tally of `rows`.
    fn of(rows: &[crate::sweep::Row]) -> Tally {
        let mut t = Tally::default();
        for r in rows {
            t.rows += 1;
            t.counts[r.summary.outcome as usize] += 1;
            if let Some(broken) = r.summary.limits_broken {
                t.limits.add(r.summary.outcome, broken, 1);
            }
            t.steps += r.summary.steps;
            let never = r.summary.first_contact_s.is_none();
            t.untouched += u64::from(never);
            if never && r.summary.outcome == Outcome::Tipped {
                t.untouched_tipped += 1;
                t.untouched_tipped_slope_deg =
                    t.untouched_tipped_slope_deg.min(r.sample.inputs.slope_deg);
            }
            let descending = r
                .summary
                .control
                .as_ref()
                .is_some_and(|c| c.descent.is_some() && c.release_time_s.is_nan());
            t.untouched_descending +=
                u64::from(never && descending && r.summary.outcome != Outcome::Tipped);
        }
        t
    }

    /// Adds `o` to this tally.
    fn add(&mut self, o: &Tally) {
        self.rows += o.rows;
        for (c, k) in self.counts.iter_mut().zip(o.counts) {
            *c += k;
        }
        self.steps += o.steps;
        self.untouched += o.untouched;
        self.untouched_tipped += o.untouched_tipped;
        self.untouched_tipped_slope_deg = self
            .untouched_tipped_slope_deg
            .min(o.untouched_tipped_slope_deg);
        self.untouched_descending += o.untouched_descending;
        self.limits.merge(&o.limits);
    }
}

/// The writer of `plan`'s file, its metadata saying what the sweep runs; keeping its
/// batches if `keep` (a plan with no file keeps them whatever `keep` says).
fn create_writer(plan: &SweepPlan, model: &Model, keep: bool) -> anyhow::Result<SweepWriter> {
    let scenario = &plan.scenario;
    let control = crate::output::sweep::control_columns(scenario);
    let parameters = crate::output::sweep::parameter_columns(scenario);
    let table = scenario
        .table
        .as_ref()
        .map_or_else(Vec::new, |t| t.metadata());
    let kept_columns = scenario
        .table
        .as_ref()
        .map_or_else(Vec::new, |t| t.kept_fields());
    let info = SweepInfo {
        scenario_toml: &plan.text,
        seed: scenario.seed,
        samples: plan.samples,
        lane_type: plan.kernel.arithmetic(),
        shard: plan.shard,
        control: &control,
        parameters: &parameters,
        table: &table,
        kept: &kept_columns,
    };
    let legs = model.legs.len();
    let writer = match &plan.out {
        Some(out) if keep => SweepWriter::create(out, plan.format, legs, &info)?.keeping(),
        Some(out) => SweepWriter::create(out, plan.format, legs, &info)?,
        None => SweepWriter::in_memory(legs, &info),
    };
    Ok(writer.with_table(scenario.table.clone()))
}

/// The line naming what the sweep runs: samples, seed, table, kernel, threads, shard and
/// where it resumes.
fn banner(
    plan: &SweepPlan,
    range: &Range<u64>,
    kept: u64,
    threads: usize,
    auto_kernel: bool,
) -> String {
    let (scenario, samples) = (&plan.scenario, plan.samples);
    let shard_note = plan.shard.map_or(String::new(), |s| {
        format!(
            ", shard {s} (samples {}..{} of {samples})",
            range.start, range.end
        )
    });
    let resume_note = plan.resume.as_ref().map_or(String::new(), |r| {
        format!(
            ", resuming {} at sample {} ({} rows kept of {})",
            plan.out.as_deref().unwrap_or(&r.path).display(),
            range.start + kept,
            kept,
            r.rows
        )
    });
    let table_note = scenario.table.as_ref().map_or(String::new(), |t| {
        format!(
            ", inputs from {} ({} rows, {} columns)",
            t.path.display(),
            t.rows,
            t.columns.len()
        )
    });
    format!(
        "touchdown sweep: {} samples, seed {}{table_note}, kernel {} ({} landers per block{}), {threads} thread{}{shard_note}{resume_note}",
        range.end - range.start,
        scenario.seed,
        plan.kernel.name(),
        plan.kernel.lanes(),
        if auto_kernel {
            "; the widest this CPU runs"
        } else {
            ""
        },
        if threads == 1 { "" } else { "s" },
    )
}

/// A progress bar of `len` things (`unit`, plural: "samples"): hidden unless asked for and
/// stderr is a terminal.
pub(super) fn progress_bar(len: u64, show: bool, unit: &'static str) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if !show || !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    indicatif::ProgressBar::new(len).with_style(
        indicatif::ProgressStyle::with_template(&format!(
            "{{bar:40}} {{pos}}/{{len}} {unit}  {{rate}}  ETA {{eta}}"
        ))
        .expect("valid template")
        // Whole things per second (indicatif's own `per_sec` has four decimals).
        .with_key(
            "rate",
            move |state: &indicatif::ProgressState, w: &mut dyn std::fmt::Write| {
                let _ = write!(w, "{:.0} {unit}/s", state.per_sec());
            },
        ),
    )
}

/// Leaves the rows so far in a valid file and returns the `Interrupted` error that says
/// which signal stopped the sweep and how to continue it.
fn interrupted(
    plan: &SweepPlan,
    writer: SweepWriter,
    run: &RunOptions<'_>,
    range: &Range<u64>,
) -> anyhow::Result<anyhow::Error> {
    let signal = run.stop.load(std::sync::atomic::Ordering::Relaxed);
    let (rows, path) = writer.finish_interrupted()?;
    let name = super::signals::signal_name(signal);
    let message = match (path, &plan.out) {
        (Some(path), _) => format!(
            "interrupted by {name}: {rows} of {} samples done, in {} (a valid file); \
             continue with: {}",
            range.end - range.start,
            path.display(),
            plan.continue_with
        ),
        (None, Some(out)) => format!(
            "interrupted by {name}: {rows} of {} samples done, written to {} as a valid \
             file; it is not a regular file, so the sweep cannot be resumed from it",
            range.end - range.start,
            shown(out)
        ),
        (None, None) => format!(
            "interrupted by {name}: {rows} of {} samples done; nothing was kept",
            range.end - range.start,
        ),
    };
    Ok(Interrupted {
        code: (128 + signal).min(255) as u8,
        message,
    }
    .into())
}

/// Warns of samples that never touched the surface, telling apart those still in flight
/// at t_max (bouncing) and those that tipped in flight, whose causes differ.
/// `at` names the sweep among several (a study's value), or is empty.
pub fn warn_untouched(done: &Executed, scenario: &Scenario, at: &str) {
    if done.untouched == 0 {
        return;
    }
    let tipped = done.untouched_tipped;
    let descending = done.untouched_descending;
    let flying = done.untouched - tipped - descending;
    let mut why = Vec::new();
    if descending > 0 {
        why.push(format!(
            "{descending} still in the powered descent at the end (bouncing), never released: \
             a descent too long for the run? Braking on its profile from \
             control.descent.start_altitude_m to inputs.release_height_m at \
             control.descent.braking_m_s2 takes about sqrt(2 (start - release) / braking); \
             see also control.descent.release_speed_m_s against the velocity sensor's noise"
        ));
    }
    if flying > 0 {
        why.push(format!(
            "{flying} still in flight at the end (bouncing): a release too high or an upward \
             velocity error for the run's length? See initial.clearance_m, \
             inputs.release_height_m and inputs.velocity_error_z_m_s"
        ));
    }
    // The tilt is taken from the ground's normal (MODEL.md 8): on a slope of 45 deg or more
    // a lander released upright already leans that far, and the slope is the likelier cause.
    // Shown rounded down, so that "or more" holds of the value printed.
    let slope = (done.untouched_tipped_slope_deg * 10.0).floor() / 10.0;
    if tipped > 0 && slope >= 45.0 {
        why.push(format!(
            "{tipped} turned past 90 deg in flight (tipped) before reaching it, all on slopes \
             of {slope:.1} deg or more: a lander released upright leans that far from the \
             ground's normal before it moves, and small body rates turn it past 90 deg in a \
             long fall (see inputs.slope_deg, and the rates inputs.rate_x_deg_s and \
             inputs.rate_y_deg_s)"
        ));
    } else if tipped > 0 {
        why.push(format!(
            "{tipped} turned past 90 deg in flight (tipped) before reaching it: body rates or \
             attitude errors too large for the fall? See inputs.rate_x_deg_s, \
             inputs.rate_y_deg_s, inputs.roll_deg and inputs.pitch_deg"
        ));
    }
    tell(&format!(
        "touchdown: warning: {at}{} of the {} samples run never touched the surface before \
         simulation.t_max_s = {} s (their first_contact_s is empty): {}\n",
        done.untouched,
        done.computed,
        scenario.simulation.t_max_s,
        why.join("; ")
    ));
}
