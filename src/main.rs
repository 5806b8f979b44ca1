use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let missing = kernels::lane::missing_cpu_features();
    if !missing.is_empty() {
        eprintln!(
            "touchdown: error: this build runs {} kernels with {} instructions, which this CPU \
             lacks ({}); rebuild it for this machine: \
             RUSTFLAGS=\"-C target-cpu=native\" cargo build --release",
            kernels::lane::LANE_NAME,
            kernels::lane::INSTRUCTION_SET,
            missing.join(", ")
        );
        return ExitCode::from(2);
    }
    let cli = touchdown::cli::Cli::parse();
    match touchdown::cli::run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            if let Some(i) = e.downcast_ref::<touchdown::cli::Interrupted>() {
                eprintln!("touchdown: {i}");
                return ExitCode::from(i.code);
            }
            eprintln!("touchdown: error: {e:#}");
            ExitCode::from(2)
        }
    }
}
