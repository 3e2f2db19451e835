//! Running the `strata` subcommands, and how their failures map to exit statuses.

use std::fmt;
use std::io::Write;

use crate::cli::Command;
use crate::diff::DiffReport;
use crate::film_exr::write_film_exr;
use crate::merge::merge_files;
use crate::stop::{INTERRUPTED_EXIT_STATUS, StopSignal};

/// A failed command. The exit status is 2 for bad input and 1 for anything else
/// (command-line syntax errors are reported by clap, also with status 2).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum CommandError {
    /// The input was at fault (a missing or malformed file, images of different sizes); the
    /// message names the file.
    BadInput(String),
    /// Anything else (an output that cannot be written, an unfinished feature).
    Failed(String),
    /// A render was stopped by Ctrl-C before its budget was spent; it wrote the image of the
    /// samples done (the message says which files and how many samples).
    Interrupted(String),
}

impl CommandError {
    /// The process exit status for this error: 2 for bad input, 130 (128 + SIGINT) for an
    /// interrupted render, 1 otherwise.
    pub fn exit_code(&self) -> u8 {
        match self {
            Self::BadInput(_) => 2,
            Self::Failed(_) => 1,
            Self::Interrupted(_) => INTERRUPTED_EXIT_STATUS,
        }
    }
}

impl fmt::Display for CommandError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::BadInput(message) | Self::Failed(message) | Self::Interrupted(message) => {
                f.write_str(message)
            }
        }
    }
}

impl std::error::Error for CommandError {}

/// Runs one parsed subcommand, writing its normal output to `out`. A render stops early at its
/// next pass boundary once `stop` is raised.
pub fn run(command: &Command, out: &mut dyn Write, stop: &StopSignal) -> Result<(), CommandError> {
    match command {
        Command::Diff(args) => {
            let report = DiffReport::of_files(&args.a, &args.b)?;
            writeln!(out, "{}", report.to_json_line())
                .map_err(|e| CommandError::Failed(format!("cannot write the report: {e}")))
        }
        Command::Render(args) => crate::render_command::run(args, stop),
        Command::Merge(args) => {
            let (film, record) = merge_files(&args.inputs)?;
            write_film_exr(&args.out, &film, &record).map_err(CommandError::Failed)?;
            if let Some(png) = &args.png {
                film.to_image()
                    .write_png_with_exposure(png, args.exposure)
                    .map_err(|e| CommandError::Failed(e.to_string()))?;
            }
            Ok(())
        }
    }
}
