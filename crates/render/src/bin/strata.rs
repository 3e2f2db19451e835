//! The `strata` command: `strata render …` and `strata diff A.exr B.exr` (see `render::cli`).

use std::process::ExitCode;

use clap::Parser;
use render::cli::Cli;
use render::commands::run;

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(&cli.command, &mut std::io::stdout().lock()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("strata: {error}");
            ExitCode::from(error.exit_code())
        }
    }
}
