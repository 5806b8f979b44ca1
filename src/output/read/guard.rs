//! The last line of defence against hostile bytes: arrow-rs and parquet may panic inside
//! their decoders on a damaged file (a buffer's offset past the end of the body, a negative
//! length), and we cannot change them. `guarded` runs the decoding of one file and turns
//! such a panic into an error naming the file. The panic hook stays silent for guarded code
//! on its own thread, and prints as before for any other panic, a real bug.

use anyhow::anyhow;
use std::cell::Cell;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;
use std::sync::Once;

thread_local! {
    /// How many guards this thread is inside (they may nest).
    static GUARDS: Cell<u32> = const { Cell::new(0) };
}

/// Runs `decode`, the decoding of the file at `path`; a panic inside it becomes the error
/// "cannot read PATH: the file is damaged (the panic's message)".
pub fn guarded<T>(path: &Path, decode: impl FnOnce() -> anyhow::Result<T>) -> anyhow::Result<T> {
    catch(decode).unwrap_or_else(|why| Err(damaged(path, &why)))
}

/// Runs `decode`; its value, or the message of the panic that ended it. The decoder's
/// state is not to be used after a panic (whoever called it drops it).
pub(super) fn catch<T>(decode: impl FnOnce() -> T) -> Result<T, String> {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if GUARDS.with(Cell::get) == 0 {
                previous(info);
            }
        }));
    });
    GUARDS.with(|g| g.set(g.get() + 1));
    let result = catch_unwind(AssertUnwindSafe(decode));
    GUARDS.with(|g| g.set(g.get() - 1));
    result.map_err(|payload| {
        payload
            .downcast_ref::<&str>()
            .map(ToString::to_string)
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "the decoder stopped".to_string())
    })
}

/// The error of a damaged file: "cannot read PATH: the file is damaged (WHY)".
pub fn damaged(path: &Path, why: &str) -> anyhow::Error {
    anyhow!(
        "cannot read {}: the file is damaged ({why})",
        path.display()
    )
}
