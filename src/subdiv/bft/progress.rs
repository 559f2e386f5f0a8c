//! How far long work is, said on standard error: Loop's table building
//! ([`super::build`]: faces classified, tables built) and the bounds of adaptive levels
//! (`lod::frame::lod_records`: elements and edges bounded). Quiet for work under a second; on
//! a terminal one line rewritten in place, elsewhere (a log, a pipe) a few plain lines.
#![forbid(unsafe_code)]

/// How far [`super::build`] is: faces classified, then tables built (done, total); also how far the
/// error bounds of adaptive levels are (`lod::frame::lod_records`: elements and edges
/// bounded).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Progress {
    Faces(usize, usize),
    Tables(usize, usize),
    Bounds(usize, usize),
}

impl Progress {
    /// The report that ends the work (every table built, every bound computed).
    pub fn is_last(&self) -> bool {
        matches!(*self, Progress::Tables(d, t) | Progress::Bounds(d, t) if d == t)
    }

    /// Done and total, whatever the phase.
    fn counts(&self) -> (usize, usize) {
        match *self {
            Progress::Faces(d, t) | Progress::Tables(d, t) | Progress::Bounds(d, t) => (d, t),
        }
    }

    /// Whether the phase has done anything yet (a start says nothing a log should keep).
    fn started(&self) -> bool {
        self.counts().0 > 0
    }

    /// Whether this report ends its phase (every face classified, every table built...).
    fn ends_phase(&self) -> bool {
        let (d, t) = self.counts();
        d == t
    }

    /// Whether `other` reports on the same phase.
    fn same_phase(&self, other: &Progress) -> bool {
        std::mem::discriminant(self) == std::mem::discriminant(other)
    }
}

impl std::fmt::Display for Progress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Progress::Faces(d, t) => write!(f, "{d} of {t} M1 faces classified"),
            Progress::Tables(d, t) => write!(f, "{d} of {t} basis function tables built"),
            Progress::Bounds(d, t) => write!(f, "{d} of {t} elements and edges bounded"),
        }
    }
}

/// `report` behind a throttle, for [`super::build`]'s `progress`: quiet in the first second (most builds
/// take less), then at most one report a second, the end of a phase it reported on, and the
/// last one (every table built) when it has reported anything.
pub fn throttled(mut report: impl FnMut(Progress)) -> impl FnMut(Progress) {
    let start = std::time::Instant::now();
    let second = std::time::Duration::from_secs(1);
    let mut last: Option<(std::time::Instant, Progress)> = None;
    move |p| {
        let now = std::time::Instant::now();
        let finished = p.is_last();
        let due = match last {
            None => now - start >= second,
            Some((at, prev)) => {
                let phase_end = p.ends_phase() && prev.same_phase(&p);
                prev != p && (finished || phase_end || now - at >= second)
            }
        };
        if due {
            last = Some((now, p));
            report(p);
        }
    }
}

/// [`throttled`] reports on standard error (`"{what}: 1234 of 24000 M1 faces classified"`):
/// on a terminal one line that each report rewrites, ended when every table is built;
/// elsewhere (a log, a pipe) plain lines, at most one every [`PLAIN_PROGRESS_EVERY`] and the
/// last. Nothing for a build under a second.
pub fn progress_line(what: impl std::fmt::Display) -> impl FnMut(Progress) {
    use std::io::IsTerminal;
    let terminal = std::io::stderr().is_terminal();
    throttled(progress_writer(what, terminal, std::io::stderr))
}

/// [`progress_line`]'s reports, unthrottled, written to `out()`: rewriting one line in place
/// where `terminal`, else plain lines.
fn progress_writer<W: std::io::Write>(
    what: impl std::fmt::Display,
    terminal: bool,
    mut out: impl FnMut() -> W,
) -> impl FnMut(Progress) {
    let mut width = 0usize;
    let mut written: Option<(std::time::Instant, Progress)> = None;
    move |p| {
        let line = format!("{what}: {p}");
        let last = p.is_last();
        if !terminal {
            // A plain line stays in the log: not one of a phase that has not begun ("0 of N
            // faces classified" read as stuck there when the next line was the last), and a
            // phase it was written for ends with its own line.
            let now = std::time::Instant::now();
            let due = written.is_none_or(|(at, _)| now - at >= PLAIN_PROGRESS_EVERY);
            let phase_end = p.ends_phase() && written.is_some_and(|(_, w)| w.same_phase(&p));
            if last || phase_end || (due && p.started()) {
                written = Some((now, p));
                let _ = writeln!(out(), "{line}");
            }
            return;
        }
        let end = if last { "\n" } else { "" };
        let pad = width.saturating_sub(line.len());
        width = line.len();
        let _ = write!(out(), "\r{line}{:pad$}{end}", "");
    }
}

/// How often [`progress_line`] writes a plain line where standard error is not a terminal.
pub const PLAIN_PROGRESS_EVERY: std::time::Duration = std::time::Duration::from_secs(5);

#[cfg(test)]
mod tests {
    use super::*;

    /// A shared byte buffer standing in for standard error.
    #[derive(Clone, Default)]
    struct Sink(std::rc::Rc<std::cell::RefCell<Vec<u8>>>);

    impl std::io::Write for Sink {
        fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
            self.0.borrow_mut().extend_from_slice(b);
            Ok(b.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn progress_rewrites_a_terminal_line_and_writes_plain_lines_elsewhere() {
        let reports = [
            Progress::Faces(0, 100),
            Progress::Faces(10, 100),
            Progress::Faces(100, 100),
            Progress::Tables(1, 3),
            Progress::Tables(3, 3),
        ];
        let text = |terminal| {
            let sink = Sink::default();
            let s = sink.clone();
            let mut report = progress_writer("loop surface", terminal, move || s.clone());
            reports.into_iter().for_each(&mut report);
            String::from_utf8(sink.0.take()).unwrap()
        };
        // A log or a pipe: no carriage return, the first report of work done, the end of its
        // phase, and the last (the others come within PLAIN_PROGRESS_EVERY of the first), each a
        // line.
        let plain = text(false);
        assert!(!plain.contains('\r'), "{plain:?}");
        assert_eq!(
            plain,
            format!(
                "loop surface: {}\nloop surface: {}\nloop surface: {}\n",
                reports[1], reports[2], reports[4]
            )
        );
        // A terminal: every report rewrites the line, the last ends it.
        let terminal = text(true);
        assert_eq!(terminal.matches('\r').count(), 5, "{terminal:?}");
        assert!(
            terminal.ends_with(&format!("{}\n", reports[4])),
            "{terminal:?}"
        );
        assert_eq!(terminal.matches('\n').count(), 1, "{terminal:?}");
    }

    /// Reports wait a second, then come at most once a second (but the end of a phase reported
    /// on), and never twice the same.
    #[test]
    fn progress_is_throttled() {
        let mut heard = Vec::new();
        {
            let mut p = throttled(|p| heard.push(p));
            p(Progress::Faces(0, 10));
            std::thread::sleep(std::time::Duration::from_millis(1050));
            p(Progress::Faces(5, 10));
            p(Progress::Faces(6, 10));
            p(Progress::Faces(10, 10));
            p(Progress::Tables(0, 2));
            p(Progress::Tables(2, 2));
            p(Progress::Tables(2, 2));
        }
        let ends = [Progress::Faces(10, 10), Progress::Tables(2, 2)];
        assert_eq!(heard, [&[Progress::Faces(5, 10)], &ends[..]].concat());
    }
}
