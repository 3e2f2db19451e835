//! The `strata` command: `strata render …`, `strata diff A.exr B.exr` and `strata merge …` (see
//! `render::cli`).

use std::process::ExitCode;

use clap::Parser;
use render::cli::{Cli, Command};
use render::commands::run;
use render::stop::{StopSignal, raise_on_ctrl_c};

fn main() -> ExitCode {
    let cli = Cli::parse();
    let stop = StopSignal::new();
    if matches!(cli.command, Command::Render(_))
        && let Err(error) = raise_on_ctrl_c(stop.clone())
    {
        eprintln!("strata: warning: Ctrl-C will not stop at a pass boundary: {error}");
    }
    match run(&cli.command, &mut std::io::stdout().lock(), &stop) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("strata: {error}");
            ExitCode::from(error.exit_code())
        }
    }
}
