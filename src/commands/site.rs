//! `touchdown site`: a landing-site map of a small body from its shape model: each facet's
//! effective gravity and slope, and how the lander's touchdowns end there (P(stable),
//! P(tipped), ... with 95 % intervals), as a table, a Markdown summary, a map picture and
//! a 3D page.

use super::flags::{Threads, parse_count, parse_kernel, parse_seed};
use super::print::print_out;
use crate::output::OutputSet;
use crate::output::format::Format;
use crate::run::KernelChoice;
use crate::run::site::{Made, SiteSettings};
use crate::shape::{GravitySum, OPENING};
use crate::site::estimate::{GravityDraw, Window};
use crate::sweep::Shard;
use std::path::PathBuf;

/// Units of a shape model's coordinates.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Units {
    /// Metres.
    M,
    /// Kilometres (as PDS shape models are given).
    Km,
}

/// How the facets' gravity is summed (`--gravity`).
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum GravityChoice {
    /// Exact up to 16,384 facets, the tree above that.
    Auto,
    /// Every facet and edge at every facet, in closed form (time grows as the square of
    /// the facets).
    Exact,
    /// The facets near each facet in closed form, groups of facets farther away by their
    /// moments (time grows as F log F; the attraction within 3.1e-5 of the exact sum's
    /// wherever measured).
    Tree,
}

/// Flags of `touchdown site`.
#[derive(clap::Args, Debug)]
pub struct SiteArgs {
    /// The shape model: a Wavefront OBJ file (`v` and `f` lines), a vertex-facet plate
    /// file (PDS `.tab`: `NV NF`, then rows `i x y z` and `j a b c`; SBMT `.plt`: the same
    /// with `NF` on its own line after the vertices) or Gaskell's ICQ file (SPC's
    /// `SHAPE.TXT`: `Q`, then `6 (Q+1)^2` rows `x y z`), told apart by content, of a closed
    /// surface whose facets wind counter-clockwise seen from outside, in the body-fixed frame
    /// (origin at the centre of mass).
    #[arg(value_name = "SHAPE")]
    pub shape: PathBuf,
    /// Units of the shape file's coordinates (no format says).
    #[arg(long, value_enum)]
    pub units: Units,
    /// Bulk density of the body, kg/m^3 (constant throughout).
    #[arg(long, value_name = "KG_M3", value_parser = positive)]
    pub density: f64,
    /// Rotation period, hours.
    #[arg(long, value_name = "HOURS", value_parser = positive)]
    pub spin_period: f64,
    /// Spin axis in the shape model's frame, X,Y,Z (need not be a unit vector).
    #[arg(long, value_name = "X,Y,Z", default_value = "0,0,1", value_parser = parse_axis, allow_hyphen_values = true)]
    pub spin_axis: [f64; 3],
    /// Scenario file of the lander (TOML); without it, the default scenario. Its slope and
    /// gravity are replaced by the body's range, drawn per sample.
    #[arg(long, value_name = "FILE")]
    pub scenario: Option<PathBuf>,
    /// Samples of the sweep (accepts 1e6).
    #[arg(long, value_name = "N", default_value = "1e6", value_parser = parse_count)]
    pub samples: u64,
    /// In place of --samples: as many samples as make the window of every facet a lander
    /// could stand on expect at least N (the least-served window sets them: where the window
    /// is cut, at slope 0 or 89 deg, and with gravity drawn uniformly at the smallest
    /// gravity); site.md says which.
    #[arg(long, value_name = "N", value_parser = parse_count, conflicts_with = "samples")]
    pub window_samples: Option<u64>,
    /// Seed of the sweep (overrides the scenario's `seed`).
    #[arg(long, value_name = "S", value_parser = parse_seed, allow_negative_numbers = true)]
    pub seed: Option<u64>,
    /// Half-width of a facet's window in slope, deg: its shares count the samples within
    /// this much of its slope.
    #[arg(long, value_name = "DEG", default_value = "1", value_parser = positive)]
    pub slope_window: f64,
    /// Half-width of a facet's window in gravity, as a fraction of its gravity.
    #[arg(long, value_name = "FRACTION", default_value = "0.05", value_parser = fraction)]
    pub gravity_window: f64,
    /// How the sweep draws gravity over the body's range: uniformly, or uniformly in its
    /// logarithm, which gives every facet's window the same share of the samples in gravity
    /// (fewer samples for the same least-served window, --window-samples).
    #[arg(long, value_enum, default_value = "uniform")]
    pub gravity_draw: GravityDrawChoice,
    /// Folder of the map (made if missing): sweep.arrow, facets.arrow, site.md, map.png
    /// and site.html. Running the same command again keeps the sweep, or continues it
    /// where it was interrupted.
    #[arg(long, value_name = "DIR", default_value = "site")]
    pub out_dir: PathBuf,
    /// Format of the sweep and of the facets' table.
    #[arg(long, value_enum, default_value = "arrow")]
    pub format: Format,
    /// Run only the K-th of N contiguous slices of the map's sweep, into the map's folder
    /// (`sweep.shard-K-of-N.arrow`, `.parquet` with --format parquet), and make no map; the command without --shard then
    /// merges the shards and makes the map.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<Shard>,
    /// Worker threads (`--threads`).
    #[command(flatten)]
    pub threads: Threads,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// SIMD kernel, as for `touchdown sweep`.
    #[arg(long, value_name = "KERNEL", default_value = "auto", value_parser = parse_kernel)]
    pub kernel: KernelChoice,
    /// How the facets' gravity is summed: exact, by a tree of the facets, or auto (exact
    /// up to 16,384 facets).
    #[arg(long, value_enum, default_value = "auto")]
    pub gravity: GravityChoice,
}

/// How the sweep draws gravity (`--gravity-draw`).
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum GravityDrawChoice {
    /// Uniformly over the range.
    Uniform,
    /// Uniformly in the logarithm.
    LogUniform,
}

impl From<GravityDrawChoice> for GravityDraw {
    fn from(choice: GravityDrawChoice) -> GravityDraw {
        match choice {
            GravityDrawChoice::Uniform => GravityDraw::Uniform,
            GravityDrawChoice::LogUniform => GravityDraw::LogUniform,
        }
    }
}

/// A finite number greater than 0.
fn positive(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!("expected a number greater than 0, not {s:?}")),
    }
}

/// A number greater than 0 and below 1.
fn fraction(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x > 0.0 && x < 1.0 => Ok(x),
        _ => Err(format!("expected a fraction between 0 and 1, not {s:?}")),
    }
}

/// Three finite numbers `X,Y,Z`, not all 0.
fn parse_axis(s: &str) -> Result<[f64; 3], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect::<Option<Vec<f64>>>()
        .filter(|v| v.len() == 3)
        .ok_or_else(|| format!("expected three numbers X,Y,Z, not {s:?}"))?;
    if v.iter().all(|x| *x == 0.0) {
        return Err("the spin axis may not be 0,0,0".into());
    }
    Ok([v[0], v[1], v[2]])
}

/// The map's files in `--out-dir`: the facets' table, the summary, the map picture and
/// the 3D page.
fn map_files(args: &SiteArgs) -> [PathBuf; 4] {
    let dir = &args.out_dir;
    [
        dir.join(format!("facets.{}", args.format.key())),
        dir.join("site.md"),
        dir.join("map.png"),
        dir.join("site.html"),
    ]
}

/// How the facets' gravity was summed, in words (the log and the table's metadata).
fn gravity_text(sum: GravitySum) -> String {
    match sum {
        GravitySum::Exact => "summed exactly".into(),
        GravitySum::Tree { opening } => format!(
            "summed by the tree of the facets (opening {opening}, moments to degree {})",
            crate::shape::ORDER
        ),
    }
}

/// Runs `touchdown site`.
pub fn run(args: &SiteArgs) -> anyhow::Result<()> {
    // As a sweep refuses it; how many more a map needs is known once the body's slopes and
    // gravities are (`crate::run::site`), before its sweep.
    if args.samples == 0 {
        anyhow::bail!("--samples must be at least 1: a map's facets count the sweep's samples");
    }
    if args.window_samples == Some(0) {
        anyhow::bail!("--window-samples must be at least 1: the windows' least samples");
    }
    let window = Window {
        slope_deg: args.slope_window,
        gravity_fraction: args.gravity_window,
    };
    let settings = SiteSettings {
        shape: args.shape.clone(),
        metres_per_unit: match args.units {
            Units::M => 1.0,
            Units::Km => 1000.0,
        },
        density_kg_m3: args.density,
        spin_period_h: args.spin_period,
        spin_axis: args.spin_axis,
        scenario: args.scenario.clone(),
        samples: args.samples,
        window_samples: args.window_samples,
        seed: args.seed,
        shard: args.shard,
        window,
        gravity_draw: args.gravity_draw.into(),
        out_dir: args.out_dir.clone(),
        format: args.format,
        threads: args.threads.threads,
        quiet: args.quiet,
        kernel: args.kernel,
        gravity: match args.gravity {
            GravityChoice::Auto => None,
            GravityChoice::Exact => Some(GravitySum::Exact),
            GravityChoice::Tree => Some(GravitySum::Tree { opening: OPENING }),
        },
    };
    let files = map_files(args);
    // The map's files are refused before the facets and the sweep if one may not be
    // written (an input of this command under its name, say), and written as one set.
    if args.shard.is_none() {
        crate::output::set::check(&files)?;
    }
    let run = match crate::run::site::run(&settings)? {
        Made::Map(run) => run,
        Made::Shard { shard, file, log } => {
            return print_out(
                "the map's log",
                &format!(
                    "shard {shard} of the map's sweep: {log} -> {}\nonce all {} shards are \
                     done, the same command without --shard merges them and makes the map\n",
                    file.display(),
                    shard.count
                ),
            );
        }
    };
    let set = OutputSet::reserve(&files)?;
    let [table, md, png, html] = files;
    let sweep_name = run
        .sweep_file
        .file_name()
        .unwrap_or_default()
        .to_string_lossy()
        .into_owned();
    crate::site::table::write(
        &table,
        args.format,
        &run.site,
        &crate::site::table::About {
            shape: &args.shape.display().to_string(),
            window,
            sweep_file: &sweep_name,
            sweep_text: &run.sweep_text,
            samples: run.samples,
            gravity: &gravity_text(run.gravity_sum),
        },
    )?;
    let scenario = args
        .scenario
        .as_ref()
        .map_or("the default scenario".to_string(), |p| {
            p.display().to_string()
        });
    let text = crate::site::summary::markdown(
        &run.site,
        &crate::site::summary::Sweep {
            scenario: &scenario,
            samples: run.samples,
            slope_range_deg: run.slope_range_deg,
            gravity_range_m_s2: run.gravity_range_m_s2,
            gravity_draw: args.gravity_draw.into(),
            window,
            tally: run.tally,
            t_max_s: run.t_max_s,
            warnings: run.warnings.clone(),
            least_window: run.least_window,
            window_samples: args.window_samples,
        },
    );
    crate::output::write_text(&md, &text)?;
    crate::plot::site::site_map(&run.site, &png)?;
    crate::view::site::site_page(&run.site, &html)?;
    set.commit()?;
    print_out(
        "the map's summary",
        &format!(
            "the sweep {} -> {}\nthe facets' gravity in {:.1} s, {}\n\n{text}\nwrote {}, {}, {} and {}\n",
            run.log,
            run.sweep_file.display(),
            run.gravity_s,
            gravity_text(run.gravity_sum),
            table.display(),
            md.display(),
            png.display(),
            html.display(),
        ),
    )?;
    drop(run.lock);
    Ok(())
}
