//! One binary for every x86-64: it picks the widest kernel the CPU runs, `--kernel` picks
//! another or is refused naming what the CPU lacks, and kernels that fuse their
//! multiply-adds write the same file. Under QEMU user mode (Debian's `qemu-user`), the
//! release binary runs a sweep on an emulated CPU without AVX-512 (Haswell: AVX2 and FMA)
//! and one without AVX (Nehalem) with the outcome counts of this machine.

use crate::common::{SHORT, TempDir, read_bytes, touchdown};
use kernels::isa::{Isa, Precision};
use std::io::Write;
use std::process::Command;

/// The kernel the banner names (`kernel f64x4 AVX2 (...`).
fn banner_kernel(stderr: &str) -> String {
    let at = stderr.find("kernel ").expect("the banner names the kernel") + "kernel ".len();
    stderr[at..]
        .split(" (")
        .next()
        .expect("kernel name")
        .to_string()
}

/// The outcome lines of a sweep's closing summary.
fn outcome_lines(stdout: &str) -> Vec<String> {
    stdout
        .lines()
        .skip_while(|l| *l != "outcomes")
        .take(6)
        .map(str::to_string)
        .collect()
}

#[test]
fn each_kernel_this_cpu_runs_can_be_chosen_and_fused_ones_write_the_same_file() {
    let dir = TempDir::new("kernels");
    dir.write("short.toml", SHORT);
    let mut fused_file: Option<(Isa, Vec<u8>)> = None;
    for isa in Isa::ALL {
        let out = format!("{}.arrow", isa.key());
        let args = [
            "sweep",
            "--scenario",
            "short.toml",
            "--samples",
            "600",
            "--out",
            &out,
            "--kernel",
            isa.key(),
        ];
        let run = touchdown(dir.path(), &args);
        if !isa.available() {
            assert_eq!(run.code, Some(2), "{run}");
            assert!(
                run.stderr.contains("this CPU cannot run it (it lacks"),
                "{run}"
            );
            continue;
        }
        assert_eq!(run.code, Some(0), "{run}");
        assert_eq!(
            banner_kernel(&run.stderr),
            isa.kernel(Precision::F64).name(),
            "{run}"
        );
        if isa.fused() {
            let bytes = read_bytes(&dir.join(&out));
            match &fused_file {
                None => fused_file = Some((isa, bytes)),
                Some((first, first_bytes)) => assert!(
                    &bytes == first_bytes,
                    "the {} and {} kernels wrote different files",
                    first.key(),
                    isa.key()
                ),
            }
        }
    }
    let auto = touchdown(dir.path(), &["sweep", "--samples", "8", "--quiet"]);
    assert_eq!(
        banner_kernel(&auto.stderr),
        Isa::detect().kernel(Precision::F64).name(),
        "{auto}"
    );
    let bad = touchdown(dir.path(), &["sweep", "--kernel", "sse9"]);
    assert_eq!(bad.code, Some(2), "{bad}");
    assert!(
        bad.stderr
            .contains("\"sse9\" is not a kernel: auto, avx512, avx2, portable"),
        "{bad}"
    );
}

/// Whether `qemu-x86_64` can run here; when it cannot, the test is skipped with a note
/// (CI installs Debian's `qemu-user` and sets `TOUCHDOWN_REQUIRE_QEMU=1`, which makes a
/// missing QEMU a failure).
fn qemu_available(test: &str) -> bool {
    if Command::new("qemu-x86_64")
        .arg("--version")
        .output()
        .is_ok()
    {
        return true;
    }
    assert!(
        std::env::var("TOUCHDOWN_REQUIRE_QEMU").as_deref() != Ok("1"),
        "qemu-x86_64 is missing but TOUCHDOWN_REQUIRE_QEMU=1"
    );
    let _ = writeln!(
        std::io::stderr(),
        "\nSKIPPED {test}: qemu-x86_64 not found (Debian: apt-get install qemu-user)"
    );
    false
}

#[test]
fn the_binary_runs_on_cpus_without_avx512_and_without_avx() {
    if !cfg!(target_arch = "x86_64")
        || !qemu_available("the_binary_runs_on_cpus_without_avx512_and_without_avx")
    {
        return;
    }
    let dir = TempDir::new("qemu");
    dir.write("short.toml", SHORT);
    let sweep = |prefix: &[&str], out: &str| {
        let mut cmd = Command::new(prefix.first().copied().unwrap_or(crate::common::BIN));
        if !prefix.is_empty() {
            cmd.args(&prefix[1..]).arg(crate::common::BIN);
        }
        let o = cmd
            .args([
                "sweep",
                "--scenario",
                "short.toml",
                "--samples",
                "800",
                "--quiet",
                "--out",
                out,
            ])
            .current_dir(dir.path())
            .output()
            .expect("run the sweep");
        let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
        let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
        assert!(
            o.status.success(),
            "{prefix:?}: exit {:?}\n{stdout}\n{stderr}",
            o.status.code()
        );
        (banner_kernel(&stderr), outcome_lines(&stdout))
    };
    let (native_kernel, native) = sweep(&[], "native.arrow");
    let (haswell_kernel, haswell) = sweep(&["qemu-x86_64", "-cpu", "Haswell"], "haswell.arrow");
    let (nehalem_kernel, nehalem) = sweep(&["qemu-x86_64", "-cpu", "Nehalem"], "nehalem.arrow");
    println!("native {native_kernel}, Haswell {haswell_kernel}, Nehalem {nehalem_kernel}");
    assert_eq!(haswell_kernel, Isa::Avx2.kernel(Precision::F64).name());
    assert_eq!(nehalem_kernel, Isa::Portable.kernel(Precision::F64).name());
    assert_eq!(haswell, native, "outcomes on an emulated Haswell");
    assert_eq!(nehalem, native, "outcomes on an emulated Nehalem");
    if Isa::detect().fused() {
        assert!(
            read_bytes(&dir.join("haswell.arrow")) == read_bytes(&dir.join("native.arrow")),
            "the AVX2 kernel on Haswell wrote another file than the {} kernel here",
            Isa::detect().key()
        );
    }
    // The widest kernel is refused on a CPU without it, naming what it lacks.
    let o = Command::new("qemu-x86_64")
        .args([
            "-cpu",
            "Haswell",
            crate::common::BIN,
            "sweep",
            "--kernel",
            "avx512",
        ])
        .current_dir(dir.path())
        .output()
        .expect("run the sweep");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("it lacks avx512f"), "{stderr}");
}
