//! `meshrefine` binary: parses the command line, runs the command, turns every failure into one
//! clear sentence and a non-zero exit status.
//!
//! Standard output is written only through [`out!`], which returns write errors: a closed pipe
//! (`meshrefine info x.obj | head -2`) ends the program quietly with status 0, as Unix filters
//! do; any other write error (`>/dev/full`) is an `error:` line and status 1. Warnings and
//! errors go to standard error, where a failed write is ignored (there is nowhere else to say
//! it).
#![forbid(unsafe_code)]

use std::io::Write as _;
use std::process::ExitCode;

/// A failed write to standard output.
#[derive(Debug)]
pub struct StdoutError(pub std::io::Error);

impl std::fmt::Display for StdoutError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "cannot write to standard output: {}", self.0)
    }
}

impl std::error::Error for StdoutError {}

/// `println!` that returns a [`StdoutError`] from the enclosing function instead of panicking,
/// with every control character but the line ends it writes escaped ([`printable_lines`]): a
/// name or path printed cannot drive the terminal. A path that must stay on its line is
/// passed through [`printable`] too.
macro_rules! out {
    ($($arg:tt)*) => {
        writeln!(
            std::io::stdout().lock(),
            "{}",
            $crate::printable_lines(&format!($($arg)*))
        )
        .map_err($crate::StdoutError)?
    };
}

/// A line on standard error (warnings, validation messages); a failed write is ignored.
pub fn note(line: std::fmt::Arguments) {
    let line = line.to_string();
    let _ = writeln!(std::io::stderr().lock(), "{}", printable(&line));
}

pub use meshrefine::paths::printable;

/// [`printable`] line by line: the line ends of a text of several lines (a benchmark's table)
/// kept, every other control character, and every character [`printable`] escapes, escaped.
pub fn printable_lines(text: &str) -> std::borrow::Cow<'_, str> {
    if !(text.chars()).any(|c| (c.is_control() && c != '\n') || meshrefine::paths::unseen(c)) {
        return text.into();
    }
    text.split('\n')
        .map(printable)
        .collect::<Vec<_>>()
        .join("\n")
        .into()
}

mod cli;

fn main() -> ExitCode {
    // meshrefine's warnings and errors read like the command's own ("warning: ..."); other
    // crates' messages and finer levels (asked for with RUST_LOG) keep their level and module.
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn"))
        .format(|buf, record| {
            let own = record.target().starts_with("meshrefine");
            match record.level() {
                log::Level::Warn if own => {
                    writeln!(buf, "warning: {}", printable(&record.args().to_string()))
                }
                log::Level::Error if own => {
                    writeln!(buf, "error: {}", printable(&record.args().to_string()))
                }
                level => writeln!(buf, "[{level} {}] {}", record.target(), record.args()),
            }
        })
        .init();
    let (cli, given) = match cli::parse() {
        Ok(parsed) => parsed,
        // --help, --version (to stdout) or a usage error (to stderr, status 2).
        Err(e) => {
            return match e.print() {
                Err(w) if w.kind() != std::io::ErrorKind::BrokenPipe => {
                    note(format_args!("error: {}", StdoutError(w)));
                    ExitCode::FAILURE
                }
                _ => ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(1)),
            };
        }
    };
    if let Err(e) = cli::check_values(&cli) {
        note(format_args!("error: {e}"));
        return ExitCode::FAILURE;
    }
    for w in cli::warnings(&cli, &given) {
        note(format_args!("warning: {w}"));
    }
    match cli::run(cli, &given) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let closed_pipe = e.chain().any(|c| {
                c.downcast_ref::<StdoutError>()
                    .is_some_and(|s| s.0.kind() == std::io::ErrorKind::BrokenPipe)
            });
            if closed_pipe {
                // The reader has gone (`| head`): nobody wants the rest. Quietly done.
                return ExitCode::SUCCESS;
            }
            note(format_args!("error: {e:#}"));
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::printable_lines;

    /// Line ends are kept; control characters and characters that show nothing are escaped,
    /// also in a text that holds no control character but them.
    #[test]
    fn printed_lines_escape_what_a_terminal_would_hide() {
        assert_eq!(printable_lines("a\nb"), "a\nb");
        assert_eq!(
            printable_lines("a\u{202e}b\nc\u{1b}"),
            "a\\u{202e}b\nc\\u{1b}"
        );
        assert_eq!(printable_lines("\u{feff}x"), "\\u{feff}x");
    }
}
