//! The `surfgrav` command-line tool. See `surfgrav --help`.

use std::io::{ErrorKind as IoErrorKind, Write};
use std::process::ExitCode;

use clap::error::ErrorKind;
use clap::Parser;
use surfgrav_scenarios::cli::{run, Cli};

/// Writes `text` and a newline to stdout. A reader that went away (`surfgrav run … | head -1`)
/// ends the program quietly with success, as a closed pipe should; another failure is reported.
fn print_stdout(text: &str) -> ExitCode {
    let mut out = std::io::stdout().lock();
    match writeln!(out, "{text}").and_then(|()| out.flush()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.kind() == IoErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(e) => {
            print_stderr(&format!("error: cannot write to stdout: {e}"));
            ExitCode::from(1)
        }
    }
}

/// Writes one line to stderr, ignoring a closed stderr (nothing else could be told).
fn print_stderr(line: &str) {
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) => {
            // Help and version go to stdout, exit 0 (quietly, also into a closed pipe).
            return print_stdout(e.render().to_string().trim_end());
        }
        Err(e) if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            return ExitCode::from(2);
        }
        Err(e) => {
            // One line: clap's first paragraph (before the usage) says `error: ...`, sometimes
            // over several lines (a list of missing arguments); join them.
            let text = e.render().to_string();
            let message: Vec<&str> = text
                .lines()
                .map(str::trim)
                .take_while(|line| !line.is_empty())
                .collect();
            print_stderr(&format!("{} (see surfgrav --help)", message.join(" ")));
            return ExitCode::from(2);
        }
    };
    match run(cli) {
        Ok(text) => {
            if text.is_empty() {
                ExitCode::SUCCESS
            } else {
                print_stdout(&text)
            }
        }
        Err(e) => {
            print_stderr(&format!("error: {}", e.message()));
            ExitCode::from(e.exit_code())
        }
    }
}
