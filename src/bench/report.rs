//! The benchmark's table: a [`Report`] of measured rows and the one list of its columns,
//! [`COLUMNS`], from which every form of the table is derived.
//!
//! Each column is declared once: its key (the CSV header and the JSON key), its markdown header
//! and alignment, its short header in the terminal summary (or none), and a function giving the
//! row's value as a [`Cell`] that knows how to write itself for each reader (CSV and JSON carry
//! numbers at 4 decimals and leave missing values empty or `null`; markdown and the summary show
//! what a reader scans, with `–` for a missing value). So the CSV, the JSON rows and the
//! markdown table cannot disagree about which columns there are or their order: CSV and JSON
//! have every column; markdown states the device above the table and shows each spread (min,
//! max) in its median's cell; the summary keeps the few columns that matter and fits
//! [`SUMMARY_WIDTH`] characters, the full table going to files.
//!
//! The CSV's column names and order are a contract: scripts/plot.py and
//! scripts/table1-runs.py read them by name.
#![forbid(unsafe_code)]

pub use super::columns::{Column, COLUMNS};
use super::{Row, Stat};
use crate::render::View;
use std::fmt::Write as _;
use std::path::Path;

/// What one benchmark run measured: the device, the frame size and count, and one row per
/// variant.
pub struct Report {
    pub device: String,
    pub frames: u32,
    pub width: u32,
    pub height: u32,
    /// What the frames showed (the `plain` view: unlit, no fragment work).
    pub view: View,
    pub rows: Vec<Row>,
    /// The cameras the rows were drawn from, in the coordinates [`Report::camera_space`]
    /// names (the markdown's `Cameras:` line).
    pub cameras: Vec<super::ViewUsed>,
    /// In which coordinates [`Report::cameras`] are: those the meshes were drawn in unless the
    /// caller maps them back (`meshrefine bench`: the mesh's own, as `--eye` takes them).
    pub camera_space: String,
}

/// How a column's cells line up in markdown and in the summary.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Align {
    Left,
    Right,
}

/// One value of a row, written as each form of the table wants it.
#[derive(Clone, Debug, PartialEq)]
pub enum Cell {
    /// A name (mesh, surface, variant): CSV quotes it only where it must.
    Name(String),
    /// Free text (device, note): CSV always quotes it.
    Prose(String),
    Count(Option<u64>),
    /// A real number; markdown and the summary show this many decimals.
    Real(Option<f64>, usize),
    /// A timing: CSV, JSON and the summary give its median, markdown `median (min–max)`.
    Spread(Option<Stat>),
    /// A value given on the command line (a pixel error): written everywhere as
    /// [`crate::lod::px`] writes it, every digit of it (however small), a number in CSV and JSON.
    Given(Option<f32>),
    /// Yes or no: `true`/`false` (a JSON boolean), empty where it does not apply (JSON `null`).
    Flag(Option<bool>),
}

impl Cell {
    fn csv(&self) -> String {
        match self {
            Cell::Name(s) if s.contains([',', '"', '\n', '\r']) => quoted(s),
            Cell::Name(s) => s.clone(),
            Cell::Prose(s) => quoted(s),
            Cell::Count(v) => v.map(|v| v.to_string()).unwrap_or_default(),
            Cell::Real(v, _) => v.map(|v| format!("{v:.4}")).unwrap_or_default(),
            Cell::Spread(s) => s.map(|s| format!("{:.4}", s.median)).unwrap_or_default(),
            Cell::Given(v) => v.map(crate::lod::px).unwrap_or_default(),
            Cell::Flag(v) => v.map(|v| v.to_string()).unwrap_or_default(),
        }
    }

    fn json(&self) -> String {
        let real = |v: Option<f64>| match v {
            Some(v) if v.is_finite() => format!("{v:.4}"),
            _ => "null".into(),
        };
        match self {
            Cell::Name(s) | Cell::Prose(s) => json_string(s),
            Cell::Count(v) => v.map(|v| v.to_string()).unwrap_or_else(|| "null".into()),
            Cell::Real(v, _) => real(*v),
            Cell::Spread(s) => real(s.map(|s| s.median)),
            Cell::Given(Some(v)) if v.is_finite() => crate::lod::px(*v),
            Cell::Given(_) => "null".into(),
            Cell::Flag(v) => v.map_or("null".into(), |v| v.to_string()),
        }
    }

    fn markdown(&self) -> String {
        match self {
            Cell::Spread(Some(s)) => format!("{:.2} ({:.2}–{:.2})", s.median, s.min, s.max),
            Cell::Name(s) | Cell::Prose(s) => s.replace('|', "\\|"),
            c => c.short(),
        }
    }

    /// The summary's cell: the median alone for a timing.
    fn short(&self) -> String {
        match self {
            Cell::Name(s) | Cell::Prose(s) => s.clone(),
            Cell::Flag(v) => v.map(|v| v.to_string()).unwrap_or_default(),
            Cell::Count(Some(v)) => v.to_string(),
            Cell::Real(Some(v), digits) => format!("{v:.digits$}"),
            Cell::Spread(Some(s)) => format!("{:.2}", s.median),
            Cell::Given(Some(v)) => crate::lod::px(*v),
            Cell::Count(None) | Cell::Real(None, _) | Cell::Spread(None) | Cell::Given(None) => {
                "–".into()
            }
        }
    }
}

/// The fields of one line of [`Report::csv`] (RFC 4180 quoting undone), for scripts and tests
/// that read the table back.
pub fn csv_fields(line: &str) -> Vec<String> {
    let (mut fields, mut field, mut quoted) = (Vec::new(), String::new(), false);
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                chars.next();
                field.push('"');
            }
            ('"', _) => quoted = !quoted,
            (',', false) => fields.push(std::mem::take(&mut field)),
            (c, _) => field.push(c),
        }
    }
    fields.push(field);
    fields
}

fn quoted(s: &str) -> String {
    format!("\"{}\"", s.replace('"', "\"\""))
}

fn json_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

use Align::{Left, Right};

/// The widest line [`Report::summary`] prints.
pub const SUMMARY_WIDTH: usize = 120;

impl Report {
    /// What the frames showed, for the paragraph above the table: nothing for the lit surface.
    fn view_note(&self) -> &'static str {
        match self.view {
            View::Shaded => "",
            View::Normals => " (the normals view)",
            View::Levels => " (the levels view)",
            View::Plain => {
                " (the `plain` view: one colour, unlit, so the fragment stage does no work and the times are the refined triangles' alone)"
            }
        }
    }

    /// The `Cameras:` line: each mesh's surface x displacement and the eye, point looked at and
    /// vertical field of view it was drawn from (several: a path, each frame's).
    fn cameras_said(&self) -> String {
        let p = |v: glam::Vec3| v.to_array().map(crate::lod::px).join(",");
        let said: Vec<String> = (self.cameras.iter())
            .map(|v| {
                let shots: Vec<String> = (v.shots.iter())
                    .map(|c| {
                        format!(
                            "`--eye {} --look-at {} --fov {}`",
                            p(c.eye),
                            p(c.target),
                            crate::lod::px(c.fov_y_degrees)
                        )
                    })
                    .collect();
                format!(
                    "{} as {} + {}: {}",
                    v.mesh,
                    v.surface.name(),
                    v.displace.name(),
                    shots.join(", then ")
                )
            })
            .collect();
        format!("Cameras ({}): {}.", self.camera_space, said.join("; "))
    }

    /// What the report's ratios compare, as the rows hold them: uniform rows against `static`
    /// and `flat` (columns), adaptive rows against the uniform rows of the same run (their
    /// notes; the ratio columns stay empty there). `short` for the terminal's summary.
    fn ratios_said(&self, short: bool) -> String {
        let adaptive = self.rows.iter().any(|r| r.adaptive.is_some());
        let columns = self
            .rows
            .iter()
            .any(|r| r.gpu_ratio.is_some() || r.throughput_vs_flat.is_some());
        let mut said = Vec::new();
        if columns {
            said.push(if short {
                "Ratios against `static` of the same surface and displacement, throughput against \
                 `flat` with the same variant and displacement, both from the same run."
            } else {
                "Ratios are against `static` at the same mesh, level, surface and displacement, \
                 and throughput (refined triangles per GPU ms) against `flat` with the same \
                 variant and displacement, measured in the same run."
            });
        }
        if adaptive {
            said.push(
                "Each adaptive row (`levels from` `view`: its levels chosen for the camera, its \
                 `level` the largest any element may get) is compared in its note with the \
                 uniform rows of the same run below it (`levels from`: the levels asked for, the \
                 smallest uniform level meeting the same bound, `bound`, and the power of two at \
                 or above it, `pow2`).",
            );
        }
        said.iter().map(|x| format!("{x} ")).collect()
    }

    /// The full table in markdown, below a paragraph saying what was measured and how.
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "Device: {}. {}x{} offscreen{}, median (min–max) of {} timed frames (more where a note says so) after one warm-up frame, taken round the variants (of every surface together; with several surfaces each `static` alone first) in turn. {}Elements: the coarse triangles, or M1's faces for `loop`.\n",
            self.device,
            self.width,
            self.height,
            self.view_note(),
            self.frames,
            self.ratios_said(false)
        );
        if !self.cameras.is_empty() {
            let _ = writeln!(s, "{}\n", crate::paths::printable(&self.cameras_said()));
        }
        let columns: Vec<&Column> = COLUMNS.iter().filter(|c| c.markdown.is_some()).collect();
        let line = |cells: Vec<String>| format!("| {} |", cells.join(" | "));
        let _ = writeln!(
            s,
            "{}",
            line(columns.iter().map(|c| c.markdown.unwrap().into()).collect())
        );
        let rule = columns.iter().map(|c| match c.align {
            Left => "---|",
            Right => "---:|",
        });
        let _ = writeln!(s, "|{}", rule.collect::<String>());
        for r in &self.rows {
            // A mesh named with control characters writes nothing a terminal acts on.
            let cells = (columns.iter())
                .map(|c| crate::paths::printable(&c.cell(self, r).markdown()).into_owned());
            let _ = writeln!(s, "{}", line(cells.collect()));
        }
        s
    }

    /// Write `prefix.md` (headed by the command that made it), `prefix.csv` and `prefix.json`.
    /// The folder must exist: outputs never create folders (the command line checks the prefix up front, `meshrefine::paths`).
    pub fn write_files(&self, prefix: &Path, command: &str) -> std::io::Result<()> {
        let files = [
            (
                "md",
                format!(
                    "Command: `{}`\n\n{}",
                    crate::paths::printable(command),
                    self.markdown()
                ),
            ),
            ("csv", self.csv()),
            ("json", self.json()),
        ];
        let paths = files.each_ref().map(|(ext, _)| with_extension(prefix, ext));
        let outputs: Vec<(&Path, &[u8])> = (paths.iter())
            .zip(&files)
            .map(|(path, (_, text))| (path.as_path(), text.as_bytes()))
            .collect();
        // All three or none: a failure leaves the files of an earlier run as they were.
        crate::paths::write_outputs(&outputs)
    }

    /// Every column, one row per line, headed by the column keys.
    pub fn csv(&self) -> String {
        let keys: Vec<&str> = COLUMNS.iter().map(|c| c.key).collect();
        let mut s = keys.join(",") + "\n";
        for r in &self.rows {
            let cells: Vec<String> = COLUMNS.iter().map(|c| c.cell(self, r).csv()).collect();
            let _ = writeln!(s, "{}", cells.join(","));
        }
        s
    }

    /// The run's device, frame count and size, and every column of every row, one row per line.
    pub fn json(&self) -> String {
        let rows: Vec<String> = self
            .rows
            .iter()
            .map(|r| {
                let fields: Vec<String> = COLUMNS
                    .iter()
                    .map(|c| format!("\"{}\":{}", c.key, c.cell(self, r).json()))
                    .collect();
                format!("{{{}}}", fields.join(","))
            })
            .collect();
        format!(
            "{{\"device\":{},\"frames\":{},\"width\":{},\"height\":{},\"view\":{},\"rows\":[\n{}\n]}}\n",
            json_string(&self.device),
            self.frames,
            self.width,
            self.height,
            json_string(self.view.name()),
            rows.join(",\n")
        )
    }

    /// A short table for the terminal, every line at most [`SUMMARY_WIDTH`] characters (save a
    /// path longer than that): the
    /// columns with a summary header, those the same on every row said once above it, notes
    /// below it, and where the full table is: `full_table` is the prefix it was written to
    /// (`None`: say that `--out PREFIX` writes it).
    pub fn summary(&self, full_table: Option<&Path>) -> String {
        let mut s = self.summary_table();
        const WHAT: &str = "The full table (every column: spreads, wall time, stored vertices and \
                            indices, VS invocations)";
        match full_table {
            // The path on a line of its own, whole, however long.
            Some(prefix) => {
                wrap(
                    &mut s,
                    &format!("{WHAT}, with its .csv and .json beside it:"),
                    "",
                );
                let path = with_extension(prefix, "md").display().to_string();
                let _ = writeln!(s, "{}", crate::paths::printable(&path));
            }
            None => wrap(
                &mut s,
                &format!(
                    "{WHAT}: `--out PREFIX` writes it to PREFIX.md, PREFIX.csv and PREFIX.json."
                ),
                "",
            ),
        }
        s
    }

    /// [`Report::summary`] without the line saying where the full table is.
    pub fn summary_table(&self) -> String {
        let mut s = String::new();
        wrap(
            &mut s,
            format!(
                "Device: {}. {}x{}, median GPU time of {} timed frames per variant (more where a \
                 note says so). {}",
                self.device,
                self.width,
                self.height,
                self.frames,
                self.ratios_said(true)
            )
            .trim_end(),
            "",
        );
        let mut columns: Vec<(&Column, Vec<String>)> = COLUMNS
            .iter()
            .filter(|c| c.summary.is_some())
            .map(|c| {
                (
                    c,
                    // Escaped here (a mesh name may hold a line end), so that the widths
                    // count what is printed.
                    (self.rows.iter())
                        .map(|r| crate::paths::printable(&c.cell(self, r).short()).into_owned())
                        .collect(),
                )
            })
            .collect();
        // Columns no row has a value in (an adaptive benchmark's, on other rows) are left out.
        columns.retain(|(_, cells)| cells.iter().any(|c| !c.is_empty() && c != "–"));
        // Columns with one value on every row are said once, above the table (a single row's
        // every column: no table is left then).
        if !self.rows.is_empty() {
            let same: Vec<String> = columns
                .iter()
                .filter(|(_, cells)| cells.iter().all(|c| *c == cells[0]))
                .map(|(c, cells)| format!("{} {}", c.summary.unwrap(), cells[0]))
                .collect();
            if !same.is_empty() {
                let rows = if self.rows.len() == 1 {
                    "The row"
                } else {
                    "Every row"
                };
                let text = format!("{rows}: {}.", same.join(", "));
                wrap_on(&mut s, &text, "", ", ");
            }
            columns.retain(|(_, cells)| cells.iter().any(|c| *c != cells[0]));
        }
        s.push('\n');
        let widths = fit_widths(&columns);
        let table = if columns.is_empty() {
            0
        } else {
            self.rows.len()
        };
        let line = |cells: Vec<String>| {
            let padded: Vec<String> = cells
                .iter()
                .zip(&columns)
                .zip(&widths)
                .map(|((cell, (c, _)), &w)| pad(&shorten(cell, w), w, c.align))
                .collect();
            padded.join("  ").trim_end().to_owned()
        };
        if table > 0 {
            let headers = columns.iter().map(|(c, _)| c.summary.unwrap().to_owned());
            let _ = writeln!(s, "{}", line(headers.collect()));
            let rule: Vec<String> = widths.iter().map(|&w| "-".repeat(w)).collect();
            let _ = writeln!(s, "{}", rule.join("  "));
        }
        for i in 0..table {
            let _ = writeln!(
                s,
                "{}",
                line(columns.iter().map(|(_, c)| c[i].clone()).collect())
            );
        }
        let noted: Vec<&Row> = self.rows.iter().filter(|r| !r.note.is_empty()).collect();
        let noted_any = !noted.is_empty();
        if noted_any {
            if table > 0 {
                s.push('\n');
            }
            for r in noted {
                let what = format!(
                    "- {} level {} {} + {} {}: {}",
                    r.mesh,
                    r.level,
                    r.surface.name(),
                    r.displace.name(),
                    r.variant,
                    r.note
                );
                wrap(&mut s, &crate::paths::printable(&what), "  ");
            }
        }
        if table > 0 || noted_any {
            s.push('\n');
        }
        s
    }
}

/// `prefix` with `.ext` added (the prefix may hold dots of its own).
fn with_extension(prefix: &Path, ext: &str) -> std::path::PathBuf {
    let mut p = prefix.as_os_str().to_owned();
    p.push(".");
    p.push(ext);
    p.into()
}

fn width(s: &str) -> usize {
    s.chars().count()
}

/// Each column's width in the summary: as wide as its widest cell or header, with the names
/// that may shrink shortened, then the rightmost columns dropped, until a line fits.
fn fit_widths(columns: &[(&Column, Vec<String>)]) -> Vec<usize> {
    let mut widths: Vec<usize> = columns
        .iter()
        .map(|(c, cells)| {
            cells
                .iter()
                .map(|s| width(s))
                .chain([width(c.summary.unwrap())])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let total = |w: &[usize]| w.iter().sum::<usize>() + 2 * w.len().saturating_sub(1);
    for (i, (c, _)) in columns.iter().enumerate() {
        let over = total(&widths).saturating_sub(SUMMARY_WIDTH);
        if c.shrinks && over > 0 {
            let least = width(c.summary.unwrap()).max(4);
            widths[i] = widths[i].saturating_sub(over).max(least);
        }
    }
    // Past any real table: the rightmost columns are left to the full table.
    while total(&widths) > SUMMARY_WIDTH && widths.len() > 1 {
        widths.pop();
    }
    widths
}

fn shorten(s: &str, w: usize) -> String {
    if width(s) <= w {
        s.to_owned()
    } else {
        let mut t: String = s.chars().take(w.saturating_sub(1)).collect();
        t.push('…');
        t
    }
}

fn pad(s: &str, w: usize, align: Align) -> String {
    let fill = " ".repeat(w.saturating_sub(width(s)));
    match align {
        Left => format!("{s}{fill}"),
        Right => format!("{fill}{s}"),
    }
}

/// Appends `text` as lines of at most [`SUMMARY_WIDTH`] characters, broken at spaces; lines
/// after the first start with `indent`.
fn wrap(out: &mut String, text: &str, indent: &str) {
    wrap_on(out, text, indent, " ");
}

/// [`wrap`], breaking lines only between the pieces of `text` that `sep` separates (`", "`: a
/// list whose items stay whole), each line but the last ending in `sep` without its spaces.
fn wrap_on(out: &mut String, text: &str, indent: &str, sep: &str) {
    let mut line = String::new();
    let pieces: Vec<&str> = text.split(sep).collect();
    let last = pieces.len() - 1;
    for (i, piece) in pieces.into_iter().enumerate() {
        let word = if i < last {
            format!("{piece}{}", sep.trim_end())
        } else {
            piece.to_owned()
        };
        let word = word.as_str();
        let fresh = line.is_empty() || line == indent;
        // A word longer than a whole line is shortened where it stands.
        let fits_alone = width(indent) + width(word) <= SUMMARY_WIDTH;
        if !fresh && fits_alone && width(&line) + 1 + width(word) > SUMMARY_WIDTH {
            let _ = writeln!(out, "{line}");
            line = indent.to_owned();
        } else if !fresh {
            line.push(' ');
        }
        let room = SUMMARY_WIDTH - width(&line);
        line.push_str(&shorten(word, room));
    }
    let _ = writeln!(out, "{line}");
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::{Displace, Surface};

    fn row(mesh: &str, level: u32, variant: &str, timed: bool) -> Row {
        let stat = |m: f64| Stat {
            median: m,
            min: m * 0.9,
            max: m * 1.3,
        };
        Row {
            mesh: mesh.into(),
            coarse_triangles: 372,
            elements: 1488,
            level,
            surface: Surface::Loop,
            displace: Displace::Sine,
            variant: variant.into(),
            refined_triangles: 1_523_712,
            gpu_ms: timed.then(|| stat(12.345_678)),
            wall_ms: timed.then(|| stat(13.5)),
            stored_vertices: 6,
            stored_indices: 12,
            geometry_bytes: 41_784,
            vertex_invocations: timed.then_some(2232),
            gpu_ratio: timed.then_some(0.987_654_3),
            wall_ratio: timed.then_some(1.012_345),
            throughput_vs_flat: timed.then_some(1.5),
            pre_pass_ms: Some(0.123_456),
            table_bytes: None,
            adaptive: None,
            note: if timed {
                String::new()
            } else {
                "not drawn: level 128 is over the device's limit, \"64\"".into()
            },
        }
    }

    fn report(rows: Vec<Row>) -> Report {
        Report {
            device: "llvmpipe (LLVM 15.0.6, 256 bits), \"quoted\"".into(),
            frames: 5,
            width: 1280,
            height: 720,
            view: View::Shaded,
            rows,
            cameras: Vec::new(),
            camera_space: super::super::DRAWN_SPACE.into(),
        }
    }

    /// The keys and values of one flat JSON object (strings unescaped, others as written).
    fn json_fields(object: &str) -> Vec<(String, String)> {
        let body = object.trim().trim_start_matches('{').trim_end_matches('}');
        let (mut out, mut token, mut key) = (Vec::new(), String::new(), None::<String>);
        let mut chars = body.chars();
        let mut in_string = false;
        while let Some(c) = chars.next() {
            match (c, in_string) {
                ('\\', true) => match chars.next() {
                    Some('n') => token.push('\n'),
                    Some(e) => token.push(e),
                    None => {}
                },
                ('"', _) => in_string = !in_string,
                (':', false) if key.is_none() => key = Some(std::mem::take(&mut token)),
                (',', false) => out.push((key.take().unwrap(), std::mem::take(&mut token))),
                (c, _) => token.push(c),
            }
        }
        out.push((key.take().unwrap(), token));
        out
    }

    /// The JSON's rows, one a line, without the separating commas.
    fn json_rows(json: &str) -> Vec<&str> {
        let rows = json
            .lines()
            .filter(|l| l.starts_with('{') && !l.ends_with('['));
        rows.map(|l| l.trim_end_matches(',')).collect()
    }

    /// A CSV or JSON number: `None` for an empty field or `null`.
    fn number(s: &str) -> Option<f64> {
        (!s.is_empty() && s != "null").then(|| s.parse().expect(s))
    }

    /// The value a column's cell stands for, as a number (names: none).
    fn value(cell: &Cell) -> Option<f64> {
        match *cell {
            Cell::Count(v) => v.map(|v| v as f64),
            Cell::Real(v, _) => v,
            Cell::Spread(s) => s.map(|s| s.median),
            Cell::Given(v) => v.map(f64::from),
            Cell::Name(_) | Cell::Prose(_) | Cell::Flag(_) => None,
        }
    }

    /// A yes-or-no column is a JSON boolean (`null` where it does not apply), `true`/`false`
    /// or empty elsewhere.
    #[test]
    fn flags_are_json_booleans() {
        for (v, json, text) in [
            (Some(true), "true", "true"),
            (Some(false), "false", "false"),
            (None, "null", ""),
        ] {
            let c = Cell::Flag(v);
            assert_eq!((c.json().as_str(), c.csv().as_str()), (json, text));
            assert_eq!((c.markdown().as_str(), c.short().as_str()), (text, text));
        }
    }

    #[test]
    fn csv_and_markdown_headers_are_what_scripts_and_readers_know() {
        let r = report(vec![row("spot", 2, "tess", true)]);
        assert_eq!(
            r.csv().lines().next().unwrap(),
            "device,mesh,coarse_triangles,elements,level,surface,displace,variant,refined_triangles,gpu_ms_median,gpu_ms_min,gpu_ms_max,wall_ms_median,wall_ms_min,wall_ms_max,gpu_ns_per_refined_triangle,gpu_ratio_vs_static,wall_ratio_vs_static,throughput_vs_flat,pre_pass_ms,table_bytes,stored_vertices,stored_indices,geometry_bytes,vertex_invocations,scene,adaptive,pixel_error,level_from,level_pass_ms,level_pass_on,culled_elements,cpu_ms,upload_bytes,level_histogram,note"
        );
        let md = r.markdown();
        let mut lines = md.lines().skip(2);
        assert_eq!(
            lines.next().unwrap(),
            "| mesh | coarse tris | elements | level | surface | displace | variant | refined tris | GPU ms | wall ms | GPU ns / refined tri | GPU / static | wall / static | throughput / flat | M0→M1 ms | table bytes | stored vertices | stored indices | geometry bytes | VS invocations | scene | adaptive | pixel error | levels from | level pass ms | level pass on | culled elements | CPU ms | upload bytes | levels (L:elements) | note |"
        );
        assert_eq!(
            lines.next().unwrap(),
            "|---|---:|---:|---:|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---:|---|---:|---|---:|---:|---:|---|---|"
        );
    }

    #[test]
    fn every_form_has_the_same_columns_in_the_same_order() {
        let r = report(vec![
            row("grid, \"big\"", 2, "pattern/push", true),
            row("spot", 128, "tess", false),
        ]);
        let keys: Vec<&str> = COLUMNS.iter().map(|c| c.key).collect();
        let csv = r.csv();
        let csv_lines: Vec<&str> = csv.lines().collect();
        assert_eq!(csv_fields(csv_lines[0]), keys);
        assert_eq!(csv_lines.len(), 1 + r.rows.len());
        for line in &csv_lines[1..] {
            assert_eq!(csv_fields(line).len(), keys.len(), "{line}");
        }
        let json = r.json();
        let json_rows = json_rows(&json);
        assert_eq!(json_rows.len(), r.rows.len(), "{json}");
        for object in json_rows {
            let fields = json_fields(object.trim_end_matches(','));
            let json_keys: Vec<&str> = fields.iter().map(|(k, _)| k.as_str()).collect();
            assert_eq!(json_keys, keys);
        }
        // Markdown: the same list, less the device (above the table) and the spreads (in their
        // medians' cells).
        let headers: Vec<&str> = COLUMNS.iter().filter_map(|c| c.markdown).collect();
        let folded: Vec<&str> = COLUMNS
            .iter()
            .filter(|c| c.markdown.is_none())
            .map(|c| c.key)
            .collect();
        assert_eq!(
            folded,
            [
                "device",
                "gpu_ms_min",
                "gpu_ms_max",
                "wall_ms_min",
                "wall_ms_max"
            ]
        );
        let md = r.markdown();
        let table: Vec<&str> = md.lines().filter(|l| l.starts_with('|')).collect();
        let cells = |l: &str| -> Vec<String> {
            let inner = l.strip_prefix("| ").unwrap().strip_suffix(" |").unwrap();
            inner.split(" | ").map(str::to_owned).collect()
        };
        assert_eq!(cells(table[0]), headers);
        assert_eq!(table.len(), 2 + r.rows.len());
        for line in &table[2..] {
            assert_eq!(cells(line).len(), headers.len(), "{line}");
        }
        assert!(table[2].contains("| 12.35 (11.11–16.05) |"), "{}", table[2]);
    }

    #[test]
    fn csv_and_json_carry_each_rows_numbers_and_names() {
        let r = report(vec![
            row("grid, \"big\"", 2, "pattern/push", true),
            row("spot", 128, "tess", false),
        ]);
        let csv = r.csv();
        let json = r.json();
        let json_rows = json_rows(&json);
        for ((row, line), object) in r.rows.iter().zip(csv.lines().skip(1)).zip(json_rows) {
            let from_csv = csv_fields(line);
            let from_json = json_fields(object.trim_end_matches(','));
            for ((c, field), (_, json_value)) in COLUMNS.iter().zip(&from_csv).zip(&from_json) {
                let cell = c.cell(&r, row);
                match &cell {
                    Cell::Name(s) | Cell::Prose(s) => {
                        assert_eq!(field, s, "{}", c.key);
                        assert_eq!(json_value, s, "{}", c.key);
                    }
                    Cell::Flag(v) => {
                        let text = v.map(|v| v.to_string());
                        assert_eq!(field, &text.clone().unwrap_or_default(), "{}", c.key);
                        assert_eq!(json_value, &text.unwrap_or("null".into()), "{}", c.key);
                    }
                    // Written at 4 decimals: within half a unit of the last.
                    _ => {
                        for written in [field, json_value] {
                            match (number(written), value(&cell)) {
                                (Some(a), Some(b)) => {
                                    assert!((a - b).abs() <= 0.5e-4, "{}: {a} vs {b}", c.key)
                                }
                                (a, b) => assert_eq!(a, b, "{}", c.key),
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn the_summary_fits_the_terminal_and_says_where_the_full_table_is() {
        let long = "a_mesh_with_a_very_long_name_".repeat(6);
        let mut rows = Vec::new();
        for (mesh, level) in [(long.as_str(), 2), ("spot", 1024)] {
            for variant in ["static", "pattern/instanced", "tess"] {
                rows.push(row(mesh, level, variant, variant != "tess"));
            }
        }
        rows[1].surface = Surface::Flat;
        rows[2].displace = Displace::Heightmap;
        let mut r = report(rows);
        r.device = "a device whose name goes on and on ".repeat(8);
        for s in [
            r.summary(None),
            r.summary(Some(Path::new("/tmp/out/run.1"))),
        ] {
            for line in s.lines() {
                assert!(
                    width(line) <= SUMMARY_WIDTH,
                    "{} chars: {line}",
                    width(line)
                );
            }
            // Every row, with its variant and a shortened mesh name.
            assert!(
                s.lines()
                    .any(|l| l.starts_with("a_mesh_with") && l.contains('…')),
                "{s}"
            );
            // Two rows each, and a line for each of tess's notes.
            for (variant, lines) in [("static", 2), ("pattern/instanced", 2), ("tess", 4)] {
                let tokens = [variant.to_owned(), format!("{variant}:")];
                let n = s
                    .lines()
                    .filter(|l| !l.starts_with("mesh"))
                    .filter(|l| l.split_whitespace().any(|t| tokens.iter().any(|v| v == t)))
                    .count();
                assert_eq!(n, lines, "{variant}:\n{s}");
            }
            assert!(s.contains("not drawn: level 128"), "{s}");
        }
        let without = r.summary(None).replace('\n', " ");
        assert!(without.contains("`--out PREFIX` writes it"), "{without}");
        assert!(r
            .summary(Some(Path::new("/tmp/out/run.1")))
            .replace('\n', " ")
            .ends_with(".json beside it: /tmp/out/run.1.md "));
    }

    #[test]
    fn the_summary_says_once_what_every_row_shares() {
        let r = report(vec![
            row("spot", 2, "static", true),
            row("spot", 2, "tess", false),
        ]);
        let s = r.summary(None);
        assert!(
            s.contains(
                "\nEvery row: mesh spot, level 2, surface loop, displace sine, refined tris \
                 1523712, stored bytes 41784.\n"
            ),
            "{s}"
        );
        let header = s.lines().find(|l| l.starts_with("variant  ")).expect(&s);
        let headers: Vec<&str> = header.split("  ").filter(|h| !h.is_empty()).collect();
        assert_eq!(
            headers,
            ["variant", "GPU ms", "ns/tri", "vs static", "vs flat"],
            "{s}"
        );
        let static_row = s.lines().find(|l| l.starts_with("static ")).expect(&s);
        let cells: Vec<&str> = static_row.split_whitespace().collect();
        assert_eq!(cells, ["static", "12.35", "8.10", "0.99", "1.50"], "{s}");
    }

    /// A mesh name's control characters are escaped in the summary (one row or several, the
    /// table and the notes under it), as on every other line of standard output: a line end in
    /// a file's name starts no line.
    #[test]
    fn the_summary_escapes_a_mesh_name() {
        for n in [1, 2] {
            let mut rows: Vec<Row> = (0..n)
                .map(|_| row("nl\nname\u{1b}[31m", 2, "static", true))
                .collect();
            // A noted row: its note is said under the table with the mesh's name.
            rows[0].note = "not drawn: level 128".into();
            let s = report(rows).summary(None);
            assert!(s.contains("- nl\\nname\\u{1b}[31m level 2"), "{s}");
            assert!(s.contains("mesh nl\\nname\\u{1b}[31m,"), "{s}");
            assert!(!s.contains('\u{1b}') && !s.contains("\nname"), "{s}");
        }
    }

    /// A single row is said whole above where the table would be, every column with its value
    /// (its mesh's name in full), and no table follows.
    #[test]
    fn a_single_row_is_said_in_one_paragraph() {
        let r = report(vec![row(
            "a_mesh_with_a_long_name_indeed",
            2,
            "static",
            true,
        )]);
        let s = r.summary(None);
        let said = s.replace('\n', " ");
        assert!(
            said.contains("The row: mesh a_mesh_with_a_long_name_indeed, level 2, surface loop,"),
            "{s}"
        );
        // Broken only between items: every line but the last ends with a comma.
        let lines: Vec<&str> = s
            .lines()
            .skip_while(|l| !l.starts_with("The row"))
            .collect();
        let end = lines.iter().position(|l| l.ends_with('.')).expect(&s);
        assert!(
            end > 0 && lines[..end].iter().all(|l| l.ends_with(',')),
            "{s}"
        );
        assert!(said.contains(", variant static,"), "{s}");
        assert!(said.contains(", GPU ms 12.35,"), "{s}");
        assert!(!s.lines().any(|l| l.starts_with("--")), "{s}");
        assert!(s.lines().all(|l| width(l) <= SUMMARY_WIDTH), "{s}");
    }

    /// The paragraph above the table says what the rows' ratios compare: `static` and `flat`
    /// where those columns hold values, the uniform rows where adaptive rows compare with them
    /// in their notes (and leave those columns empty).
    #[test]
    fn the_header_says_what_the_ratios_compare() {
        let uniform = report(vec![row("spot", 2, "static", true)]);
        let adaptive_row = |adaptive: bool| {
            let mut r = row("spot", 64, "pattern/instanced", true);
            (r.gpu_ratio, r.wall_ratio, r.throughput_vs_flat) = (None, None, None);
            r.adaptive = Some(crate::bench::AdaptiveCells {
                scene: "close-up".into(),
                pixel_error: 1.0,
                adaptive,
                level_from: if adaptive { "view" } else { "bound" }.into(),
                level_pass_ms: None,
                level_pass_on: None,
                culled_elements: None,
                cpu_ms: None,
                upload_bytes: None,
                histogram: String::new(),
            });
            r
        };
        let adaptive = report(vec![adaptive_row(true), adaptive_row(false)]);
        for (r, static_ratios, notes) in [(&uniform, true, false), (&adaptive, false, true)] {
            for text in [r.markdown(), r.summary(None)] {
                let flat = text.replace('\n', " ");
                assert_eq!(flat.contains("against `static`"), static_ratios, "{text}");
                assert_eq!(flat.contains("is compared in its note"), notes, "{text}");
                assert!(
                    !flat.contains("  Elements") && !flat.contains(";  "),
                    "{text}"
                );
            }
        }
    }
}
