//! The sweep run: a scenario from its file, a sweep file or the command line's values
//! turned into a plan, and the plan run on a pool of workers (signals, progress, resume,
//! the writer). Every command that runs the lander (sweep, study, boundary, trace) comes
//! through here; nothing here knows the command line's flags.

pub mod boundary;
mod eta;
mod execute;
mod folder;
mod load;
pub mod memory;
mod plan;
mod signals;
pub mod site;
mod steps;
pub mod study;
pub mod trace;
mod workers;

pub use execute::{Executed, RunOptions, execute, warn_untouched};
pub use load::{
    KernelChoice, load_scenario, scenario_from_toml, scenario_of_metadata, scenario_of_sweep,
    scenario_of_text,
};
pub use plan::{SweepPlan, SweepSettings, output_format};
pub use signals::{end_on_signals, signal_name, stop_on_signals};
pub use workers::{CHUNK, Interrupted, shown, tell, worker_pool};
