//! `touchdown sensitivity`'s report: the indices of a Saltelli sweep as Markdown.

use super::analysis::{Analysis, OUTPUTS, analyse};

/// `touchdown sensitivity`: the first-order and total indices of every varied input for
/// P(stable), P(tipped), the peak CG acceleration and the longest damper stroke, from a
/// sweep (or shard) run with `design = "sobol-indices"`, as Markdown.
pub fn report(path: &std::path::Path, bootstrap: usize) -> anyhow::Result<String> {
    Ok(markdown(path, &analyse(path, bootstrap)?))
}

/// The Markdown report of `analysis` of the sweep at `path`.
#[must_use]
pub fn markdown(path: &std::path::Path, analysis: &Analysis) -> String {
    use std::fmt::Write as _;
    let Analysis {
        names,
        outputs,
        base_points: n,
        rows,
        interrupted,
        seed,
        bootstrap,
    } = analysis;
    let mut t = String::new();
    let _ = writeln!(t, "# touchdown sensitivity: {}\n", path.display());
    if let Some(note) = interrupted {
        let _ = writeln!(t, "**{note}.**\n");
    }
    let _ = writeln!(
        t,
        "{n} base points of Saltelli's design ({} samples each: A, B and one AB_i per varied \
         input; {rows} samples in the file), seed {seed}. First-order indices S_i (Saltelli \
         2010: the share of the variance an input explains alone) and total indices ST_i \
         (Jansen 1999: with all its interactions), with 95 % bootstrap intervals from \
         {bootstrap} replicates. Inputs not listed are fixed in the scenario.\n",
        names.len() + 2,
    );
    for (name, (mean, ix)) in OUTPUTS.iter().zip(outputs) {
        let _ = writeln!(t, "## {name}: mean {mean:.4} over A and B\n");
        match ix {
            None => {
                let _ = writeln!(t, "No variance: every sample gives {mean}.\n");
            }
            Some(ix) => {
                let _ = writeln!(
                    t,
                    "| input | S_i | 95 % interval | ST_i | 95 % interval |\n|---|---:|---:|---:|---:|"
                );
                for (q, input) in names.iter().enumerate() {
                    let (f, tt) = (ix.first[q], ix.total[q]);
                    let _ = writeln!(
                        t,
                        "| {input} | {:.3} | {:.3} to {:.3} | {:.3} | {:.3} to {:.3} |",
                        f.estimate, f.low, f.high, tt.estimate, tt.low, tt.high
                    );
                }
                let _ = writeln!(t);
            }
        }
    }
    t
}
