//! Sample counts: in any notation, they give the same sweep.

use super::{check_sweep_file, sweep};
use crate::common::{SHORT, TempDir, read_bytes};
use touchdown::scenario::INPUT_FIELDS;

#[test]
fn sample_counts_in_any_notation_give_the_same_sweep() {
    let dir = TempDir::new("sweep-samples");
    dir.write("short.toml", SHORT);
    let run = |samples: &str, out: &str| {
        let (b, s) = sweep(
            &dir,
            &[
                "--scenario",
                "short.toml",
                "--samples",
                samples,
                "--seed",
                "4",
                "--out",
                out,
            ],
        );
        assert_eq!((b.samples, b.seed), (2500, 4));
        assert_eq!(s.samples, 2500, "the summary's `samples` line");
        check_sweep_file(&dir.join(out), &s, 4, SHORT);
        s
    };
    let plain = run("2500", "plain.arrow");
    let sci = run("2.5e3", "sci.arrow");
    assert_eq!(plain.outcomes, sci.outcomes);
    assert!(
        read_bytes(&dir.join("plain.arrow")) == read_bytes(&dir.join("sci.arrow")),
        "--samples 2.5e3 and --samples 2500 wrote different files"
    );

    // Without --samples, the scenario's `samples`; with it, the flag's.
    let text = format!("samples = 1200\n{SHORT}");
    dir.write("counted.toml", &text);
    let (b, s) = sweep(
        &dir,
        &["--scenario", "counted.toml", "--out", "default.arrow"],
    );
    assert_eq!((b.samples, s.samples), (1200, 1200));
    let default = check_sweep_file(&dir.join("default.arrow"), &s, 1, &text);
    let (b, s) = sweep(
        &dir,
        &[
            "--scenario",
            "counted.toml",
            "--samples",
            "700",
            "--out",
            "flag.arrow",
        ],
    );
    assert_eq!((b.samples, s.samples), (700, 700));
    let flag = check_sweep_file(&dir.join("flag.arrow"), &s, 1, &text);
    // Fewer samples of the same sweep: the first rows of the longer one.
    for (name, _) in INPUT_FIELDS {
        assert!(
            default.f64s(name)[..700] == flag.f64s(name)[..],
            "{name}: the 700 samples are not the first 700 of 1200"
        );
    }
    assert_eq!(
        default.strings("outcome")[..700],
        flag.strings("outcome")[..]
    );
}
