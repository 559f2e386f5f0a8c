//! A progress line on standard error for long work: nothing for small work
//! ([`ProgressLine::set_size`]) nor in the first second (most work takes less), then, on a
//! terminal, one line rewritten in place a few times a second, and elsewhere (a log, a pipe) a
//! plain line as each quarter of a phase is passed; a last line when the work is done, where
//! anything was shown. `MESHREFINE_PROGRESS_AFTER` replaces that rule by a delay in seconds
//! after which any work reports (`0`: from the start).
#![forbid(unsafe_code)]

use std::io::{IsTerminal as _, Write as _};
use std::time::{Duration, Instant};

/// The environment variable that sets the quiet delay, in seconds (`0`: report from the start).
pub const PROGRESS_AFTER_ENV: &str = "MESHREFINE_PROGRESS_AFTER";

/// Work smaller than this (refined triangles) says nothing unless `MESHREFINE_PROGRESS_AFTER`
/// is set: on the slowest device supported (lavapipe) it takes a few seconds at most, and small
/// exports keep their standard error as it was.
pub const PROGRESS_MIN_TRIANGLES: u64 = 1 << 18;

pub struct ProgressLine {
    start: Instant,
    /// Silence before the first report (None: no report at all).
    quiet: Option<Duration>,
    /// Set by `MESHREFINE_PROGRESS_AFTER`: work of any size reports.
    forced: bool,
    terminal: bool,
    /// When the line was last written (terminal).
    last: Option<Instant>,
    /// Width of the line last written in place, to blank its tail.
    width: usize,
    /// The last (phase, quarter) written as a plain line.
    step: Option<(u32, u32)>,
    shown: bool,
}

impl ProgressLine {
    /// Fails on a `MESHREFINE_PROGRESS_AFTER` that is not a number of seconds.
    pub fn new() -> Result<Self, String> {
        let (quiet, forced) = match std::env::var(PROGRESS_AFTER_ENV) {
            Err(_) => (Duration::from_secs(1), false),
            Ok(s) => (
                s.trim()
                    .parse::<f64>()
                    .ok()
                    .and_then(|s| Duration::try_from_secs_f64(s).ok())
                    .ok_or_else(|| {
                        format!("{PROGRESS_AFTER_ENV} must be a number of seconds, not '{s}'")
                    })?,
                true,
            ),
        };
        Ok(Self {
            start: Instant::now(),
            quiet: Some(quiet),
            forced,
            terminal: std::io::stderr().is_terminal(),
            last: None,
            width: 0,
            step: None,
            shown: false,
        })
    }

    /// The work makes about `triangles` refined triangles: below [`PROGRESS_MIN_TRIANGLES`] it
    /// says nothing (unless forced).
    pub fn set_size(&mut self, triangles: u64) {
        if !self.forced && triangles < PROGRESS_MIN_TRIANGLES {
            self.quiet = None;
        }
    }

    /// Report `text`, `fraction` (0 to 1) of the way through `phase` (phases count up).
    pub fn report(&mut self, phase: u32, fraction: f64, text: &str) {
        let now = Instant::now();
        if self.quiet.is_none_or(|q| now - self.start < q) {
            return;
        }
        if self.terminal {
            if self
                .last
                .is_some_and(|at| now - at < Duration::from_millis(250))
            {
                return;
            }
            self.last = Some(now);
            self.in_place(text, "");
        } else {
            let step = (phase, (fraction.clamp(0.0, 1.0) * 4.0) as u32);
            if self.step.is_some_and(|s| s >= step) {
                return;
            }
            self.step = Some(step);
            let _ = writeln!(std::io::stderr().lock(), "{text}");
        }
        self.shown = true;
    }

    /// End with `text`, where anything was reported.
    pub fn finish(&mut self, text: &str) {
        if !self.shown {
            return;
        }
        if self.terminal {
            self.in_place(text, "\n");
        } else {
            let _ = writeln!(std::io::stderr().lock(), "{text}");
        }
        self.shown = false;
    }

    fn in_place(&mut self, text: &str, end: &str) {
        let pad = self.width.saturating_sub(text.len());
        self.width = text.len();
        let _ = write!(std::io::stderr().lock(), "\r{text}{:pad$}{end}", "");
    }
}

impl Drop for ProgressLine {
    /// A line left in place (the work failed) is ended, so what follows starts a line of its own.
    fn drop(&mut self) {
        if self.shown && self.terminal {
            let _ = writeln!(std::io::stderr().lock());
        }
    }
}

/// `n` and `what`, plural but for one (`1 pass`, `3 passes`).
pub fn plural(n: u64, what: &str) -> String {
    match (n, what.strip_suffix("ss")) {
        (1, _) => format!("1 {what}"),
        (_, Some(_)) => format!("{n} {what}es"),
        _ => format!("{n} {what}s"),
    }
}

/// `n` as millions with one decimal (`1.2 M`) from a million on, plain below.
pub fn count(n: u64) -> String {
    if n >= 1_000_000 {
        format!("{:.1} M", n as f64 / 1e6)
    } else {
        n.to_string()
    }
}

/// `done of total`, both as [`count`] writes `total` (`0.3 of 4.5 M`, `20 of 20`).
pub fn count_of(done: u64, total: u64) -> String {
    if total >= 1_000_000 {
        format!("{:.1} of {:.1} M", done as f64 / 1e6, total as f64 / 1e6)
    } else {
        format!("{done} of {total}")
    }
}
