//! No panic on any file (issue 33, point 8): every file touchdown reads, damaged anywhere
//! in its metadata, offsets or sizes, or cut off, is refused with an error naming it (exit
//! 2 from the program), never a panic (exit 101) or an abort (134, a huge allocation).
//!
//! In-process, exhaustively: every byte of the metadata of an Arrow IPC file (its schema
//! message, each batch's message header, the footer), of an IPC stream, and of a Parquet
//! file (its footer and page indexes, and the page headers at the start of each column
//! chunk) flipped with two masks, a sample of the data bytes, and truncations at many
//! lengths, through each library reader (under `catch_unwind`). Through the program: a
//! sample of the same damage for every command that reads a file, checking exit codes.

use crate::common::{SHORT, TempDir, read_bytes, touchdown};
use arrow_array::{Float64Array, RecordBatch};
use arrow_schema::{DataType, Field, Schema};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use touchdown::output::columns::Table;
use touchdown::output::resume::Interrupted;
use touchdown::scenario::Scenario;

/// The masks each chosen byte is flipped with: all bits (a small length turns negative or
/// huge) and, outside runs of text (the scenario, units, descriptions, where any change
/// is just other text), bit 6 alone (a length or offset grows and stays positive).
const MASKS: [u8; 2] = [0xff, 0x40];

/// Printable bytes in a row from which they count as text.
const TEXT_RUN: usize = 16;

/// A library reader of a file: its name, every how many damaged copies it reads, and the
/// call that reads the damaged copy at the path given.
type Reader = (
    &'static str,
    usize,
    Box<dyn Fn(&Path) -> anyhow::Result<()> + Sync>,
);

/// One data byte in this many is flipped (the data are numbers: any bits are valid values,
/// and the exhaustive sweep is over the metadata, where the offsets and sizes are).
const BODY_STRIDE: usize = 53;

/// How a file is laid out, to find its metadata.
#[derive(Clone, Copy, PartialEq)]
enum Layout {
    ArrowFile,
    ArrowStream,
    Parquet,
}

/// A file to damage, and the readers of it.
struct Target {
    /// The intact file.
    source: PathBuf,
    layout: Layout,
    /// The name the damaged copy is written under.
    name: &'static str,
    /// Library readers: a name, every how many damaged copies it reads, and the call that
    /// reads the damaged copy at the path given.
    readers: Vec<Reader>,
    /// Commands of the program that read the damaged copy (`{}` stands for its name).
    commands: Vec<Vec<&'static str>>,
}

/// The byte positions to flip: every byte of the metadata, one data byte in `BODY_STRIDE`.
fn positions(bytes: &[u8], layout: Layout) -> Vec<usize> {
    let mut out = Vec::new();
    let metadata = |range: std::ops::Range<usize>, out: &mut Vec<usize>| {
        out.extend(range.start.min(bytes.len())..range.end.min(bytes.len()));
    };
    let body = |range: std::ops::Range<usize>, out: &mut Vec<usize>| {
        out.extend((range.start..range.end.min(bytes.len())).step_by(BODY_STRIDE));
    };
    match layout {
        Layout::ArrowFile | Layout::ArrowStream => {
            let mut at = if layout == Layout::ArrowFile { 8 } else { 0 };
            metadata(0..at, &mut out);
            // Messages: continuation marker, metadata length, flatbuffer, body.
            while at + 8 <= bytes.len() && bytes[at..at + 4] == [0xff; 4] {
                let len = i32::from_le_bytes(bytes[at + 4..at + 8].try_into().unwrap()) as usize;
                if len == 0 {
                    break;
                }
                let message = arrow_ipc::root_as_message(&bytes[at + 8..at + 8 + len])
                    .expect("an intact message");
                let body_len = message.bodyLength() as usize;
                metadata(at..at + 8 + len, &mut out);
                body(at + 8 + len..at + 8 + len + body_len, &mut out);
                at += 8 + len + body_len;
            }
            // The end-of-stream marker, and in a file the footer, its length and magic.
            metadata(at..bytes.len(), &mut out);
        }
        Layout::Parquet => {
            let meta = parquet::file::metadata::ParquetMetaDataReader::new()
                .parse_and_finish(&bytes::Bytes::copy_from_slice(bytes))
                .expect("intact Parquet");
            metadata(0..4, &mut out);
            let mut end = 4;
            for rg in meta.row_groups() {
                for c in rg.columns() {
                    let (start, len) = c.byte_range();
                    let (start, len) = (start as usize, len as usize);
                    body(start..start + len, &mut out);
                    // The page headers: the first one, and the data page's after a dictionary.
                    metadata(start..start + 48, &mut out);
                    let data = c.data_page_offset() as usize;
                    metadata(data..data + 48, &mut out);
                    end = end.max(start + len);
                }
            }
            // Page indexes, footer, its length and magic.
            metadata(end..bytes.len(), &mut out);
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// The lengths a file is cut to: the first and last 64, and 100 between.
fn truncations(len: usize) -> Vec<usize> {
    let mut out: Vec<usize> = (0..64.min(len)).collect();
    out.extend(len.saturating_sub(64)..len);
    out.extend((1..100).map(|k| len * k / 100));
    out.sort_unstable();
    out.dedup();
    out
}

/// Damage done to a file.
#[derive(Clone, Copy)]
enum Damage {
    /// The byte at a position flipped with a mask.
    Flip(usize, u8),
    /// The file cut to a length.
    Cut(usize),
}

impl Damage {
    /// Every damage done to a file of `bytes`.
    fn all(bytes: &[u8], layout: Layout) -> Vec<Damage> {
        let text = text_bytes(bytes);
        let flips = positions(bytes, layout).into_iter().flat_map(|p| {
            let masks = if text[p] { &MASKS[..1] } else { &MASKS[..] };
            masks.iter().map(move |&m| Damage::Flip(p, m))
        });
        let cuts = truncations(bytes.len()).into_iter().map(Damage::Cut);
        flips.chain(cuts).collect()
    }

    /// The damaged copy of `bytes`.
    fn apply(self, bytes: &[u8]) -> Vec<u8> {
        match self {
            Damage::Flip(p, mask) => {
                let mut b = bytes.to_vec();
                b[p] ^= mask;
                b
            }
            Damage::Cut(len) => bytes[..len].to_vec(),
        }
    }

    /// Does it to `file`, a copy of `intact` (in place: rewriting a file whole costs
    /// milliseconds where the readers take a fraction of one).
    fn apply_in_place(self, file: &mut std::fs::File, intact: &[u8]) {
        match self {
            Damage::Flip(p, mask) => write_at(file, p, &[intact[p] ^ mask]),
            Damage::Cut(len) => file.set_len(len as u64).unwrap(),
        }
    }

    /// Makes `file` a copy of `intact` again.
    fn undo(self, file: &mut std::fs::File, intact: &[u8]) {
        match self {
            Damage::Flip(p, _) => write_at(file, p, &intact[p..=p]),
            Damage::Cut(len) => write_at(file, len, &intact[len..]),
        }
    }
}

impl std::fmt::Display for Damage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Damage::Flip(p, mask) => write!(f, "byte {p} ^ {mask:#04x}"),
            Damage::Cut(len) => write!(f, "cut to {len} bytes"),
        }
    }
}

/// Which bytes lie in runs of `TEXT_RUN` or more printable ones.
fn text_bytes(bytes: &[u8]) -> Vec<bool> {
    let mut text = vec![false; bytes.len()];
    let mut start = 0;
    for i in 0..=bytes.len() {
        let printable = i < bytes.len() && (bytes[i] == b'\n' || (0x20..0x7f).contains(&bytes[i]));
        if !printable {
            if i - start >= TEXT_RUN {
                text[start..i].fill(true);
            }
            start = i + 1;
        }
    }
    text
}

fn write_at(file: &mut std::fs::File, at: usize, bytes: &[u8]) {
    use std::io::{Seek, SeekFrom, Write};
    file.seek(SeekFrom::Start(at as u64)).unwrap();
    file.write_all(bytes).unwrap();
}

/// The panic message of a payload.
fn message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(ToString::to_string)
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_default()
}

/// The fixture files, made by the program, and the tables of inputs, written here.
fn fixtures(dir: &TempDir) {
    dir.write("short.toml", SHORT);
    let run = |args: &str| {
        let r = touchdown(dir.path(), &args.split(' ').collect::<Vec<_>>());
        assert_eq!(r.code, Some(0), "{r}");
    };
    let sweep = "sweep --quiet --scenario short.toml";
    for out in ["s.arrow", "s.parquet"] {
        run(&format!("{sweep} --samples 20 --out {out}"));
    }
    for (k, out) in ["0/2", "1/2"].iter().zip(["sh0.arrow", "sh1.arrow"]) {
        run(&format!("{sweep} --samples 20 --shard {k} --out {out}"));
    }
    run(&format!(
        "{sweep} --design sobol-indices --samples 26 --out so.arrow"
    ));
    run("trace --scenario short.toml --every 100 --out t.arrow");
    let batch = RecordBatch::try_new(
        Arc::new(Schema::new(vec![
            Field::new("slope_deg", DataType::Float64, false),
            Field::new("yaw_deg", DataType::Float64, false),
        ])),
        vec![
            Arc::new(Float64Array::from_iter_values(
                (0..8).map(|i| 2.0 * f64::from(i)),
            )),
            Arc::new(Float64Array::from_iter_values(
                (0..8).map(|i| 40.0 * f64::from(i)),
            )),
        ],
    )
    .unwrap();
    let create = |name: &str| std::fs::File::create(dir.join(name)).unwrap();
    let mut w =
        arrow_ipc::writer::FileWriter::try_new(create("in.arrow"), &batch.schema()).unwrap();
    w.write(&batch).unwrap();
    w.finish().unwrap();
    let mut w =
        arrow_ipc::writer::StreamWriter::try_new(create("in.stream"), &batch.schema()).unwrap();
    w.write(&batch).unwrap();
    w.finish().unwrap();
    let mut w =
        parquet::arrow::ArrowWriter::try_new(create("in.parquet"), batch.schema(), None).unwrap();
    w.write(&batch).unwrap();
    w.close().unwrap();
}

/// The readers of a sweep file: report's (`SweepFile`, which compare, sensitivity, study
/// and `trace --sweep` read it with), on every damaged copy; `--resume`'s (the copy is named
/// as the `.interrupted` file of a sweep) and plot's (`Table`), on a share of them (they
/// decode it as report does, and read its metadata each their own way).
fn sweep_readers() -> Vec<Reader> {
    vec![
        (
            "report",
            1,
            Box::new(|p| {
                let source = touchdown::output::sweep::SweepSource::Path(p.to_path_buf());
                touchdown::report::report(&source, None).map(drop)
            }),
        ),
        (
            "--resume",
            3,
            Box::new(|p| Interrupted::read(&p.with_extension("")).map(drop)),
        ),
        (
            "columns (plot)",
            5,
            Box::new(|p| Table::read(p, |_| true).map(drop)),
        ),
    ]
}

/// The commands that read a sweep file, `{}` its damaged copy, `intact` the file intact.
fn sweep_commands(intact: &'static str, resume: &'static str) -> Vec<Vec<&'static str>> {
    vec![
        vec!["report", "{}"],
        vec!["compare", intact, "{}"],
        vec![
            "trace", "--sweep", "{}", "--sample", "3", "--out", "tr.arrow",
        ],
        vec!["plot", "{}", "--out-dir", "plots"],
        vec!["sweep", "--quiet", "--resume", resume],
    ]
}

fn targets(dir: &TempDir) -> Vec<Target> {
    let scenario = Arc::new(Scenario::from_toml(SHORT).unwrap());
    let table = |scenario: &Arc<Scenario>| -> Vec<Reader> {
        let scenario = scenario.clone();
        vec![(
            "--inputs",
            1,
            Box::new(move |p| touchdown::table::attach(&mut (*scenario).clone(), p, false)),
        )]
    };
    let inputs = || {
        vec![vec![
            "sweep",
            "--quiet",
            "--scenario",
            "short.toml",
            "--inputs",
            "{}",
            "--out",
            "o.arrow",
        ]]
    };
    let target = |source: &str, layout, name, readers, commands| Target {
        source: dir.join(source),
        layout,
        name,
        readers,
        commands,
    };
    vec![
        target(
            "s.arrow",
            Layout::ArrowFile,
            "r.arrow.interrupted",
            sweep_readers(),
            sweep_commands("s.arrow", "r.arrow"),
        ),
        target(
            "s.parquet",
            Layout::Parquet,
            "r.parquet.interrupted",
            sweep_readers(),
            sweep_commands("s.parquet", "r.parquet"),
        ),
        // Read as a sweep file is (`open`): only through the program.
        target(
            "sh1.arrow",
            Layout::ArrowFile,
            "dsh1.arrow",
            Vec::new(),
            vec![vec!["merge", "sh0.arrow", "{}", "--out", "m.arrow"]],
        ),
        target(
            "so.arrow",
            Layout::ArrowFile,
            "dso.arrow",
            Vec::new(),
            vec![vec!["sensitivity", "{}", "--bootstrap", "10"]],
        ),
        target(
            "t.arrow",
            Layout::ArrowFile,
            "dt.arrow",
            vec![(
                "trace (plot, animate, view)",
                1,
                Box::new(|p| touchdown::scene::Scene::read(p).map(drop)),
            )],
            vec![
                vec!["plot", "{}", "--out-dir", "plots"],
                vec![
                    "animate", "{}", "--out", "a.gif", "--fps", "1", "--size", "160x120",
                ],
                vec!["view", "{}", "--out", "v.html"],
            ],
        ),
        target(
            "in.arrow",
            Layout::ArrowFile,
            "din.arrow",
            table(&scenario),
            inputs(),
        ),
        target(
            "in.stream",
            Layout::ArrowStream,
            "din.stream",
            table(&scenario),
            inputs(),
        ),
        target(
            "in.parquet",
            Layout::Parquet,
            "din.parquet",
            table(&scenario),
            inputs(),
        ),
    ]
}

/// What the damage to one target gave: panics of the library's readers, and runs of the
/// program that neither succeeded nor refused the file naming it with exit 2.
#[derive(Default)]
struct Findings {
    panics: Vec<String>,
    runs: Vec<String>,
    /// Runs of the program made.
    runs_made: usize,
}

/// Every damage done to `target`'s file, through its library readers; a sample through the
/// program, run in `work` (a folder of its own, with copies of the fixtures in `dir`).
fn damage(dir: &Path, work: &Path, target: &Target) -> Findings {
    std::fs::create_dir(work).unwrap();
    for entry in std::fs::read_dir(dir).unwrap() {
        let p = entry.unwrap().path();
        if p.is_file() {
            std::fs::copy(&p, work.join(p.file_name().unwrap())).unwrap();
        }
    }
    let mut found = Findings::default();
    let intact = read_bytes(&target.source);
    let path = work.join(target.name);
    std::fs::write(&path, &intact).unwrap();
    let mut file = std::fs::OpenOptions::new().write(true).open(&path).unwrap();
    // The damage that made a reader panic, or refuse the file as damaged (the guard caught
    // a panic): the hardest cases, to run through the program too.
    let mut hard = Vec::new();
    let all = Damage::all(&intact, target.layout);
    for (k, &damage) in all.iter().enumerate() {
        damage.apply_in_place(&mut file, &intact);
        let mut is_hard = false;
        for (reader, every, read) in &target.readers {
            if k % every != 0 {
                continue;
            }
            match catch_unwind(AssertUnwindSafe(|| read(&path))) {
                Err(payload) => {
                    is_hard = true;
                    found.panics.push(format!(
                        "{reader} of {} ({damage}): panic {:?}",
                        target.name,
                        message(&*payload)
                    ));
                }
                Ok(Err(e)) => is_hard |= format!("{e:#}").contains("damaged"),
                Ok(Ok(())) => {}
            }
        }
        if is_hard {
            hard.push(damage);
        }
        damage.undo(&mut file, &intact);
    }
    // Through the program: 4 of the hardest cases, 5 flips spread over the file and 3
    // truncations, for each command.
    let flips: Vec<Damage> = all
        .iter()
        .copied()
        .filter(|d| matches!(d, Damage::Flip(..)))
        .collect();
    let cuts: Vec<Damage> = all
        .iter()
        .copied()
        .filter(|d| matches!(d, Damage::Cut(_)))
        .collect();
    let mut sample: Vec<Damage> = hard.iter().copied().step_by(hard.len() / 4 + 1).collect();
    sample.extend((0..5).map(|k| flips[k * flips.len() / 5]));
    sample.extend((0..3).map(|k| cuts[(2 * k + 1) * cuts.len() / 6]));
    for damage in sample {
        for command in &target.commands {
            // Afresh for each run: `--resume` takes the file away.
            std::fs::write(&path, damage.apply(&intact)).unwrap();
            for out in ["r.arrow", "r.parquet", "o.arrow", "m.arrow", "tr.arrow"] {
                let _ = std::fs::remove_file(work.join(out));
            }
            let args: Vec<&str> = command
                .iter()
                .map(|a| if *a == "{}" { target.name } else { a })
                .collect();
            let run = touchdown(work, &args);
            found.runs_made += 1;
            let named = run
                .stderr
                .contains(target.name.trim_end_matches(".interrupted"));
            let refused = run.code == Some(2) && named && !run.stderr.contains("panicked");
            if !(run.code == Some(0) || refused) {
                found
                    .runs
                    .push(format!("{} ({damage}): {run}", target.name));
            }
        }
    }
    found
}

#[test]
fn damaged_files_are_refused_never_panic_or_abort() {
    let dir = TempDir::new("hostile");
    fixtures(&dir);
    let targets = targets(&dir);
    // Two threads, the targets shared out between them.
    let found: Vec<Findings> = std::thread::scope(|s| {
        let (dir, targets) = (dir.path(), &targets);
        let threads: Vec<_> = (0..2)
            .map(|t| {
                s.spawn(move || {
                    let mine = targets.iter().enumerate().skip(t).step_by(2);
                    mine.map(|(k, target)| damage(dir, &dir.join(format!("{k}")), target))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        threads
            .into_iter()
            .flat_map(|t| t.join().unwrap())
            .collect()
    });
    let panics: Vec<&String> = found.iter().flat_map(|f| &f.panics).collect();
    let runs: Vec<&String> = found.iter().flat_map(|f| &f.runs).collect();
    let runs_made: usize = found.iter().map(|f| f.runs_made).sum();
    assert!(
        panics.is_empty() && runs.is_empty(),
        "{} panics in-process, first: {:#?}\n{} of {runs_made} runs of the program neither \
         succeeded nor refused naming the file with exit 2, first: {:#?}",
        panics.len(),
        &panics[..panics.len().min(12)],
        runs.len(),
        &runs[..runs.len().min(6)]
    );
}

/// A compressed buffer of a table of inputs that says it holds 16 TiB: refused before the
/// decoder asks for them (an abort on main: "memory allocation of 17592186044416 bytes
/// failed", exit 134).
#[test]
fn a_compressed_table_claiming_terabytes_is_refused() {
    let dir = TempDir::new("hostile-lz4");
    dir.write("short.toml", SHORT);
    let rows = 1000;
    let batch = RecordBatch::try_new(
        Arc::new(Schema::new(vec![Field::new(
            "slope_deg",
            DataType::Float64,
            false,
        )])),
        vec![Arc::new(Float64Array::from_iter_values(
            (0..rows).map(|i| f64::from(i % 30)),
        ))],
    )
    .unwrap();
    let mut bytes = lz4_file(&batch);
    // The values' buffer: its first 8 bytes are its size decompressed, 8 bytes a row.
    let size = (8 * rows as i64).to_le_bytes();
    let at = bytes
        .windows(8)
        .position(|w| w == size)
        .expect("the size prefix");
    bytes[at..at + 8].copy_from_slice(&(1i64 << 44).to_le_bytes());
    refused_as_damaged(&dir, &bytes, &[]);
}

/// `batch` as an Arrow IPC file compressed with LZ4.
fn lz4_file(batch: &RecordBatch) -> Vec<u8> {
    let options = arrow_ipc::writer::IpcWriteOptions::default()
        .try_with_compression(Some(arrow_ipc::CompressionType::LZ4_FRAME))
        .unwrap();
    let mut bytes = Vec::new();
    let mut w =
        arrow_ipc::writer::FileWriter::try_new_with_options(&mut bytes, &batch.schema(), options)
            .unwrap();
    w.write(batch).unwrap();
    w.finish().unwrap();
    drop(w);
    bytes
}

/// Checks that a sweep of the table `bytes` (`lz.arrow`, with the flags `more`) is refused
/// as a damaged file (exit 2, naming it).
fn refused_as_damaged(dir: &TempDir, bytes: &[u8], more: &[&str]) {
    std::fs::write(dir.join("lz.arrow"), bytes).unwrap();
    let args = [
        "sweep",
        "--quiet",
        "--scenario",
        "short.toml",
        "--inputs",
        "lz.arrow",
    ];
    let run = touchdown(
        dir.path(),
        &[&args[..], more, &["--out", "o.arrow"]].concat(),
    );
    assert!(
        run.code == Some(2) && run.stderr.contains("lz.arrow") && run.stderr.contains("damaged"),
        "{run}"
    );
}

/// The same for a coded (dictionary) column's texts: their buffer, in a dictionary message
/// ahead of the record batches, says it holds 16 TiB.
#[test]
fn a_compressed_dictionary_claiming_terabytes_is_refused() {
    let dir = TempDir::new("hostile-lz4-dictionary");
    dir.write("short.toml", SHORT);
    let rows = 1000;
    let coded = DataType::Dictionary(Box::new(DataType::Int8), Box::new(DataType::Utf8));
    // Three texts of 1,000 bytes: a size (3,000) no other buffer has.
    let texts = ["a", "b", "c"].map(|t| t.repeat(1000));
    let case = arrow_array::DictionaryArray::<arrow_array::types::Int8Type>::try_new(
        arrow_array::Int8Array::from_iter_values((0..rows).map(|i| (i % 3) as i8)),
        Arc::new(arrow_array::StringArray::from_iter_values(&texts)),
    )
    .unwrap();
    let batch = RecordBatch::try_new(
        Arc::new(Schema::new(vec![
            Field::new("slope_deg", DataType::Float64, false),
            Field::new("case", coded, false),
        ])),
        vec![
            Arc::new(Float64Array::from_iter_values(
                (0..rows).map(|i| f64::from(i % 30)),
            )),
            Arc::new(case),
        ],
    )
    .unwrap();
    let mut bytes = lz4_file(&batch);
    // The texts' offsets (0, 1000, 2000, 3000, stored as they are) come before them: the
    // last 3,000 is the texts' size prefix.
    let size = 3000i64.to_le_bytes();
    let at = bytes
        .windows(8)
        .rposition(|w| w == size)
        .expect("the size prefix of the texts");
    bytes[at..at + 8].copy_from_slice(&(1i64 << 44).to_le_bytes());
    refused_as_damaged(&dir, &bytes, &["--keep-columns"]);
}
