//! Whether the memory a request would hold fits the machine: a request that would not is
//! refused with its estimate before any work, rather than dying of it halfway.

/// Bytes of memory the machine has available for a new process (Linux: `MemAvailable` of
/// `/proc/meminfo`); `None` where it does not say.
#[must_use]
pub fn available_bytes() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib.saturating_mul(1024))
}

/// `bytes` as people read it: `512 MB`, `3.2 GB`, `1.3e5 GB`.
#[must_use]
pub fn shown_bytes(bytes: u64) -> String {
    let gb = bytes as f64 / 1e9;
    if gb < 1.0 {
        format!("{:.0} MB", bytes as f64 / 1e6)
    } else if gb < 1e4 {
        format!("{gb:.1} GB")
    } else {
        format!("{gb:.1e} GB")
    }
}

/// Refuses a request that would hold about `bytes` of memory where the machine has less
/// available; `what` names the request and says what the estimate counts.
pub fn check_fits(bytes: u64, what: impl FnOnce() -> String) -> anyhow::Result<()> {
    match available_bytes() {
        Some(free) if bytes > free => anyhow::bail!(
            "{} would hold about {} of memory, and this machine has {} available: ask \
             for less",
            what(),
            shown_bytes(bytes),
            shown_bytes(free)
        ),
        _ => Ok(()),
    }
}

/// Makes every thread of the process allocate from one malloc arena (glibc), unless the
/// user set their number with `MALLOC_ARENA_MAX`. Called first thing, before any thread.
///
/// glibc gives each thread an arena of its own (up to 8 a core), and each arena keeps the
/// peak of what its thread once held: the rows and columns a worker builds, the Parquet
/// pages it encodes. So the peak memory of a sweep grew with its threads, and with one arena
/// it does not (README, "One malloc arena", has the figures). Nothing allocates in a step:
/// a sample costs about two allocations, which glibc's per-thread cache mostly serves
/// without the arena's lock, and all of malloc and free took 0.2 % of the sweep's
/// instructions (callgrind, 5,000 samples), so the one lock is no serial share worth
/// counting. Elsewhere (musl, other systems) this does nothing.
pub fn one_malloc_arena() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    if std::env::var_os("MALLOC_ARENA_MAX").is_none() {
        // SAFETY: `mallopt` sets one of the allocator's parameters; it reads and writes
        // nothing of ours.
        unsafe {
            libc::mallopt(libc::M_ARENA_MAX, 1);
        }
    }
}
