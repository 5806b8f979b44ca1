//! Python readers: the Arrow and Parquet files of sweeps of four- and three-leg landers,
//! read by `check_sweep.py`, hold the samples, seed, legs and outcome counts of the sweep.

use super::sweep;
use crate::common::{SHORT, THREE_LEGS, TempDir, python_readers_available, run_python_check};

/// Runs a sweep and `check_sweep.py` on its file.
fn check_sweep_with_python(dir: &TempDir, scenario: &str, seed: u64, format: &str, legs: usize) {
    let samples = 3000;
    let out = format!("sweep-{legs}-legs.{format}");
    let (seed_s, samples_s) = (seed.to_string(), samples.to_string());
    let args = [
        "--scenario",
        scenario,
        "--samples",
        &samples_s,
        "--seed",
        &seed_s,
        "--format",
        format,
        "--out",
        &out,
        "--quiet",
    ];
    let (_, s) = sweep(dir, &args);
    assert_eq!(s.samples, samples);
    let counts = s
        .outcomes
        .iter()
        .map(|(o, c)| format!("\"{o}\": {c}"))
        .collect::<Vec<_>>()
        .join(", ");
    run_python_check(
        "check_sweep.py",
        &[
            dir.join(&out).as_os_str(),
            format.as_ref(),
            samples_s.as_ref(),
            seed_s.as_ref(),
            legs.to_string().as_ref(),
            format!("{{{counts}}}").as_ref(),
        ],
        &format!("the sweep file of `touchdown sweep {}`", args.join(" ")),
    );
}

#[test]
fn python_readers_open_the_sweep() {
    if !python_readers_available("python_readers_open_the_sweep") {
        return;
    }
    let dir = TempDir::new("sweep-python");
    dir.write("short.toml", SHORT);
    dir.write("three-legs.toml", THREE_LEGS);
    check_sweep_with_python(&dir, "short.toml", 11, "arrow", 4);
    check_sweep_with_python(&dir, "short.toml", 11, "parquet", 4);
    check_sweep_with_python(&dir, "three-legs.toml", 12, "arrow", 3);
    check_sweep_with_python(&dir, "three-legs.toml", 12, "parquet", 3);
}
