//! Every command block of README.md and scenarios/README.md runs as printed and gives the
//! figures the text prints after it.
//!
//! Each block (`sh`, `bash`, `console`, `python`) has a plan in `plans.rs`: run here, run by
//! another test (named), or not run, with the reason (a Slurm cluster, a package install, a
//! map of twenty minutes). A block without a plan fails the test, so a new block is run or
//! said not to be. The blocks of a file run in order in one folder (a block reads the files
//! an earlier one wrote), `touchdown` being this build and `python3` the tests' Python
//! environment, with `scenarios/`, `bodies/` and `examples/` beside them as in a clone.
//!
//! A block runs at the size it prints, or at the smaller size its text states ("CI runs
//! this at `--samples 2e4`"). Then it must give the figures printed after it:
//! - at the size printed (same seed, same samples), every line of the printed output
//!   (`text` blocks; `...` skips, times are the machine's) and every figure of the plan to
//!   the printed digits;
//! - at a smaller size, the plan's figures within their statistical error: a share within
//!   four binomial standard errors of the smaller run (a deterministic run of a fixed seed;
//!   four standard errors is a false alarm once in 16,000 figures), a value the printed
//!   interval of the smaller run covers.
//!
//! The README's blocks take about 250 s together on a 2-core AVX2 machine loaded by other
//! builds (the longest: `flat.toml`'s 20,000 samples at the printed size, 60 s there); a
//! block's time is in the list the test prints.

mod parse;
mod pattern;
mod plans;

use crate::common::{TempDir, readme_path};
use parse::Block;
use pattern::{Pattern, Printed};
use plans::{Agree, Figure, How, PLANS, Plan, Run};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

/// Set to a part of a block's place (`README.md:612`, a heading), it runs only the blocks
/// whose place contains it: to see one block's figures again (a block that reads an
/// earlier block's files needs that block too).
const ONLY: &str = "TOUCHDOWN_README_BLOCKS";

/// How many standard errors a share of a smaller run may lie from the printed one.
const STANDARD_ERRORS: f64 = 4.0;

#[test]
fn readme_blocks_run_as_printed() {
    check_file("README.md");
}

#[test]
fn scenarios_readme_blocks_run_as_printed() {
    check_file("scenarios/README.md");
}

/// Runs the command blocks of `file` by their plans; panics listing every block without a
/// plan, every plan without a block, and every figure that differs.
fn check_file(file: &'static str) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let markdown = std::fs::read_to_string(root.join(file)).expect("read the README");
    let blocks = parse::blocks(file, &markdown);
    let plans: Vec<&Plan> = PLANS.iter().filter(|p| p.file == file).collect();
    let mut problems = Vec::new();
    for plan in &plans {
        let n = blocks
            .iter()
            .filter(|b| b.is_command() && b.text.contains(plan.key))
            .count();
        if n != 1 {
            problems.push(format!(
                "{file}: the plan of the block containing {:?} matches {n} command blocks, not one",
                plan.key
            ));
        }
    }
    let dir = TempDir::new("readme-blocks");
    for link in ["scenarios", "bodies", "examples"] {
        std::os::unix::fs::symlink(root.join(link), dir.join(link)).expect("link a folder");
    }
    let path = readme_path(&dir);
    // Asked only where a block runs Python: a file without such blocks runs without it.
    let python = std::cell::OnceCell::new();
    let python =
        || *python.get_or_init(|| crate::common::python_readers_available("readme_blocks"));
    let only = std::env::var(ONLY).ok();
    let mut report = String::new();
    for block in blocks.iter().filter(|b| b.is_command()) {
        let Some(plan) = plans.iter().find(|p| block.text.contains(p.key)) else {
            problems.push(format!(
                "{}: a command block that no plan in tests/readme_blocks/plans.rs names; \
                 give it one (run, run elsewhere, or not run and why):\n{}",
                block.place(),
                block.text
            ));
            continue;
        };
        match &plan.how {
            How::Elsewhere(why) => {
                let _ = writeln!(report, "{}: run by {why}", block.place());
            }
            How::NotRun(why) => {
                let _ = writeln!(report, "{}: not run: {why}", block.place());
            }
            How::Run { .. } if uses_python(block) && !python() => {
                let _ = writeln!(report, "{}: not run: no Python environment", block.place());
            }
            How::Run(_)
                if only
                    .as_ref()
                    .is_some_and(|o| !block.place().contains(o.as_str())) =>
            {
                let _ = writeln!(report, "{}: not run: not named by {ONLY}", block.place());
            }
            How::Run(run) => {
                let start = std::time::Instant::now();
                problems.extend(run_block(block, &dir, &path, run));
                let took = start.elapsed().as_secs_f64();
                let _ = writeln!(report, "{}: run, {took:.1} s", block.place());
            }
        }
    }
    // Straight to the terminal: the harness hides what a passing test prints.
    let _ = std::io::stderr().write_all(format!("\n{file}'s command blocks:\n{report}").as_bytes());
    assert!(
        problems.is_empty(),
        "{} of {file}'s command blocks do not reproduce as printed:\n\n{}\n\n(the files are \
         kept in {})",
        problems.len(),
        problems.join("\n\n"),
        dir.path().display()
    );
}

/// Whether the block runs Python.
fn uses_python(block: &Block) -> bool {
    block.language == "python" || block.text.contains("python3")
}

/// The size a block runs at: its text's "CI runs this at `--FLAG VALUE`", if it says so.
struct Size {
    flag: String,
    printed: f64,
    run: f64,
}

/// The smaller size the block's text states, and the block's lines with `then` after them,
/// the smaller size in place of the printed one.
fn smaller_size(block: &Block, then: &str) -> Result<(String, Option<Size>), String> {
    let lines = format!("{}{then}", block.text);
    const SAYS: &str = "CI runs this at ";
    let told = [&block.text, &block.after]
        .into_iter()
        .find_map(|t| t.split(SAYS).nth(1).map(|rest| rest.replace('`', "")));
    let Some(told) = told else {
        return Ok((lines, None));
    };
    let mut words = told.split_whitespace();
    let (Some(flag), Some(value)) = (words.next(), words.next()) else {
        return Err(format!(
            "{}: \"{SAYS}\" names no flag and value",
            block.place()
        ));
    };
    let value = value.trim_end_matches(['.', ',', ')', ';', ':']);
    let number = |v: &str| v.parse::<f64>().ok();
    let run = number(value).ok_or(format!(
        "{}: {SAYS}{flag} {value}: not a number",
        block.place()
    ))?;
    let mut printed = None;
    let text = lines
        .lines()
        .map(|line| {
            let mut words: Vec<String> = line.split(' ').map(str::to_string).collect();
            for k in 1..words.len() {
                if words[k - 1] == flag && !line.trim_start().starts_with('#') {
                    printed = printed.or(number(&words[k]));
                    words[k] = value.to_string();
                }
            }
            words.join(" ")
        })
        .collect::<Vec<_>>()
        .join("\n");
    let printed = printed.ok_or(format!(
        "{}: its text says {SAYS}{flag} {value}, but no command of it gives {flag}",
        block.place()
    ))?;
    Ok((
        text,
        Some(Size {
            flag: flag.to_string(),
            printed,
            run,
        }),
    ))
}

/// Runs one block in `dir` and compares what it printed with the text after it; returns
/// what differs.
fn run_block(block: &Block, dir: &TempDir, path: &str, run: &Run) -> Vec<String> {
    let (text, size) = match smaller_size(block, run.then) {
        Ok(t) => t,
        Err(e) => return vec![e],
    };
    let text: String = text
        .lines()
        .filter(|line| !run.drop.iter().any(|(d, _)| line.contains(d)))
        .map(|line| {
            line.replace("cargo run --release -- ", "touchdown ")
                .replace("target/release/touchdown", "touchdown")
        })
        .collect::<Vec<_>>()
        .join("\n");
    let script = if block.language == "python" {
        let file = format!("block-{}.py", block.line);
        std::fs::write(dir.join(&file), &text).expect("write the Python block");
        format!("{}\npython3 {file}\n", run.before)
    } else {
        format!("{}\n{text}\n", run.before)
    };
    let out = std::process::Command::new("bash")
        .args([
            "-e",
            "-o",
            "pipefail",
            "-c",
            &format!("exec 2>&1\n{script}"),
        ])
        .current_dir(dir.path())
        .env("PATH", path)
        .env_remove("RUST_BACKTRACE")
        .output()
        .expect("run bash");
    let output = String::from_utf8_lossy(&out.stdout).into_owned();
    let shown = || format!("--- the lines run ---\n{script}\n--- what they printed ---\n{output}");
    if !out.status.success() {
        return vec![format!(
            "{}: failed with {}\n{}",
            block.place(),
            out.status,
            shown()
        )];
    }
    let mut problems = Vec::new();
    if size.is_none() {
        for printed in block.printed_output() {
            for line in printed
                .lines()
                .filter(|l| !l.trim().is_empty() && l.trim() != "...")
            {
                if Pattern::printed_line(line).find(&output).is_none() {
                    problems.push(format!(
                        "{}: the printed output's line\n    {line}\nis not what the commands \
                         printed (same seed and size)",
                        block.place()
                    ));
                }
            }
        }
    }
    for figure in run.figures {
        if let Err(e) = check_figure(figure, block, &output, size.as_ref()) {
            problems.push(format!("{}: {}: {e}", block.place(), figure.what));
        }
    }
    if !problems.is_empty() {
        problems.push(format!("{}:\n{}", block.place(), shown()));
    }
    problems
}

/// Whether `figure`'s numbers in the text after `block` agree with the same numbers in
/// `output`, as its plan says they must.
fn check_figure(
    figure: &Figure,
    block: &Block,
    output: &str,
    size: Option<&Size>,
) -> Result<(), String> {
    let printed = Pattern::new(figure.readme)
        .find(&block.section_rest)
        .ok_or(format!("the text no longer prints {:?}", figure.readme))?;
    let got = Pattern::new(figure.output)
        .find(output)
        .ok_or(format!("the commands printed no {:?}", figure.output))?;
    let values = |v: &[Printed]| v.iter().map(|p| p.value).collect::<Vec<_>>();
    let differs = |why: &str| {
        Err(format!(
            "the text prints {:?}, the commands gave {:?} ({why})",
            values(&printed),
            values(&got)
        ))
    };
    let smaller = size.filter(|s| s.run != s.printed);
    match (figure.agree, smaller) {
        (Agree::Digits, Some(s)) => Err(format!(
            "compared digit for digit, but the block runs at {} {} where the text printed {}: \
             give the figure a statistical check",
            s.flag, s.run, s.printed
        )),
        (Agree::Digits, None) | (Agree::DigitsAtAnySize, _) => {
            if printed.len() != got.len() {
                return differs("not as many numbers");
            }
            let same = printed
                .iter()
                .zip(&got)
                .all(|(p, g)| (p.value - g.value).abs() <= p.half_digit + g.half_digit + 1e-12);
            if same {
                Ok(())
            } else {
                differs("they must agree to the printed digits")
            }
        }
        (Agree::InInterval, _) => {
            let (&[p], &[low, high]) = (printed.as_slice(), got.as_slice()) else {
                return differs("a value against an interval: one number and two");
            };
            let slack = p.half_digit + low.half_digit.max(high.half_digit);
            if low.value - slack <= p.value && p.value <= high.value + slack {
                Ok(())
            } else {
                differs("the printed value outside the interval the run printed")
            }
        }
        (Agree::Share(_) | Agree::Count, None) => Err(
            "a statistical check of a run of the printed size: compare it digit for digit"
                .to_string(),
        ),
        (Agree::Share(_) | Agree::Count, Some(s)) => {
            let (&[p], &[g]) = (printed.as_slice(), got.as_slice()) else {
                return differs("a share against a share: one number each");
            };
            let (printed_n, run_n) = (s.printed, s.run);
            let (share, run_share, n) = match figure.agree {
                Agree::Share(of) => (p.value / 100.0, g.value / 100.0, of * run_n),
                _ => (p.value / printed_n, g.value / run_n, run_n),
            };
            let n = n.max(1.0);
            let error = (share * (1.0 - share) / n).sqrt().max(1.0 / n);
            let rounding = match figure.agree {
                Agree::Count => 0.0,
                _ => (p.half_digit + g.half_digit) / 100.0,
            };
            if (share - run_share).abs() <= STANDARD_ERRORS * error + rounding {
                Ok(())
            } else {
                differs(&format!(
                    "shares {share:.4} and {run_share:.4} of {n} samples, more than \
                     {STANDARD_ERRORS} standard errors ({error:.4}) apart"
                ))
            }
        }
    }
}
