use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
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
