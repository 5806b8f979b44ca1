//! What the test does with each command block of the two READMEs, and the figures the
//! text prints after the blocks it runs.

/// A command block's plan.
pub(super) struct Plan {
    /// The file the block is in.
    pub(super) file: &'static str,
    /// Text that only this block of the file contains.
    pub(super) key: &'static str,
    pub(super) how: How,
}

pub(super) enum How {
    /// Run here.
    Run(Run),
    /// Run by another test, named.
    Elsewhere(&'static str),
    /// Not run in the tests, and why.
    NotRun(&'static str),
}

/// How a block runs.
pub(super) struct Run {
    /// Shell lines run before it (a file the text tells the reader to make).
    pub(super) before: &'static str,
    /// Shell lines run after it: a check of what its comments claim.
    pub(super) then: &'static str,
    /// Its lines that are left out (containing the first text), and why.
    pub(super) drop: &'static [(&'static str, &'static str)],
    /// The figures the text prints after it, beside its printed output's lines.
    pub(super) figures: &'static [Figure],
}

/// A figure of the text and the same figure in what the commands printed: patterns of
/// literal text with `{}` for each number compared (in the same order in both), `{_}` for a
/// number passed over and `{..}` for any text.
pub(super) struct Figure {
    pub(super) what: &'static str,
    pub(super) readme: &'static str,
    pub(super) output: &'static str,
    pub(super) agree: Agree,
}

/// How a figure of the text and of a run must agree.
#[derive(Clone, Copy)]
pub(super) enum Agree {
    /// The run of the printed size: to the printed digits.
    Digits,
    /// A figure no size changes (a body's gravity and slopes): to the printed digits.
    DigitsAtAnySize,
    /// The text's value inside the 95 % interval the run printed.
    InInterval,
    /// A share in percent of the given fraction of the samples, within the standard
    /// errors of a run of fewer samples.
    Share(f64),
    /// A count of samples, as a share of the samples, the same.
    Count,
}

const fn run(figures: &'static [Figure]) -> How {
    How::Run(Run {
        before: "",
        then: "",
        drop: &[],
        figures,
    })
}

const fn figure(
    what: &'static str,
    readme: &'static str,
    output: &'static str,
    agree: Agree,
) -> Figure {
    Figure {
        what,
        readme,
        output,
        agree,
    }
}

const README: &str = "README.md";
const SCENARIOS: &str = "scenarios/README.md";

/// Why the Python package's examples are not run here.
const NEEDS_THE_PACKAGE: &str = "needs the Python package installed (`pip install ./python`, the \
    block above); tests/python_package.rs builds it and runs python/tests";

/// Why the thesis studies' runs are not.
const ALL_STUDIES: &str = "every study file at its own samples: about 20 minutes of sweeping on \
    2 cores";

pub(super) const PLANS: &[Plan] = &[
    Plan {
        file: README,
        key: "cargo run --release -- sweep --samples 1e6 --out sweep.arrow",
        how: How::Run(Run {
            before: "",
            then: "",
            drop: &[(
                "cargo test --release",
                "the test command itself, which runs this test",
            )],
            figures: &[],
        }),
    },
    Plan {
        file: README,
        key: "t = pl.read_ipc(\"trace.arrow\")",
        how: How::Run(Run {
            before: "touchdown trace",
            then: "",
            drop: &[],
            figures: &[],
        }),
    },
    Plan {
        file: README,
        key: "touchdown trace --sweep sweep.arrow --sample 2 --out s2.arrow",
        how: run(&[]),
    },
    Plan {
        file: README,
        key: "cat > soil.toml",
        how: run(&[figure(
            "the stable share on the drawn ground",
            "Of the 200,000 landers {} % stand",
            "outcomes stable {_} {} %",
            Agree::Share(1.0),
        )]),
    },
    Plan {
        file: README,
        key: "pl.read_ipc('soil.arrow')",
        how: run(&[]),
    },
    Plan {
        file: README,
        key: "touchdown sweep --inputs gnc.csv --out gnc.arrow",
        how: How::Elsewhere(
            "tests/inputs/readme.rs, on a default sweep of 3,000 samples, with the default \
             scenario as changed.toml",
        ),
    },
    Plan {
        file: README,
        key: "scenarios/sensitivity-flat.toml --out sf.arrow",
        how: How::NotRun(
            "800,000 samples of landers that slide until t_max: 12.6 min on 2 AVX-512 cores",
        ),
    },
    Plan {
        file: README,
        key: "--vary lander.footpad_radius_m=0.45:0.9:10",
        how: How::NotRun(
            "200,000 samples: 387 s on 2 AVX-512 cores; tests/study.rs checks a study's table \
             against the report of each of its sweeps",
        ),
    },
    Plan {
        file: README,
        key: "scenarios/flat.toml --samples 20000 --out flat.arrow",
        how: run(&[
            figure(
                "the stable share on the sweep's slopes",
                "stand on {} % of its uniform",
                "| stable | {_} | {} % |",
                Agree::Digits,
            ),
            figure(
                "the stable share on Rayleigh slopes of mode 10 deg",
                "mode of 10°, {} % ({}-{} %)",
                "rayleigh:10 Each sample{..}| stable | {} % | {} – {} % |",
                Agree::Digits,
            ),
            figure(
                "the effective sample size on those slopes",
                "worth {} unweighted",
                "rayleigh:10 Each sample{..}worth {} unweighted",
                Agree::Digits,
            ),
            figure(
                "the stable share on slopes normal about 35 deg",
                "(sd 8°), {} % ({}-{} %)",
                "sd 8 deg, within 0-90 deg){..}| stable | {} % | {} – {} % |",
                Agree::Digits,
            ),
        ]),
    },
    Plan {
        file: README,
        key: "cat > wide.toml",
        how: run(&[
            figure(
                "the allowable slope of the 0-45 deg sector",
                "| 0–45 deg | {_} | {_} | {} deg |",
                "| 0–45 deg | {_} | {_} | {_} deg | {}–{} deg |",
                Agree::InInterval,
            ),
            figure(
                "the allowable slope of the 45-90 deg sector",
                "| 45–90 deg | {_} | {_} | {} deg |",
                "| 45–90 deg | {_} | {_} | {_} deg | {}–{} deg |",
                Agree::InInterval,
            ),
            figure(
                "the allowable slope of the 315-360 deg sector",
                "| 315–360 deg | {_} | {_} | {} deg |",
                "| 315–360 deg | {_} | {_} | {_} deg | {}–{} deg |",
                Agree::InInterval,
            ),
        ]),
    },
    Plan {
        file: README,
        key: "cat > touchdown-state.toml",
        how: run(&[]),
    },
    Plan {
        file: README,
        key: "touchdown envelope touchdown-state.arrow",
        how: run(&[]),
    },
    Plan {
        file: README,
        key: "cat > plane.toml",
        how: run(&[
            figure(
                "the samples on slopes of 0-15 deg",
                "## slope 0–15 deg: {} samples",
                "## slope 0–15 deg: {} samples",
                Agree::Count,
            ),
            // A third of the samples lie on 0-15 deg.
            figure(
                "their stable share",
                "## slope 0–15 deg: {_} samples, {} % stable",
                "## slope 0–15 deg: {_} samples, {} % stable",
                Agree::Share(0.33),
            ),
        ]),
    },
    Plan {
        file: README,
        key: "cat > gear.toml",
        how: run(&[]),
    },
    Plan {
        file: README,
        key: "cat > td.toml",
        how: run(&[
            figure(
                "the tangential speed 99 % stable at 0.05-0.10 m/s towards the surface",
                "up to {} m/s (",
                "|---|---:|---:|---:|---:| | {_}–{_} | {_} | {_} % | {_} | {}–{} |",
                Agree::InInterval,
            ),
            figure(
                "the same at 0.10-0.15 m/s",
                "up to {_} m/s ({_}-{_}) and {} m/s",
                "|---|---:|---:|---:|---:| | {_}–{_} | {_} | {_} % | {_} | {_}–{_} | | {_}–{_} | {_} | {_} % | {_} | {}–{} |",
                Agree::InInterval,
            ),
        ]),
    },
    Plan {
        file: README,
        key: "--shard $k/4 --out part$k.arrow",
        how: How::Run(Run {
            before: "",
            // The comment's claim: the merged shards are the one process's file.
            then: "touchdown sweep --samples 1e7 --quiet --out one.arrow\ncmp one.arrow sweep.arrow\n",
            drop: &[],
            figures: &[],
        }),
    },
    Plan {
        file: README,
        key: "SHARDS=16 SAMPLES=1e7",
        how: How::NotRun(
            "needs a Slurm cluster; tests/slurm/run.sh, run by .ci/run, runs the same scripts on \
             a single-node Slurm",
        ),
    },
    Plan {
        file: README,
        key: ".venv/bin/pip install -v ./python",
        how: How::NotRun(
            "builds the Python package (minutes); tests/python_package.rs builds the same wheel \
             and tests it",
        ),
    },
    Plan {
        file: README,
        key: "s = touchdown.Scenario.default()",
        how: How::NotRun(NEEDS_THE_PACKAGE),
    },
    Plan {
        file: README,
        key: "class DampThenHold:",
        how: How::NotRun(NEEDS_THE_PACKAGE),
    },
    Plan {
        file: README,
        key: "scenarios/flat.toml > flat-0-40.toml",
        how: run(&[
            figure(
                "the stable share on the elastic plane",
                "| stable | {} % | {_} % |",
                "| stable | {} % | {_} % |",
                Agree::Share(1.0),
            ),
            figure(
                "the stable share on regolith",
                "| stable | {_} % | {} % |",
                "| stable | {_} % | {} % |",
                Agree::Share(1.0),
            ),
            figure(
                "the tipped share on regolith",
                "| tipped | {_} % | {} % |",
                "| tipped | {_} % | {} % |",
                Agree::Share(1.0),
            ),
        ]),
    },
    Plan {
        file: README,
        key: "scenarios/rocks.toml --samples 10000 --out rocks.arrow",
        how: run(&[
            figure(
                "the stable share among rocks",
                "outcomes stable {_} {} %",
                "outcomes stable {_} {} %",
                Agree::Share(1.0),
            ),
            figure(
                "the tipped share among rocks",
                "outcomes stable {_} {_} % tipped {_} {} %",
                "outcomes stable {_} {_} % tipped {_} {} %",
                Agree::Share(1.0),
            ),
        ]),
    },
    Plan {
        file: README,
        key: "--samples 2e5 --out-dir didymos",
        how: run(&[
            figure(
                "the effective gravity",
                "| effective gravity | {} to {} m/s^2 (a factor of {}), mean {} |",
                "| effective gravity | {} to {} m/s^2 (ratio {}), mean {} by area |",
                Agree::DigitsAtAnySize,
            ),
            figure(
                "the slopes",
                "| slope | mean {} deg by area, median {}, steepest {}; {} / {} / {} % of the surface",
                "| slope | mean {} deg by area, median {}, steepest {}; below 10 / 20 / 30 deg: {} / {} / {} %",
                Agree::DigitsAtAnySize,
            ),
            figure(
                "the surface where gravity points off the ground",
                "(slope over 90 deg) | **{} % of the surface**",
                "(slope over 90 deg) | {} %",
                Agree::DigitsAtAnySize,
            ),
            figure(
                "the roughness",
                "| roughness (reported only) | mean {} deg by area, median {}, roughest {} |",
                "| roughness | mean {} deg by area, median {}, roughest {} (",
                Agree::DigitsAtAnySize,
            ),
            figure(
                "the surface too steep to stand on",
                "({} % too steep to stand on",
                "too steep to stand on (89 deg or more) | {} %",
                Agree::DigitsAtAnySize,
            ),
        ]),
    },
    Plan {
        file: README,
        key: "for k in 0 1 2 3; do $site --shard $k/4; done",
        how: How::NotRun("1e6 samples of 1200 s runs: about 37 min on 2 AVX-512 cores"),
    },
    Plan {
        file: README,
        key: "touchdown site bodies/itokawa/itokawa.obj",
        how: How::NotRun(
            "the shape model is not in the repository: bodies/itokawa/SOURCE.md downloads it",
        ),
    },
    Plan {
        file: README,
        key: "cargo run --release -p user_law",
        how: How::NotRun(
            "compiles a second program (examples/user_law), minutes; its own crate tests its \
             sweep (examples/user_law/tests/sweep.rs)",
        ),
    },
    Plan {
        file: README,
        key: "cargo bench --bench throughput",
        how: How::NotRun(
            "benchmarks: the prototype and MuJoCo's script lie outside the repository \
             (../shared/anchors), and their figures want idle cores",
        ),
    },
    Plan {
        file: README,
        key: "for t in 1 2 $(nproc); do",
        how: How::NotRun(
            "measures speed (three sweeps of 2e5 samples, a minute on 2 cores): its figures \
             want idle cores, and the serial share it prints is a ratio of CPU times",
        ),
    },
    Plan {
        file: SCENARIOS,
        key: "for f in scenarios/*.toml; do",
        how: How::NotRun(ALL_STUDIES),
    },
    Plan {
        file: SCENARIOS,
        key: "scenarios/run-all.sh target/release/touchdown out",
        how: How::NotRun(ALL_STUDIES),
    },
    Plan {
        file: SCENARIOS,
        key: "for f in hold-down-study hold-down-study-attitude; do",
        how: How::NotRun("2 x 144,000 samples: 88 s on 2 AVX-512 cores"),
    },
    Plan {
        file: SCENARIOS,
        key: "--vary lander.footpad_radius_m=0.45:0.9:10",
        how: How::NotRun(
            "200,000 samples: 387 s on 2 AVX-512 cores; tests/study.rs checks a study's table \
             against the report of each of its sweeps",
        ),
    },
];
