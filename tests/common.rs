//! Helpers shared by the end-to-end tests of the command line (`cli`, `sweep_cli`): fresh
//! temp folders, runs of the `touchdown` binary, bad-input checks and the Python readers;
//! and the table of measured against expected values of the validation tests
//! (`validation`, `thrust`).

use std::fmt::Write as _;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

pub(crate) const BIN: &str = env!("CARGO_BIN_EXE_touchdown");

/// A short scenario: the default sweep with flights cut at 20 s.
pub(crate) const SHORT: &str = "[simulation]\nt_max_s = 20.0\n";

/// The short scenario with a three-leg lander.
pub(crate) const THREE_LEGS: &str = "[lander]\nlegs = 3\n\n[simulation]\nt_max_s = 20.0\n";

/// The `[inputs]` lines of a lander set down: its release height and its roll and pitch
/// (TOML values: a number or a distribution) as given, no velocity or rate errors. Every
/// test of set-down landers takes its lines from here.
macro_rules! set_down_lines {
    ($release_height:expr, $attitude:expr) => {
        concat!(
            "release_height_m = ",
            $release_height,
            "\nvelocity_error_x_m_s = 0.0\nvelocity_error_y_m_s = 0.0\nvelocity_error_z_m_s = 0.0\n",
            "roll_deg = ",
            $attitude,
            "\npitch_deg = ",
            $attitude,
            "\nrate_x_deg_s = 0.0\nrate_y_deg_s = 0.0\nrate_z_deg_s = 0.0\n"
        )
    };
}
pub(crate) use set_down_lines;

/// `[inputs]` lines of a lander set down rather than dropped: no fall, no velocity,
/// attitude or rate errors.
pub(crate) const SET_DOWN: &str = set_down_lines!("0.0", "0.0");

/// A fresh, empty folder for one test.
pub(crate) struct TempDir(PathBuf);

impl TempDir {
    pub(crate) fn new(test: &str) -> TempDir {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let dir =
            std::env::temp_dir().join(format!("touchdown-cli-{test}-{}-{n}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create the test's temp folder");
        TempDir(dir)
    }

    pub(crate) fn path(&self) -> &Path {
        &self.0
    }

    pub(crate) fn join(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }

    pub(crate) fn write(&self, name: &str, text: &str) -> PathBuf {
        let p = self.join(name);
        std::fs::write(&p, text).expect("write a test file");
        p
    }

    /// Names of the entries in the folder, sorted.
    pub(crate) fn entries(&self) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(&self.0)
            .expect("list the temp folder")
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        if std::thread::panicking() {
            eprintln!("kept the files of the failed test in {}", self.0.display());
        } else {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

/// What a run of the binary gave.
pub(crate) struct Run {
    pub(crate) args: Vec<String>,
    pub(crate) code: Option<i32>,
    pub(crate) stdout: String,
    pub(crate) stderr: String,
}

impl Run {
    /// Panics, showing the whole run, unless it succeeded quietly.
    pub(crate) fn assert_ok(&self) -> &Self {
        assert!(
            self.code == Some(0) && self.stderr.is_empty(),
            "expected success of {self}"
        );
        self
    }
}

impl std::fmt::Display for Run {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "`touchdown {}`: exit code {:?}\n--- stdout ---\n{}--- stderr ---\n{}--------------",
            self.args.join(" "),
            self.code,
            self.stdout,
            self.stderr
        )
    }
}

/// A `PATH` for shell lines as the README prints them: `touchdown` is this build and
/// `python3` the tests' Python environment, both in `DIR/bin`, ahead of the caller's `PATH`.
pub(crate) fn readme_path(dir: &TempDir) -> String {
    let bin = dir.join("bin");
    std::fs::create_dir_all(&bin).expect("make the folder of the README's commands");
    // A script, not a link: a virtual environment's interpreter knows it by its own path.
    let script = bin.join("python3");
    std::fs::write(&script, format!("#!/bin/sh\nexec '{}' \"$@\"\n", python()))
        .expect("write the python3 script");
    std::fs::set_permissions(&script, std::os::unix::fs::PermissionsExt::from_mode(0o755))
        .expect("make the python3 script executable");
    std::os::unix::fs::symlink(BIN, bin.join("touchdown")).expect("link the touchdown binary");
    format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    )
}

/// Runs `touchdown ARGS` in `dir`, without a backtrace setting from the caller's
/// environment (so that a panic shows its usual `RUST_BACKTRACE` note).
pub(crate) fn touchdown(dir: &Path, args: &[&str]) -> Run {
    let out = Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .env_remove("RUST_BACKTRACE")
        .env_remove("RUST_LIB_BACKTRACE")
        .output()
        .expect("run the touchdown binary");
    Run {
        args: args.iter().map(ToString::to_string).collect(),
        code: out.status.code(),
        stdout: String::from_utf8(out.stdout).expect("stdout is UTF-8"),
        stderr: String::from_utf8(out.stderr).expect("stderr is UTF-8"),
    }
}

/// The texts of a text column (`outcome`, `limits_broken`, a kept column), plain or coded
/// into a dictionary, a null as "" (a panic if it is not text).
pub(crate) fn texts(column: &dyn arrow_array::Array) -> Vec<String> {
    let t = touchdown::output::read::Texts::of(column)
        .unwrap_or_else(|| panic!("a column of {}, not text", column.data_type()));
    t.iter().map(|v| v.unwrap_or("").to_string()).collect()
}

/// Writes the Arrow file `src` again as `dst` with its coded text columns (dictionaries:
/// `outcome`, `limits_broken`) as plain text (`Utf8`), as sweeps wrote them before they were
/// coded: the same rows, batches, field metadata and schema metadata.
pub(crate) fn plain_copy(src: &Path, dst: &Path) {
    use arrow_array::{ArrayRef, RecordBatch, StringArray};
    use arrow_schema::{DataType, Schema};
    use std::sync::Arc;
    let file = std::fs::File::open(src).expect("open the file");
    let reader = arrow_ipc::reader::FileReader::try_new(file, None).expect("an Arrow file");
    let schema = reader.schema();
    let fields = schema.fields().iter().map(|f| match f.data_type() {
        DataType::Dictionary(..) => Arc::new(f.as_ref().clone().with_data_type(DataType::Utf8)),
        _ => f.clone(),
    });
    let plain = Arc::new(Schema::new_with_metadata(
        fields.collect::<Vec<_>>(),
        schema.metadata().clone(),
    ));
    let out = std::fs::File::create(dst).expect("create the copy");
    let mut w = arrow_ipc::writer::FileWriter::try_new(out, &plain).unwrap();
    for b in reader {
        let b = b.expect("a batch");
        let columns = b.columns().iter().map(|c| match c.data_type() {
            DataType::Dictionary(..) => {
                Arc::new(StringArray::from_iter_values(texts(c.as_ref()))) as ArrayRef
            }
            _ => c.clone(),
        });
        w.write(&RecordBatch::try_new(plain.clone(), columns.collect()).unwrap())
            .unwrap();
    }
    w.finish().unwrap();
}

/// The texts of column `name` over `batches` (a panic if a batch lacks it).
pub(crate) fn batch_texts(batches: &[arrow_array::RecordBatch], name: &str) -> Vec<String> {
    let columns = batches.iter().map(|b| {
        b.column_by_name(name)
            .unwrap_or_else(|| panic!("no column {name}"))
    });
    columns.flat_map(|c| texts(c.as_ref())).collect()
}

/// Column `name` of the Arrow file at `path`, as `f64` (`None` if it has no such column).
pub(crate) fn arrow_column(path: &Path, name: &str) -> Option<Vec<f64>> {
    arrow_values::<arrow_array::types::Float64Type>(path, name)
}

/// Column `name` of the Arrow file at `path`, of unsigned 32-bit integers (`None` if it has
/// no such column).
pub(crate) fn arrow_u32s(path: &Path, name: &str) -> Option<Vec<u32>> {
    arrow_values::<arrow_array::types::UInt32Type>(path, name)
}

/// Column `name` of the Arrow file at `path`, of the primitive type `T` (`None` if it has
/// no such column; a panic if it is of another type).
fn arrow_values<T: arrow_array::ArrowPrimitiveType>(
    path: &Path,
    name: &str,
) -> Option<Vec<T::Native>> {
    let file = std::fs::File::open(path).expect("open the file");
    let reader = arrow_ipc::reader::FileReader::try_new(file, None).expect("an Arrow file");
    let mut out = Vec::new();
    for b in reader {
        let b = b.expect("a batch");
        let c = b.column_by_name(name)?;
        let c = c
            .as_any()
            .downcast_ref::<arrow_array::PrimitiveArray<T>>()
            .unwrap_or_else(|| panic!("{name}: {} values", T::DATA_TYPE));
        out.extend(c.values().iter().copied());
    }
    Some(out)
}

pub(crate) fn read_bytes(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

// ---------------------------------------------------------------------------------------
// Bad input.

/// One bad input: a scenario file (written as `scenario.toml` and passed with `--scenario`
/// when given), further arguments of the subcommand, and what stderr must contain.
pub(crate) struct BadInput {
    pub(crate) name: &'static str,
    pub(crate) scenario: Option<&'static str>,
    pub(crate) args: &'static [&'static str],
    pub(crate) expect: &'static [&'static str],
}

pub(crate) const fn bad_scenario(
    name: &'static str,
    scenario: &'static str,
    expect: &'static [&'static str],
) -> BadInput {
    BadInput {
        name,
        scenario: Some(scenario),
        args: &[],
        expect,
    }
}

pub(crate) const fn bad_args(
    name: &'static str,
    args: &'static [&'static str],
    expect: &'static [&'static str],
) -> BadInput {
    BadInput {
        name,
        scenario: None,
        args,
        expect,
    }
}

/// What is wrong with the run of `touchdown COMMAND` on one bad input (empty when it was
/// refused properly: exit code 2, an error naming what `case` expects, no panic, nothing on
/// stdout, no file made). `never` lists further text stderr must not have (such as the
/// banner a command prints when it starts its work).
pub(crate) fn check_bad_input(command: &str, case: &BadInput, never: &[&str]) -> Vec<String> {
    let dir = TempDir::new("bad-input");
    let mut args = vec![command];
    if let Some(text) = case.scenario {
        dir.write("scenario.toml", text);
        args.extend(["--scenario", "scenario.toml"]);
    }
    args.extend(case.args);
    let before = dir.entries();
    let run = touchdown(dir.path(), &args);

    let mut problems = Vec::new();
    if run.code != Some(2) {
        problems.push(format!("exit code {:?}, expected 2", run.code));
    }
    if !run.stderr.contains("error:") {
        problems.push("stderr does not say `error:`".to_string());
    }
    for s in case.expect {
        if !run.stderr.contains(s) {
            problems.push(format!("stderr lacks {s:?}"));
        }
    }
    for s in ["panicked", "RUST_BACKTRACE", "stack backtrace"] {
        if run.stderr.contains(s) {
            problems.push(format!("stderr has panic text {s:?}"));
        }
    }
    for s in never {
        if run.stderr.contains(s) {
            problems.push(format!("stderr has {s:?}"));
        }
    }
    if !run.stdout.is_empty() {
        problems.push("something was printed on stdout".to_string());
    }
    let after = dir.entries();
    if after != before {
        problems.push(format!("files before: {before:?}, after: {after:?}"));
    }
    if problems.is_empty() {
        Vec::new()
    } else {
        vec![format!(
            "{}:\n    {}\n{run}",
            case.name,
            problems.join("\n    ")
        )]
    }
}

// ---------------------------------------------------------------------------------------
// Python readers.

/// What the Python tests import: the readers, matplotlib for examples/python, and what the
/// Python package is built and tested with (tests/python_package.rs).
const PYTHON_MODULES: &str = "pandas, polars, pyarrow, matplotlib, numpy, maturin, pytest, nbclient, nbformat, ipykernel, tqdm";

/// The interpreter the Python tests run: `TOUCHDOWN_PYTHON` if set (it must have the
/// packages), else the one of a virtual environment under `target/` that the tests make on
/// first use from `tests/python/requirements.txt` (`python3 -m venv`, then pip) and reuse
/// after. Nothing is installed into the system's Python.
pub(crate) fn python() -> String {
    match python_environment() {
        Ok(p) => p.clone(),
        Err(_) => "python3".to_string(),
    }
}

/// The interpreter with the packages, or why there is none (once per test run).
fn python_environment() -> &'static Result<String, String> {
    static PYTHON: std::sync::OnceLock<Result<String, String>> = std::sync::OnceLock::new();
    PYTHON.get_or_init(|| {
        if let Ok(p) = std::env::var("TOUCHDOWN_PYTHON") {
            return check_imports(&p).map(|()| p);
        }
        provision_venv()
    })
}

/// Whether `python` imports the packages.
fn check_imports(python: &str) -> Result<(), String> {
    match Command::new(python)
        .args(["-c", &format!("import {PYTHON_MODULES}")])
        .output()
    {
        Err(e) => Err(format!("cannot run {python}: {e}")),
        Ok(o) if !o.status.success() => Err(format!(
            "{python} cannot import {PYTHON_MODULES}: {}",
            String::from_utf8_lossy(&o.stderr).trim()
        )),
        Ok(_) => Ok(()),
    }
}

/// Makes (or reuses) `target/tmp/python-venv` with the packages of
/// `tests/python/requirements.txt`; returns its interpreter.
fn provision_venv() -> Result<String, String> {
    let requirements = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/python/requirements.txt");
    let wanted = std::fs::read_to_string(&requirements)
        .map_err(|e| format!("cannot read {}: {e}", requirements.display()))?;
    let venv = Path::new(env!("CARGO_TARGET_TMPDIR")).join("python-venv");
    let python = venv.join("bin/python");
    let stamp = venv.join("requirements.installed");
    if std::fs::read_to_string(&stamp).ok().as_deref() == Some(wanted.as_str())
        && check_imports(&python.to_string_lossy()).is_ok()
    {
        return Ok(python.to_string_lossy().into_owned());
    }
    let run = |program: &Path, args: &[&std::ffi::OsStr], what: &str| -> Result<(), String> {
        let o = Command::new(program)
            .args(args)
            .output()
            .map_err(|e| format!("{what}: cannot run {}: {e}", program.display()))?;
        if o.status.success() {
            return Ok(());
        }
        let tail: Vec<&str> = std::str::from_utf8(&o.stderr)
            .unwrap_or("")
            .lines()
            .rev()
            .take(6)
            .collect();
        Err(format!(
            "{what} failed ({:?}):\n{}",
            o.status.code(),
            tail.into_iter().rev().collect::<Vec<_>>().join("\n")
        ))
    };
    let _ = writeln!(
        std::io::stderr(),
        "\nmaking the Python environment of the tests in {} ({PYTHON_MODULES}; once, reused after)",
        venv.display()
    );
    if !python.exists() {
        run(
            Path::new("python3"),
            &["-m".as_ref(), "venv".as_ref(), venv.as_os_str()],
            "python3 -m venv (Debian and Ubuntu: apt-get install python3-venv)",
        )?;
    }
    run(
        &python,
        &[
            "-m".as_ref(),
            "pip".as_ref(),
            "install".as_ref(),
            "--quiet".as_ref(),
            "--disable-pip-version-check".as_ref(),
            "-r".as_ref(),
            requirements.as_os_str(),
        ],
        &format!(
            "pip install -r {} into {} (it needs the package index, https://pypi.org, or a \
             mirror set in PIP_INDEX_URL)",
            requirements.display(),
            venv.display()
        ),
    )?;
    check_imports(&python.to_string_lossy())?;
    std::fs::write(&stamp, &wanted)
        .map_err(|e| format!("cannot write {}: {e}", stamp.display()))?;
    Ok(python.to_string_lossy().into_owned())
}

/// Whether the Python readers can run for `test`. Skipped (`false`, with a note on the
/// terminal) under `TOUCHDOWN_SKIP_PYTHON=1`. When the environment cannot be made, the
/// first test to ask fails with the reason, and the others skip pointing at it.
pub(crate) fn python_readers_available(test: &str) -> bool {
    if std::env::var("TOUCHDOWN_SKIP_PYTHON").as_deref() == Ok("1") {
        // Straight to the terminal: the test harness hides what `eprintln!` prints in a
        // test that passes.
        let _ = writeln!(
            std::io::stderr(),
            "\nSKIPPED {test} (TOUCHDOWN_SKIP_PYTHON=1)"
        );
        return false;
    }
    let Err(why) = python_environment() else {
        return true;
    };
    static REPORTED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
    if REPORTED.swap(true, Ordering::Relaxed) {
        let _ = writeln!(
            std::io::stderr(),
            "\nSKIPPED {test}: no Python environment (the failing Python test says why)"
        );
        return false;
    }
    panic!(
        "the Python tests need {PYTHON_MODULES}, and their environment could not be made:\n{why}\n\n\
         Set TOUCHDOWN_PYTHON to an interpreter that has them, or TOUCHDOWN_SKIP_PYTHON=1 to \
         skip the Python tests."
    );
}

/// Runs `tests/python/SCRIPT ARGS`; panics with its output unless it exits 0. `what` says
/// for the message which file it checked.
pub(crate) fn run_python_check(script: &str, args: &[&std::ffi::OsStr], what: &str) {
    let script = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/python")
        .join(script);
    let o = Command::new(python())
        .arg(&script)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {}: {e}", script.display()));
    assert!(
        o.status.success(),
        "{} found problems in {what} ({:?}):\n{}{}",
        script.display(),
        o.status.code(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// The measured-against-expected rows of one test, printed together at the end; the test
/// fails on `finish` if any row failed.
pub(crate) struct Table {
    name: &'static str,
    text: String,
    failures: Vec<String>,
}

impl Table {
    pub(crate) fn new(name: &'static str) -> Table {
        let mut text = String::new();
        writeln!(
            text,
            "\n== {name}\n{:<64} {:<34} {:>14} {:>14} {:>11} {:>11}  ok",
            "case", "quantity", "measured", "expected", "error", "tolerance"
        )
        .unwrap();
        Table {
            name,
            text,
            failures: Vec::new(),
        }
    }

    pub(crate) fn row(&mut self, case: &str, quantity: &str, values: [String; 4], ok: bool) {
        let [m, e, err, tol] = values;
        let mark = if ok { "ok" } else { "FAIL" };
        writeln!(
            self.text,
            "{case:<64} {quantity:<34} {m:>14} {e:>14} {err:>11} {tol:>11}  {mark}"
        )
        .unwrap();
        if !ok {
            let tolerance = if tol.is_empty() {
                String::new()
            } else {
                format!(" (tolerance {tol})")
            };
            self.failures
                .push(format!("{case}: {quantity} = {m}, expected {e}{tolerance}"));
        }
    }

    /// `|measured - expected| <= tolerance`.
    pub(crate) fn close(
        &mut self,
        case: &str,
        quantity: &str,
        measured: f64,
        expected: f64,
        tolerance: f64,
    ) {
        let error = (measured - expected).abs();
        self.row(
            case,
            quantity,
            [g(measured), g(expected), g(error), g(tolerance)],
            error <= tolerance,
        );
    }

    /// `|measured / expected - 1| <= tolerance`.
    pub(crate) fn relative(
        &mut self,
        case: &str,
        quantity: &str,
        measured: f64,
        expected: f64,
        tolerance: f64,
    ) {
        let error = (measured / expected - 1.0).abs();
        self.row(
            case,
            quantity,
            [g(measured), g(expected), pct(error), pct(tolerance)],
            error <= tolerance,
        );
    }

    /// `measured <= limit` (an error that should vanish).
    pub(crate) fn at_most(&mut self, case: &str, quantity: &str, measured: f64, limit: f64) {
        self.row(
            case,
            quantity,
            [
                g(measured),
                format!("<= {}", g(limit)),
                String::new(),
                String::new(),
            ],
            measured <= limit,
        );
    }

    /// `measured >= limit`.
    pub(crate) fn at_least(&mut self, case: &str, quantity: &str, measured: f64, limit: f64) {
        self.row(
            case,
            quantity,
            [
                g(measured),
                format!(">= {}", g(limit)),
                String::new(),
                String::new(),
            ],
            measured >= limit,
        );
    }

    /// A discrete result, e.g. an outcome.
    pub(crate) fn equal<T: std::fmt::Debug + PartialEq>(
        &mut self,
        case: &str,
        quantity: &str,
        measured: T,
        expected: T,
    ) {
        let ok = measured == expected;
        self.row(
            case,
            quantity,
            [
                format!("{measured:?}"),
                format!("{expected:?}"),
                String::new(),
                String::new(),
            ],
            ok,
        );
    }

    pub(crate) fn finish(self) {
        println!("{}", self.text);
        assert!(
            self.failures.is_empty(),
            "{}: {} check(s) failed:\n  {}",
            self.name,
            self.failures.len(),
            self.failures.join("\n  ")
        );
    }
}

/// A number in a short, readable form.
pub(crate) fn g(x: f64) -> String {
    if x == 0.0 || (1e-3..1e5).contains(&x.abs()) {
        format!("{x:.6}")
    } else {
        format!("{x:.4e}")
    }
}

/// A fraction as a percentage.
pub(crate) fn pct(x: f64) -> String {
    if x == 0.0 || 100.0 * x >= 0.01 {
        format!("{:.3} %", 100.0 * x)
    } else {
        format!("{:.1e} %", 100.0 * x)
    }
}

/// The JSON a page of `touchdown view` or `site` holds in its `<script id="ID">` (the data
/// as the page reads it).
pub(crate) fn page_json(page: &str, id: &str) -> serde_json::Value {
    let start = page
        .find(&format!("<script id=\"{id}\" type=\"application/json\">"))
        .expect("the page's data");
    let json = &page[start..];
    let json = &json[json.find('>').unwrap() + 1..json.find("</script>").unwrap()];
    serde_json::from_str(&json.replace("<\\/", "</")).expect("the page's JSON")
}
