//! The runs of a landing-site map: the shape model read and checked, each facet's gravity
//! and slope, the one sweep over the (slope, gravity) range the body spans kept in the
//! map's folder (kept when done before, resumed when interrupted, run otherwise), and each
//! facet's outcome shares from it (`site::estimate`).

use super::execute::{RunOptions, warn_untouched};
use super::load::{KernelChoice, load_scenario, scenario_from_toml};
use super::signals::stop_on_signals;
use super::steps::{Done, Kept, Names, Running, run_step, shard_file, shards_there, step_of};
use super::workers::worker_pool;
use crate::output::FolderLock;
use crate::output::format::Format;
use crate::output::sweep::SweepFile;
use crate::reference::Outcome;
use crate::scenario::Scenario;
use crate::shape::{
    FacetGravity, FacetTree, GravitySum, Polyhedron, facet_gravity, read_shape, roughness_deg,
    tree_facets, unit_axis,
};
use crate::site::estimate::{
    Counts, GravityDraw, LeastWindow, Window, expected_samples, grid_bytes,
};
use crate::site::warnings::{BodyFigures, implausible_body, sweep_failures};
use crate::site::{Body, SLOPE_LIMIT_DEG, STEEP_START_DEG, Site, SiteFacet, SweepTally};
use crate::sweep::Shard;
use anyhow::{Context as _, anyhow, bail};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The settings of a landing-site map (`touchdown site`'s flags).
#[derive(Debug, Clone)]
pub struct SiteSettings {
    /// The shape model, a Wavefront OBJ or a vertex-facet plate file.
    pub shape: PathBuf,
    /// Metres per unit of the shape file's coordinates.
    pub metres_per_unit: f64,
    /// Bulk density, kg/m^3.
    pub density_kg_m3: f64,
    /// Rotation period, h.
    pub spin_period_h: f64,
    /// Spin axis in the shape model's frame (need not be a unit vector).
    pub spin_axis: [f64; 3],
    /// Scenario file of the lander; the default scenario without it.
    pub scenario: Option<PathBuf>,
    /// Samples of the sweep (set from the body where `window_samples` is given).
    pub samples: u64,
    /// The samples the least-served window of a facet a lander could stand on must expect:
    /// the sweep's `samples` are then set from the body so that it does.
    pub window_samples: Option<u64>,
    /// Overrides the scenario's seed.
    pub seed: Option<u64>,
    /// The slice of the sweep to run, and no map (`--shard K/N`).
    pub shard: Option<Shard>,
    /// The window a facet's shares count samples in.
    pub window: Window,
    /// How the sweep draws gravity over the body's range (`--gravity-draw`).
    pub gravity_draw: GravityDraw,
    /// The map's folder.
    pub out_dir: PathBuf,
    /// Format of the sweep and of the facets' table.
    pub format: Format,
    /// Worker threads (default: one per core).
    pub threads: Option<usize>,
    /// No progress bar, no banner.
    pub quiet: bool,
    /// The kernel the sweep runs with (`--kernel`).
    pub kernel: KernelChoice,
    /// How the facets' gravity is summed; `None`: by the facets' count
    /// ([`GravitySum::auto`]).
    pub gravity: Option<GravitySum>,
}

/// What a site's run leaves: the map, its sweep and a line on what was done with it.
pub struct SiteRun {
    /// Every facet's numbers.
    pub site: Site,
    /// The sweep file, in the map's folder.
    pub sweep_file: PathBuf,
    /// The sweep's scenario text (the lander's, with slope and gravity drawn).
    pub sweep_text: String,
    /// The ranges of slope (deg) and gravity (m/s^2) the sweep drew.
    pub slope_range_deg: (f64, f64),
    /// See `slope_range_deg`.
    pub gravity_range_m_s2: (f64, f64),
    /// What was done with the sweep.
    pub log: String,
    /// What its samples did beyond the facets' shares.
    pub tally: SweepTally,
    /// `simulation.t_max_s` of its scenario, s.
    pub t_max_s: f64,
    /// The warnings on its samples (diverged, never touched), told on stderr too.
    pub warnings: Vec<String>,
    /// Seconds to compute the facets' gravity.
    pub gravity_s: f64,
    /// How it was summed.
    pub gravity_sum: GravitySum,
    /// The samples of the sweep (`SiteSettings::samples`, or as `window_samples` set them).
    pub samples: u64,
    /// The window of a facet a lander could stand on that expects the fewest samples (none
    /// where no facet is flat enough).
    pub least_window: Option<LeastWindow>,
    /// The folder, locked until the map is written.
    pub lock: FolderLock,
}

/// The most samples `--window-samples` may set: beyond, the sweep would run for days on
/// any machine (the default map's 1e6 takes minutes).
const MOST_SIZED_SAMPLES: f64 = 1e10;

/// The window that expects the least share of the sweep's samples among the facets a
/// lander could stand on (`expected` a share: of one sample); `None` where there is no such
/// facet.
fn least_window(
    args: &SiteSettings,
    gravity: &[FacetGravity],
    slopes: (f64, f64),
    gravities: (f64, f64),
) -> Option<LeastWindow> {
    gravity
        .iter()
        .enumerate()
        .filter(|(_, f)| f.slope_deg < SLOPE_LIMIT_DEG)
        .map(|(i, f)| LeastWindow {
            facet: i as u32,
            slope_deg: f.slope_deg,
            gravity_m_s2: f.effective_magnitude_m_s2,
            expected: expected_samples(
                1,
                slopes.1,
                gravities,
                args.gravity_draw,
                args.window,
                (f.slope_deg, f.effective_magnitude_m_s2),
            ),
        })
        .min_by(|a, b| a.expected.total_cmp(&b.expected))
}

/// `args` with its samples set so that the least-served window, `least` (its share of the
/// samples), expects `window_samples` (where given): `ceil(window_samples / share)`.
fn sized(args: &SiteSettings, least: Option<LeastWindow>) -> anyhow::Result<SiteSettings> {
    let Some(wanted) = args.window_samples else {
        return Ok(args.clone());
    };
    let Some(least) = least else {
        bail!("--window-samples {wanted}: no facet of this body is flat enough to stand on");
    };
    let needed = (wanted as f64 / least.expected).ceil();
    if !needed.is_finite() || needed > MOST_SIZED_SAMPLES {
        bail!(
            "--window-samples {wanted}: the least-served window (facet {}, slope {:.2} deg, \
             gravity {:.4e} m/s^2) holds {:.3e} of the sweep's samples, so the sweep would need \
             {needed:.3e} samples, more than {MOST_SIZED_SAMPLES:e}: ask for fewer, or widen \
             --slope-window or --gravity-window",
            least.facet,
            least.slope_deg,
            least.gravity_m_s2,
            least.expected
        );
    }
    Ok(SiteSettings {
        samples: (needed as u64).max(1),
        ..args.clone()
    })
}

/// Tells `text` on stderr as a warning (`workers::tell`: never a panic where stderr is gone).
fn warn(text: &str) {
    super::workers::tell(&format!("touchdown: warning: {text}\n"));
}

/// The units of the shape file, by name.
fn units(args: &SiteSettings) -> &'static str {
    if args.metres_per_unit == 1000.0 {
        "km"
    } else {
        "m"
    }
}

/// The body's figures the warnings judge.
fn figures<'a>(args: &SiteSettings, volume_m3: f64) -> BodyFigures<'a> {
    BodyFigures {
        units: units(args),
        metres_per_unit: args.metres_per_unit,
        volume_m3,
        density_kg_m3: args.density_kg_m3,
    }
}

/// A gravity estimated to take longer than this, s, says so before it starts, on a
/// terminal or not: "more than a few minutes".
const GRAVITY_TOLD_S: f64 = 180.0;

/// The time of a whole of `n` parts on `threads` threads, s, estimated from the time of a
/// few of them spread over it (at most 16, for at most about 0.2 s), and how many were
/// timed: `part(k)` does part `k`.
fn estimate(n: usize, threads: usize, part: impl Fn(usize)) -> (f64, usize) {
    let tried = n.min(16);
    let started = Instant::now();
    let mut k = 0;
    while k < tried && (k == 0 || started.elapsed().as_secs_f64() < 0.2) {
        part(k * n / tried);
        k += 1;
    }
    let per_part_s = started.elapsed().as_secs_f64() / k.max(1) as f64;
    (per_part_s * n as f64 / threads.max(1) as f64, k)
}

/// Says, before it starts, how long the facets' gravity will take where that is more than
/// `GRAVITY_TOLD_S` (a terminal's bar is all that would say so): summed exactly it costs
/// the square of the facets, by the tree (`tree`) about `F log F`.
fn tell_gravity_time(
    args: &SiteSettings,
    poly: &Polyhedron,
    tree: Option<&FacetTree>,
    axis: [f64; 3],
    omega: f64,
) {
    let threads = rayon::current_num_threads();
    let n = poly.mesh().facet_geometry().len();
    let plural = if threads == 1 { "" } else { "s" };
    let shape = args.shape.display();
    if let Some(tree) = tree {
        let (estimate_s, measured) = estimate(tree.leaves(), threads, |k| {
            std::hint::black_box(tree.leaf_sums(k));
        });
        if estimate_s > GRAVITY_TOLD_S {
            warn(&format!(
                "{shape}: the gravity of its {n} facets will take about {} on {threads} \
                 thread{plural} by the tree of the facets (measured on {measured} of its {} \
                 leaves); Ctrl-C stops it",
                super::eta::duration(estimate_s),
                tree.leaves(),
            ));
        }
        return;
    }
    let (estimate_s, measured) = estimate(n, threads, |f| {
        std::hint::black_box(facet_gravity(poly, f, axis, omega));
    });
    if estimate_s <= GRAVITY_TOLD_S {
        return;
    }
    // The cost goes as the square of the facets.
    let ten_minutes = (n as f64 * (600.0 / estimate_s).sqrt()).floor();
    warn(&format!(
        "{shape}: the gravity of its {n} facets summed exactly will take about {} on {threads} \
         thread{plural} (measured on {measured} of them; it grows as the square of the facets: \
         a model of {ten_minutes} facets takes about 10 min; --gravity tree sums it in about \
         F log F); Ctrl-C stops it",
        super::eta::duration(estimate_s),
    ));
}

/// How far from the origin, as a fraction of the body's size (its bounding box's diagonal),
/// its centre of mass at constant density may lie before a map warns: 1 % (the Itokawa
/// radar model's is 0.28 %, a shape model's origin being its centre of mass).
const OFF_CENTRE: f64 = 0.01;

/// Warns where the body's centre of mass at constant density lies far from the origin of
/// its frame, about which the spin turns and the latitudes are taken.
fn warn_off_centre(shape: &Path, poly: &Polyhedron) {
    let c = poly.centre_of_mass_m();
    let off = c.iter().map(|x| x * x).sum::<f64>().sqrt();
    // Shown to the millimetre, without a "-0.000".
    let c = c.map(|x| if x.abs() < 0.0005 { 0.0 } else { x });
    let size = poly.mesh().size_m();
    if off > OFF_CENTRE * size {
        warn(&format!(
            "{}: its centre of mass at constant density lies {off:.3} m \
             ({:.1} % of its size) from the origin, at ({:.3}, {:.3}, {:.3}) m; the spin turns \
             about the origin and the latitudes are taken from it (a shape model is given about \
             its centre of mass): recentre the model, unless its origin is a centre of mass \
             measured otherwise",
            shape.display(),
            100.0 * off / size,
            c[0],
            c[1],
            c[2]
        ));
    }
}

/// Reads and checks the shape model, and computes every facet's gravity and slope on `pool`
/// (summed as `args.gravity` says) and its roughness.
fn body_of(
    args: &SiteSettings,
    pool: &rayon::ThreadPool,
) -> anyhow::Result<(Body, Vec<FacetGravity>, Vec<f64>, GravitySum)> {
    let mesh = read_shape(&args.shape, args.metres_per_unit)?
        .check()
        .map_err(|e| anyhow!("{}: {e}", args.shape.display()))?;
    let poly = Polyhedron::new(mesh, args.density_kg_m3)
        .map_err(|e| anyhow!("{}: {e}", args.shape.display()))?;
    if !poly.mass_kg().is_finite() {
        bail!(
            "--density {} kg/m^3: the body's mass, the density times its volume of {:.4e} m^3, \
             overflows (is no number), and so would its gravity: check --density and its unit, \
             kg/m^3",
            crate::site::given_number(args.density_kg_m3),
            poly.mesh().volume_m3()
        );
    }
    warn_off_centre(&args.shape, &poly);
    if let Some(w) = implausible_body(&figures(args, poly.mesh().volume_m3())) {
        warn(&format!("{}: {w}", args.shape.display()));
    }
    let axis = unit_axis(args.spin_axis).map_err(|e| anyhow!("--spin-axis: {e}"))?;
    let omega = 2.0 * std::f64::consts::PI / (args.spin_period_h * 3600.0);
    let count = poly.mesh().facet_geometry().len();
    let sum = args.gravity.unwrap_or(GravitySum::auto(count));
    let tree = match sum {
        GravitySum::Exact => None,
        GravitySum::Tree { opening } => Some(pool.install(|| FacetTree::new(poly.mesh(), opening))),
    };
    pool.install(|| tell_gravity_time(args, &poly, tree.as_ref(), axis, omega));
    let bar = super::execute::progress_bar(count as u64, !args.quiet, "facets");
    let facets = pool.install(|| match &tree {
        None => crate::shape::facets_told(&poly, axis, omega, sum, |k| bar.inc(k as u64)),
        Some(tree) => tree_facets(&poly, tree, axis, omega, |k| bar.inc(k as u64)),
    });
    bar.finish_and_clear();
    drop(tree);
    let mesh = poly.mesh();
    let roughness = roughness_deg(mesh);
    let body = Body {
        name: args
            .shape
            .file_stem()
            .map_or("body".into(), |s| s.to_string_lossy().into_owned()),
        vertices: mesh.mesh().vertices.clone(),
        triangles: mesh
            .mesh()
            .facets
            .iter()
            .map(|f| [f[0], f[1], f[2]])
            .collect(),
        density_kg_m3: args.density_kg_m3,
        spin_period_h: args.spin_period_h,
        spin_axis: axis,
        mass_kg: poly.mass_kg(),
        volume_m3: mesh.volume_m3(),
        area_m2: mesh.surface_area_m2(),
        centre_of_mass_m: poly.centre_of_mass_m(),
    };
    Ok((body, facets, roughness, sum))
}

/// The ranges the sweep draws: slopes from 0 to the steepest facet's (below
/// `SLOPE_LIMIT_DEG`) and gravities over the facets', each widened by the window, so
/// that no facet's window is cut but at slope 0.
fn ranges(facets: &[FacetGravity], window: Window) -> anyhow::Result<((f64, f64), (f64, f64))> {
    let standing = || {
        facets
            .iter()
            .filter(|f| f.slope_deg.is_finite() && f.slope_deg < SLOPE_LIMIT_DEG)
    };
    let steepest = standing().map(|f| f.slope_deg).fold(f64::NAN, f64::max);
    if steepest.is_nan() {
        bail!(
            "no facet of the shape model has a slope a lander can stand on (below \
             {SLOPE_LIMIT_DEG} deg against its effective gravity): a spin this fast throws the \
             surface off (check --spin-period and its units, hours)"
        );
    }
    let g = standing().map(|f| f.effective_magnitude_m_s2);
    let (g_min, g_max) = g.fold((f64::INFINITY, 0.0_f64), |(a, b), x| (a.min(x), b.max(x)));
    if g_min.is_nan() || g_min <= 0.0 {
        bail!(
            "the effective gravity vanishes on the body (the spin balances the attraction there): no lander can settle"
        );
    }
    Ok((
        (0.0, (steepest + window.slope_deg).min(SLOPE_LIMIT_DEG)),
        (
            g_min * (1.0 - window.gravity_fraction),
            g_max * (1.0 + window.gravity_fraction),
        ),
    ))
}

/// The scenario text of the site's sweep: the lander's `base` with its slopes drawn
/// uniformly over `slopes` and its gravity over `gravities` as `args.gravity_draw` says.
fn sweep_text(
    args: &SiteSettings,
    base: &str,
    slopes: (f64, f64),
    gravities: (f64, f64),
) -> anyhow::Result<(String, Scenario)> {
    let mut table: toml::Table = base
        .parse()
        .map_err(|e| anyhow!("cannot read the scenario as TOML: {e}"))?;
    let drawn = |dist: &str, (min, max): (f64, f64)| {
        let mut t = toml::Table::new();
        t.insert("dist".into(), dist.into());
        t.insert("min".into(), min.into());
        t.insert("max".into(), max.into());
        toml::Value::Table(t)
    };
    let gravity = match args.gravity_draw {
        GravityDraw::Uniform => "uniform",
        GravityDraw::LogUniform => "log-uniform",
    };
    table.insert("gravity_m_s2".into(), drawn(gravity, gravities));
    let inputs = table
        .entry("inputs")
        .or_insert_with(|| toml::Value::Table(toml::Table::new()));
    let Some(inputs) = inputs.as_table_mut() else {
        bail!("the scenario's `inputs` is not a table");
    };
    inputs.insert("slope_deg".into(), drawn("uniform", slopes));
    // The body by its file's name: the sweep depends on its ranges alone, so a map made
    // again from another folder keeps it.
    let text = format!(
        "# touchdown site: {} ({} kg/m^3, {} h), slope and gravity drawn over the body's\n{}",
        args.shape.file_name().map_or_else(
            || args.shape.display().to_string(),
            |n| n.to_string_lossy().into_owned()
        ),
        crate::site::given_number(args.density_kg_m3),
        crate::site::given_number(args.spin_period_h),
        toml::to_string(&table).context("cannot write the site's scenario")?
    );
    let scenario = scenario_from_toml(&text).map_err(|e| {
        anyhow!("the site's sweep (the scenario with slope and gravity drawn): {e}")
    })?;
    if scenario.table.is_some() || scenario.design == crate::scenario::Design::SobolIndices {
        bail!(
            "a site's sweep draws its samples independently: its scenario may not be a Sobol-index design"
        );
    }
    Ok((text, scenario))
}

/// How messages name the map's sweep.
fn names() -> Names {
    Names {
        whose: "this map's sweep".into(),
        owner: "map",
        sweep: "the map's sweep".into(),
        sweep_long: "the map's sweep".into(),
        set_by_flags: &[
            (
                "inputs.slope_deg",
                "the slopes drawn, from 0 to the steepest facet's plus --slope-window",
            ),
            (
                "gravity_m_s2",
                "the gravities drawn (as --gravity-draw says), the facets' (summed as --gravity \
                 says) widened by --gravity-window",
            ),
        ],
    }
}

/// Does the site's sweep, or its shard `args.shard`: kept when done before, merged from
/// its shards, resumed when interrupted, run otherwise; returns what was done.
fn sweep(
    args: &SiteSettings,
    pool: &rayon::ThreadPool,
    file: &Path,
    text: &str,
    scenario: &Scenario,
) -> anyhow::Result<String> {
    let kept = Kept {
        text,
        scenario,
        file,
        samples: args.samples,
        names: names(),
    };
    let step = step_of(&kept, args.shard)?;
    let stop = stop_on_signals()?;
    let options = RunOptions {
        pool,
        stop: &stop,
        progress: !args.quiet,
        banner: false,
        auto_kernel: matches!(args.kernel, KernelChoice::Auto),
        keep: false,
        counter: None,
    };
    let running = Running {
        shard: args.shard,
        format: args.format,
        kernel: args.kernel,
        continue_with: "the same touchdown site command again",
        options: &options,
    };
    let ran = |done: &super::execute::Executed| {
        // A map tells of its samples that never touched once counted, with their likely
        // cause at the body's gravity (`sweep_failures`); a shard, as a sweep does.
        if args.shard.is_some() {
            warn_untouched(done, scenario, "in the site's sweep, ");
        }
        format!(
            "{} samples in {:.1} s{}",
            done.computed,
            done.wall_s,
            if done.rows > done.computed {
                format!(", {} kept", done.rows - done.computed)
            } else {
                String::new()
            }
        )
    };
    Ok(match run_step(&kept, step, &running)? {
        Done::Kept => "kept (done before)".into(),
        Done::Merged { shards, rows } => format!("merged from {shards} shards ({rows} samples)"),
        Done::Resumed(done) | Done::Ran(done) => ran(&done),
    })
}

/// Counts what one batch of the sweep's samples did beyond their outcomes into `tally`.
fn tally_batch(
    b: &crate::output::sweep::SweepBatch<'_>,
    outcomes: &[Outcome],
    tally: &mut SweepTally,
) -> anyhow::Result<()> {
    let first_contact = b.f64s("first_contact_s")?;
    let input = |name: &str| -> anyhow::Result<Option<&arrow_array::Float64Array>> {
        if b.has(name) {
            b.f64s(name).map(Some)
        } else {
            Ok(None)
        }
    };
    let (release, rising) = (input("release_height_m")?, input("velocity_error_z_m_s")?);
    let slope = b.f64s("slope_deg")?;
    for (i, o) in outcomes.iter().enumerate() {
        tally.samples += 1;
        tally.diverged += u64::from(*o == Outcome::Diverged);
        tally.held += u64::from(*o == Outcome::Held);
        // A sample that diverged (at its first step, as often) is told of as that alone.
        if arrow_array::Array::is_null(first_contact, i) && *o != Outcome::Diverged {
            tally.untouched += 1;
            if *o == Outcome::Tipped && slope.value(i) >= STEEP_START_DEG {
                tally.untouched_steep += 1;
                tally.untouched_steep_slope_deg = if tally.untouched_steep == 1 {
                    slope.value(i)
                } else {
                    tally.untouched_steep_slope_deg.min(slope.value(i))
                };
                continue;
            }
            if let Some(r) = release {
                tally.untouched_release_m = tally.untouched_release_m.max(r.value(i));
            }
            if let Some(v) = rising {
                tally.untouched_rising_m_s = tally.untouched_rising_m_s.max(v.value(i));
            }
        }
    }
    Ok(())
}

/// The sweep's samples counted for the facets' windows, and what they did beyond.
fn counts(
    file: &Path,
    slopes: (f64, f64),
    gravities: (f64, f64),
    window: Window,
) -> anyhow::Result<(Counts, SweepTally)> {
    let mut f = SweepFile::open(file)?;
    let mut batches = f.batches();
    // One batch's samples at a time: the counts keep none of them.
    let mut batch = Vec::new().into_iter();
    let mut failed = None;
    let mut tally = SweepTally::default();
    let samples = std::iter::from_fn(|| {
        loop {
            if let Some(sample) = batch.next() {
                return Some(sample);
            }
            let read = batches.next()?.and_then(|b| {
                let (slope, gravity) = (b.f64s("slope_deg")?, b.f64s("gravity_m_s2")?);
                let outcomes = b.outcomes()?;
                tally_batch(&b, &outcomes, &mut tally)?;
                Ok(outcomes
                    .into_iter()
                    .enumerate()
                    .map(|(i, o)| (slope.value(i), gravity.value(i), o))
                    .collect::<Vec<(f64, f64, Outcome)>>())
            });
            match read {
                Ok(v) => batch = v.into_iter(),
                Err(e) => {
                    failed = Some(e);
                    return None;
                }
            }
        }
    });
    let counts = Counts::new(samples, slopes.1, gravities, window);
    match failed {
        Some(e) => Err(e),
        None => Ok((counts, tally)),
    }
}

/// Samples the median facet's window must hold on average for a map to be made: with
/// fewer, most facets would have none.
const LEAST_MEDIAN_WINDOW_SAMPLES: f64 = 1.0;

/// Refuses `--samples` too few for the map, before its sweep: the facets a lander can stand
/// on (`gravity`) would mostly get no sample in their windows.
fn check_samples(
    args: &SiteSettings,
    gravity: &[FacetGravity],
    slopes: (f64, f64),
    gravities: (f64, f64),
) -> anyhow::Result<()> {
    let mut expected: Vec<f64> = gravity
        .iter()
        .filter(|f| f.slope_deg < SLOPE_LIMIT_DEG)
        .map(|f| {
            expected_samples(
                args.samples,
                slopes.1,
                gravities,
                args.gravity_draw,
                args.window,
                (f.slope_deg, f.effective_magnitude_m_s2),
            )
        })
        .collect();
    expected.sort_by(f64::total_cmp);
    let Some(&median) = expected.get(expected.len() / 2) else {
        return Ok(());
    };
    if median >= LEAST_MEDIAN_WINDOW_SAMPLES {
        return Ok(());
    }
    let needed = args.samples as f64 * LEAST_MEDIAN_WINDOW_SAMPLES / median;
    bail!(
        "--samples {}: too few for this map: the median facet's window (+-{} deg of slope, \
         +-{} % of gravity) would hold {median:.3} samples on average, and most facets none; \
         this body's map needs at least {} samples (one in the median window), and about 100 \
         times that for shares known to +-0.1",
        args.samples,
        args.window.slope_deg,
        100.0 * args.window.gravity_fraction,
        if needed.is_finite() {
            format!("{:.0}", needed.ceil())
        } else {
            "more".into()
        }
    )
}

/// The most memory, bytes, a map's grid takes where the machine does not say what it has
/// available (not Linux): 4 GB, thousands of times the default windows' grid on the
/// Itokawa model (under 1 MB).
const UNKNOWN_MEMORY_CAP: f64 = 4e9;

/// Refuses windows so fine that the counts' grid would not fit the machine, before the
/// sweep runs.
fn check_grid(
    args: &SiteSettings,
    slopes: (f64, f64),
    gravities: (f64, f64),
) -> anyhow::Result<()> {
    let bytes = grid_bytes(slopes.1, gravities, args.window);
    // Beyond any machine (and beyond what a grid's index can count): refused outright.
    if bytes.is_nan() || bytes >= 2f64.powi(50) {
        bail!(
            "--slope-window {} and --gravity-window {}: windows this fine would need a grid of \
             {} of memory to count the sweep's samples in: widen them",
            args.window.slope_deg,
            args.window.gravity_fraction,
            super::memory::shown_bytes(bytes.min(u64::MAX as f64) as u64)
        );
    }
    // A shard counts nothing: the machine that merges the shards makes the grid.
    if args.shard.is_some() {
        return Ok(());
    }
    let what = || {
        format!(
            "--slope-window {} and --gravity-window {}: the grid that counts the sweep's \
             samples in windows this fine",
            args.window.slope_deg, args.window.gravity_fraction
        )
    };
    // Where the machine does not say what it has, a grid past UNKNOWN_MEMORY_CAP is refused.
    if super::memory::available_bytes().is_none() && bytes > UNKNOWN_MEMORY_CAP {
        bail!(
            "{} would hold about {} of memory, more than the {} a map takes where the \
             machine does not say what it has: widen them",
            what(),
            super::memory::shown_bytes(bytes as u64),
            super::memory::shown_bytes(UNKNOWN_MEMORY_CAP as u64)
        );
    }
    super::memory::check_fits(bytes as u64, what)
}

/// What a site's run made.
pub enum Made {
    /// The map.
    Map(Box<SiteRun>),
    /// One shard of its sweep (`--shard K/N`), and no map yet.
    Shard {
        /// The slice run.
        shard: Shard,
        /// The shard's file, in the map's folder.
        file: PathBuf,
        /// What was done with it.
        log: String,
    },
}

/// Makes the map: the body, its sweep (run, resumed, merged from its shards or kept) and
/// each facet's shares; or with `--shard K/N`, the body and that slice of its sweep.
pub fn run(args: &SiteSettings) -> anyhow::Result<Made> {
    let dir = &args.out_dir;
    if dir.exists() && !dir.is_dir() {
        bail!("--out-dir {}: that is a file, not a folder", dir.display());
    }
    let (_, base_text) = load_scenario(args.scenario.as_ref(), args.seed)?;
    let ext = match args.format {
        Format::Arrow => "arrow",
        Format::Parquet => "parquet",
    };
    let sweep_file = dir.join(format!("sweep.{ext}"));
    // Shards missing or of two counts are refused by their names before the facets'
    // gravity, the costly part; what they hold is compared once the sweep's text is known.
    if args.shard.is_none()
        && !sweep_file.exists()
        && !crate::output::interrupted_path(&sweep_file).exists()
    {
        shards_there(&sweep_file, &names())?;
    }
    let pool = worker_pool(args.threads)?;
    let started = std::time::Instant::now();
    let (body, gravity, roughness, gravity_sum) = body_of(args, &pool)?;
    let gravity_s = started.elapsed().as_secs_f64();
    let (slopes, gravities) = ranges(&gravity, args.window)?;
    check_grid(args, slopes, gravities)?;
    let least = least_window(args, &gravity, slopes, gravities);
    let args = &sized(args, least)?;
    check_samples(args, &gravity, slopes, gravities)?;
    // What the least-served window expects of the samples the sweep takes.
    let least = least.map(|w| LeastWindow {
        expected: w.expected * args.samples as f64,
        ..w
    });
    let (text, scenario) = sweep_text(args, &base_text, slopes, gravities)?;
    std::fs::create_dir_all(dir)
        .map_err(|e| anyhow!("cannot make the map's folder {}: {e}", dir.display()))?;
    // Shared by the shards of one map, which a cluster runs side by side.
    let lock = FolderLock::acquire(dir, args.shard.is_some())?;
    let log = sweep(args, &pool, &sweep_file, &text, &scenario)?;
    if let Some(shard) = args.shard {
        return Ok(Made::Shard {
            shard,
            file: shard_file(&sweep_file, shard),
            log,
        });
    }
    let (counts, tally) = counts(&sweep_file, slopes, gravities, args.window)?;
    // The facets' gravities, without the windows' widening.
    let g_range = (
        gravities.0 / (1.0 - args.window.gravity_fraction),
        gravities.1 / (1.0 + args.window.gravity_fraction),
    );
    let warnings = sweep_failures(
        &tally,
        &figures(args, body.volume_m3),
        g_range,
        (
            scenario.simulation.t_max_s,
            scenario.initial.start != crate::scenario::Start::Touchdown,
        ),
    );
    for w in &warnings {
        warn(&format!("in the map's sweep, {w}"));
    }
    let facets = gravity
        .iter()
        .zip(&roughness)
        .enumerate()
        .map(|(i, (f, &rough))| {
            let standing = f.slope_deg < SLOPE_LIMIT_DEG
                && counts.covers(f.slope_deg, f.effective_magnitude_m_s2);
            let (samples, shares) = if standing {
                counts.shares(f.slope_deg, f.effective_magnitude_m_s2, args.window)
            } else {
                (0, None)
            };
            SiteFacet {
                facet: i as u32,
                centroid_m: f.centroid_m,
                latitude_deg: f.latitude_deg,
                longitude_deg: f.longitude_deg,
                normal: f.normal,
                area_m2: f.area_m2,
                effective_gravity_m_s2: f.effective_m_s2,
                gravity_m_s2: f.effective_magnitude_m_s2,
                slope_deg: f.slope_deg,
                roughness_deg: rough,
                samples,
                shares,
            }
        })
        .collect();
    Ok(Made::Map(Box::new(SiteRun {
        site: Site { body, facets },
        sweep_file,
        sweep_text: text,
        slope_range_deg: slopes,
        gravity_range_m_s2: gravities,
        log,
        tally,
        t_max_s: scenario.simulation.t_max_s,
        warnings,
        gravity_s,
        gravity_sum,
        samples: args.samples,
        least_window: least,
        lock,
    })))
}
