use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = touchdown::cli::Cli::parse();
    match touchdown::cli::run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("touchdown: error: {e:#}");
            ExitCode::from(2)
        }
    }
}
