//! `surfgrav report`: the founding paper's scenes run side by side, written to `REPORT.md`.

use std::path::Path;

use crate::cli::CliError;

/// Runs the paper presets and writes the report folder.
///
/// # Errors
/// A bad `--out`; a failed run.
pub fn report_command(out: Option<&Path>, quiet: bool) -> Result<String, CliError> {
    let _ = (out, quiet);
    Err(CliError::Failed("report: not written yet".into()))
}
