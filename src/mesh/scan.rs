//! The validating pre-scan of OBJ text (see `obj.rs` for why it exists).
//!
//! Statements understood: `v x y z [w]` or `v x y z r g b` (colours ignored), `vn x y z`,
//! `vt u [v [w]]` (finite; `w` ignored), and `f` with corners `v`, `v/vt`, `v//vn` or
//! `v/vt/vn` (positive 1-based or negative relative indices; every index, texture ones
//! included, must refer to a statement of its kind). `#` starts a comment
//! anywhere on a line. The other statements of the format are ignored, and so are lines that are no statement of it (with one warning). Absolute indices may refer to vertices
//! defined later in the file; relative ones count back from the current line.

use glam::{Vec2, Vec3};

use super::normals::unit;
use super::{MeshError, MAX_INDICES};

/// A face statement.
pub(crate) struct FaceInfo {
    /// 1-based line.
    pub line: usize,
    pub corners: usize,
    /// Corners that carry a normal index.
    pub with_normals: usize,
    /// The 0-based texture-coordinate index of every corner, when every corner has one.
    pub texcoords: Option<Vec<u32>>,
}

/// What the validating pass found.
pub(crate) struct Scan {
    /// The file in canonical form, line for line: `v x y z`, `vn x y z`, `f` with absolute
    /// 1-based `v` or `v//vn` corners, and empty lines for everything else.
    pub canonical: String,
    pub faces: Vec<FaceInfo>,
    /// Each `vt` statement's `(u, v)`.
    pub texcoords: Vec<Vec2>,
    /// Each `v` statement's position, in file order (so messages can number vertices as the
    /// file does).
    pub positions: Vec<Vec3>,
    /// Each `vn` statement: its line and value.
    normals: Vec<(usize, Vec3)>,
    /// For each corner with a normal: (0-based normal index, line of its face).
    normal_refs: Vec<(usize, usize)>,
}

pub(crate) fn parse_error(path: &str, line: Option<usize>, msg: String) -> MeshError {
    MeshError::Parse {
        path: path.into(),
        line,
        msg,
    }
}

/// A NUL byte on `line`: binary data.
pub(crate) fn binary_data(path: &str, line: usize) -> MeshError {
    parse_error(
        path,
        Some(line),
        "contains a NUL byte, so this is binary data, not a Wavefront OBJ file".into(),
    )
}

/// The keyword and the remaining words of a line, with any `#` comment removed.
fn statement(line: &str) -> (Option<&str>, std::str::SplitWhitespace<'_>) {
    let content = line.split('#').next().unwrap_or("");
    let mut words = content.split_whitespace();
    (words.next(), words)
}

/// The file's statements: (1-based line of the first, its text, how many lines it spans). A
/// line whose statement (the text before any `#` comment) ends in `\\` continues on the next
/// (the OBJ format's continuation: the two are one statement, the backslash a space; on the
/// last line it is a space too); lines end in `\\n`, `\\r\\n` or, in a file with no `\\n` at
/// all, a lone `\\r` (old Mac text).
fn statements(text: &str) -> Vec<(usize, std::borrow::Cow<'_, str>, usize)> {
    use std::borrow::Cow;
    let lines: Vec<&str> = if !text.contains('\n') && text.contains('\r') {
        text.strip_suffix('\r')
            .unwrap_or(text)
            .split('\r')
            .collect()
    } else {
        text.lines().collect()
    };
    // Where the line's continuing backslash is (none in a comment, which ends the line).
    let continued = |line: &str| -> Option<usize> {
        let line = line.trim_end();
        (!line.contains('#') && line.ends_with('\\')).then(|| line.len() - 1)
    };
    let mut out = Vec::with_capacity(lines.len());
    let mut i = 0;
    while i < lines.len() {
        let Some(cut) = continued(lines[i]) else {
            out.push((i + 1, Cow::Borrowed(lines[i]), 1));
            i += 1;
            continue;
        };
        // Pieces appended once each: time linear in the statement's length.
        let (first, mut joined, mut cut) = (i, String::new(), Some(cut));
        while let Some(c) = cut {
            joined.push_str(&lines[i][..c]);
            joined.push(' ');
            i += 1;
            cut = match lines.get(i) {
                Some(line) => continued(line),
                None => break,
            };
        }
        if let Some(line) = lines.get(i) {
            joined.push_str(line);
            i += 1;
        }
        out.push((first + 1, Cow::Owned(joined), i - first));
    }
    out
}

/// An index as written, resolved to 0-based, or why not.
enum Resolved {
    Ok(usize),
    Zero,
    /// Positive, beyond the total count.
    AfterLast,
    /// Negative, before the first element defined so far.
    BeforeFirst,
}

fn resolve(index: i64, so_far: usize, total: usize) -> Resolved {
    match index {
        0 => Resolved::Zero,
        i if i > 0 => match usize::try_from(i - 1) {
            Ok(r) if r < total => Resolved::Ok(r),
            _ => Resolved::AfterLast,
        },
        // so_far <= MAX_INDICES, so the sum cannot overflow.
        i => usize::try_from(so_far as i64 + i).map_or(Resolved::BeforeFirst, Resolved::Ok),
    }
}

/// Scanning state for one file.
struct Scanner<'a> {
    path: &'a str,
    v_total: usize,
    vn_total: usize,
    vt_total: usize,
    v_count: usize,
    corners_total: usize,
    /// Faces giving `vt` on some corners only (they get none), and the first's line.
    partial_texcoords: (usize, Option<usize>),
    scan: Scan,
}

impl Scan {
    /// Validates `text`, reporting the first problem with its line.
    pub(crate) fn run(path: &str, text: &str) -> Result<Scan, MeshError> {
        // Pass 1: totals, for forward references, and a check for binary data.
        let (mut v_total, mut vn_total, mut vt_total) = (0usize, 0usize, 0usize);
        let statements = statements(text);
        for (ln, line, _) in &statements {
            if line.contains('\0') {
                return Err(binary_data(path, *ln));
            }
            match statement(line).0 {
                Some("v") => v_total += 1,
                Some("vn") => vn_total += 1,
                Some("vt") => vt_total += 1,
                _ => {}
            }
        }
        for (what, count) in [
            ("vertices", v_total),
            ("normals", vn_total),
            ("texture coordinates", vt_total),
        ] {
            if count > MAX_INDICES {
                return Err(MeshError::TooLarge {
                    path: path.into(),
                    what,
                    count,
                });
            }
        }

        // Pass 2: validate every statement and write the canonical text.
        let mut s = Scanner {
            path,
            v_total,
            vn_total,
            vt_total,
            v_count: 0,
            corners_total: 0,
            partial_texcoords: (0, None),
            scan: Scan {
                canonical: String::with_capacity(text.len()),
                faces: Vec::new(),
                texcoords: Vec::new(),
                positions: Vec::with_capacity(v_total),
                normal_refs: Vec::new(),
                normals: Vec::new(),
            },
        };
        // Lines that are no OBJ statement (a misspelt `F 1 2 3`, stray text): how many, the
        // first's line and word.
        let (mut unknown, mut first_unknown) = (0usize, None);
        for (ln, line, span) in &statements {
            let (keyword, words) = statement(line);
            let words: Vec<&str> = words.collect();
            let ln = *ln;
            match keyword {
                Some("v") => s.vertex(ln, &words)?,
                Some("vn") => s.normal(ln, &words)?,
                Some("vt") => s.texcoord(ln, &words)?,
                Some("f") => s.face(ln, &words)?,
                Some(k) if !super::obj::OBJ_KEYWORDS.contains(&k) => {
                    unknown += 1;
                    first_unknown.get_or_insert((ln, super::shown_word(k)));
                }
                _ => {}
            }
            // One line of canonical text per line of the file: tobj's lines are the file's.
            for _ in 0..*span {
                s.scan.canonical.push('\n');
            }
        }
        if let (n, Some(line)) = s.partial_texcoords {
            log::warn!(
                "'{path}': {n} face(s) give texture coordinates (vt) for some corners only (the first at line {line}): those faces have none"
            );
        }
        if let Some((line, word)) = first_unknown {
            log::warn!(
                "'{path}': {unknown} line(s) with no OBJ statement ignored (the first: line {line}, '{word}')"
            );
        }

        if s.corners_total > MAX_INDICES {
            return Err(MeshError::TooLarge {
                path: path.into(),
                what: "triangle corners",
                count: s.corners_total,
            });
        }
        if s.scan.faces.is_empty() {
            return Err(if v_total == 0 {
                parse_error(
                    path,
                    None,
                    "is not a Wavefront OBJ file: it defines no vertices or faces".into(),
                )
            } else {
                MeshError::EmptyMesh { path: path.into() }
            });
        }
        Ok(s.scan)
    }

    /// Whether to keep the file's normals: every corner of every face has one, and those
    /// used are valid (else [`MeshError::BadNormal`] naming the `vn` line). Warns when only
    /// some faces have them.
    pub(crate) fn use_file_normals(&self, path: &str) -> Result<bool, MeshError> {
        let complete = self
            .faces
            .iter()
            .filter(|f| f.with_normals == f.corners)
            .count();
        if complete < self.faces.len() {
            if self.faces.iter().any(|f| f.with_normals > 0) {
                log::warn!(
                    "'{path}': only {complete} of {} faces give a normal for every corner; computing normals for all faces",
                    self.faces.len()
                );
            }
            return Ok(false);
        }
        for &(n, face_line) in &self.normal_refs {
            let (line, v) = self.normals[n];
            if unit(v).is_none() {
                let msg = if v.is_finite() {
                    format!(
                        "the normal used by the face on line {face_line} reads as ({}, {}, {}) in f32: it has zero length",
                        v.x, v.y, v.z
                    )
                } else {
                    format!(
                        "normal ({}, {}, {}) used by the face on line {face_line} is not finite in f32 (NaN, infinite, or beyond about ±3.4e38)",
                        v.x, v.y, v.z
                    )
                };
                return Err(MeshError::BadNormal {
                    path: path.into(),
                    line: Some(line),
                    msg,
                });
            }
        }
        Ok(true)
    }
}

impl Scanner<'_> {
    fn err(&self, line: usize, msg: String) -> MeshError {
        parse_error(self.path, Some(line), msg)
    }

    fn non_finite(&self, line: usize, what: &str) -> MeshError {
        MeshError::NonFinite {
            path: self.path.into(),
            line: Some(line),
            what: what.into(),
        }
    }

    fn float(&self, line: usize, word: &str, what: &str) -> Result<f32, MeshError> {
        word.parse().map_err(|_| {
            let word = super::shown_word(word);
            self.err(line, format!("{what} '{word}' is not a number"))
        })
    }

    /// `v x y z`, `v x y z w` (divided by w) or `v x y z r g b` (colours ignored).
    fn vertex(&mut self, ln: usize, words: &[&str]) -> Result<(), MeshError> {
        if words.len() < 3 {
            return Err(self.err(
                ln,
                format!("vertex has {} coordinate(s) but 3 are needed", words.len()),
            ));
        }
        let mut c = [0f32; 3];
        for (c, w) in c.iter_mut().zip(words) {
            *c = self.float(ln, w, "vertex coordinate")?;
        }
        let mut p = Vec3::from(c);
        match words.len() {
            3 | 6 => {}
            4 => {
                let w = self.float(ln, words[3], "vertex weight")?;
                if !w.is_finite() {
                    return Err(self.non_finite(ln, "vertex weight"));
                }
                if w == 0.0 {
                    return Err(self.err(ln, "vertex weight w is zero".into()));
                }
                p /= w;
                if c.iter().all(|c| c.is_finite()) && !p.is_finite() {
                    return Err(self.non_finite(ln, "vertex coordinate divided by its weight w"));
                }
            }
            n => {
                return Err(self.err(
                    ln,
                    format!(
                        "vertex has {n} values but 'x y z', 'x y z w' or 'x y z r g b' was expected"
                    ),
                ))
            }
        }
        if !p.is_finite() {
            return Err(self.non_finite(ln, "vertex coordinate"));
        }
        self.v_count += 1;
        self.scan.positions.push(p);
        // `Display` for f32 prints the shortest text that parses back to the same value.
        self.scan
            .canonical
            .push_str(&format!("v {} {} {}", p.x, p.y, p.z));
        Ok(())
    }

    /// `vn x y z`, exactly three numbers (as `vt` takes at most three). Zero or non-finite
    /// normals are only an error if used.
    fn normal(&mut self, ln: usize, words: &[&str]) -> Result<(), MeshError> {
        if words.len() != 3 {
            return Err(self.err(
                ln,
                format!("normal has {} component(s) but 3 are needed", words.len()),
            ));
        }
        let mut c = [0f32; 3];
        for (c, w) in c.iter_mut().zip(words) {
            *c = self.float(ln, w, "normal component")?;
        }
        self.scan.normals.push((ln, Vec3::from(c)));
        self.scan
            .canonical
            .push_str(&format!("vn {} {} {}", c[0], c[1], c[2]));
        Ok(())
    }

    /// `vt u [v [w]]`: one to three finite numbers (`v` defaults to 0, `w` is ignored).
    fn texcoord(&mut self, ln: usize, words: &[&str]) -> Result<(), MeshError> {
        if words.is_empty() || words.len() > 3 {
            return Err(self.err(
                ln,
                format!(
                    "texture coordinate has {} component(s) but 1 to 3 are needed",
                    words.len()
                ),
            ));
        }
        let mut c = [0f32; 2];
        for (c, w) in c.iter_mut().zip(words) {
            *c = self.float(ln, w, "texture coordinate")?;
        }
        if let Some(w) = words.get(2) {
            self.float(ln, w, "texture coordinate")?;
        }
        if !c.iter().all(|x| x.is_finite()) {
            return Err(self.non_finite(ln, "texture coordinate"));
        }
        self.scan.texcoords.push(Vec2::from(c));
        Ok(())
    }

    fn face(&mut self, ln: usize, words: &[&str]) -> Result<(), MeshError> {
        if words.len() < 3 {
            return Err(self.err(
                ln,
                format!(
                    "face has {} vertex reference(s) but at least 3 are needed",
                    words.len()
                ),
            ));
        }
        let mut with_normals = 0;
        let mut with_texcoords = 0;
        let mut texcoords = Some(Vec::with_capacity(words.len()));
        let mut canonical = String::from("f");
        for word in words {
            let (v, t, n) = self.corner(ln, word)?;
            let v = self.position_index(ln, v)?;
            match t {
                Some(t) => {
                    let t = self.texcoord_index(ln, t)?;
                    with_texcoords += 1;
                    if let Some(ts) = &mut texcoords {
                        ts.push(t as u32);
                    }
                }
                None => texcoords = None,
            }
            canonical.push_str(&format!(" {}", v + 1));
            if let Some(n) = n {
                let n = self.normal_index(ln, n)?;
                canonical.push_str(&format!("//{}", n + 1));
                self.scan.normal_refs.push((n, ln));
                with_normals += 1;
            }
        }
        if with_texcoords > 0 && with_texcoords < words.len() {
            self.partial_texcoords.0 += 1;
            self.partial_texcoords.1.get_or_insert(ln);
        }
        self.scan.canonical.push_str(&canonical);
        self.corners_total = self
            .corners_total
            .saturating_add((words.len() - 2).saturating_mul(3));
        self.scan.faces.push(FaceInfo {
            line: ln,
            corners: words.len(),
            with_normals,
            texcoords,
        });
        Ok(())
    }

    /// One corner `v`, `v/vt`, `v//vn` or `v/vt/vn`: the position, texture-coordinate and
    /// normal indices as written.
    fn corner(&self, ln: usize, word: &str) -> Result<(i64, Option<i64>, Option<i64>), MeshError> {
        let parts: Vec<&str> = word.split('/').collect();
        // Quoted short, whatever the file holds (only where a message quotes it).
        let shown = || super::shown_word(word);
        if parts.len() > 3 {
            return Err(self.err(
                ln,
                format!(
                    "face vertex '{}' has more than three '/'-separated indices",
                    shown()
                ),
            ));
        }
        let index = |s: &str, what: &str| -> Result<Option<i64>, MeshError> {
            if s.is_empty() {
                return Ok(None);
            }
            s.parse().map(Some).map_err(|_| {
                self.err(
                    ln,
                    format!("face vertex '{}' has an invalid {what} index", shown()),
                )
            })
        };
        let v = index(parts[0], "position")?.ok_or_else(|| {
            self.err(
                ln,
                format!("face vertex '{}' has no position index", shown()),
            )
        })?;
        let t = match parts.get(1) {
            Some(s) => index(s, "texture coordinate")?,
            None => None,
        };
        let n = match parts.get(2) {
            Some(s) => index(s, "normal")?,
            None => None,
        };
        Ok((v, t, n))
    }

    fn position_index(&self, ln: usize, index: i64) -> Result<usize, MeshError> {
        let out_of_range = |count| MeshError::IndexOutOfRange {
            path: self.path.into(),
            line: Some(ln),
            index,
            count,
        };
        match resolve(index, self.v_count, self.v_total) {
            Resolved::Ok(r) => Ok(r),
            Resolved::Zero | Resolved::AfterLast => Err(out_of_range(self.v_total)),
            Resolved::BeforeFirst => Err(out_of_range(self.v_count)),
        }
    }

    fn normal_index(&self, ln: usize, index: i64) -> Result<usize, MeshError> {
        let so_far = self.scan.normals.len();
        self.attribute_index(ln, index, so_far, self.vn_total, "normal")
    }

    fn texcoord_index(&self, ln: usize, index: i64) -> Result<usize, MeshError> {
        let so_far = self.scan.texcoords.len();
        self.attribute_index(ln, index, so_far, self.vt_total, "texture coordinate")
    }

    /// A `vn` or `vt` index: `so_far` defined before this line, `total` in the file.
    fn attribute_index(
        &self,
        ln: usize,
        index: i64,
        so_far: usize,
        total: usize,
        what: &str,
    ) -> Result<usize, MeshError> {
        let msg = match resolve(index, so_far, total) {
            Resolved::Ok(r) => return Ok(r),
            Resolved::Zero => format!("face refers to {what} 0 but OBJ indices start at 1"),
            Resolved::AfterLast if total == 0 => format!(
                "face refers to {what} {index} but the file defines no {what}s (no '{}' lines)",
                if what == "normal" { "vn" } else { "vt" }
            ),
            Resolved::AfterLast => format!(
                "face refers to {what} {index} but the file defines only {total} {what}(s)"
            ),
            Resolved::BeforeFirst => format!(
                "face refers to {what} {index} (relative) but only {so_far} {what}(s) are defined before this line"
            ),
        };
        Err(self.err(ln, msg))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_support::{err, load, TRI};

    #[test]
    fn canonical_text_keeps_lines_and_resolves_indices() {
        let text = "# c\no a\nv 1 2 3 2\nv 0 0 0 # v\nv 1 0 0\nvt 0 0\nvn 0 0 1\n\
                    usemtl m\nf -3/1/1 2//-1 3/1\nl 1 2\n";
        let scan = Scan::run("x", text).unwrap();
        assert_eq!(
            scan.canonical,
            "\n\nv 0.5 1 1.5\nv 0 0 0\nv 1 0 0\n\nvn 0 0 1\n\nf 1//1 2//1 3\n\n"
        );
        assert_eq!(scan.faces.len(), 1);
        assert_eq!(scan.faces[0].line, 9);
        assert_eq!(scan.faces[0].with_normals, 2);
    }

    /// A statement continued with `\` is one statement, named by its first line; its lines
    /// stay lines of the canonical text. A file with lone `\r` line ends (old Mac text) reads
    /// as one with `\n`.
    #[test]
    fn continued_statements_and_carriage_returns() {
        let text = "v 0 0 0\nv 1 \\\n 0 0\nv 0 1 0\nf 1 \\\n2 \\\n 3\nf 1 2 9\n";
        let Err(e) = Scan::run("x", text) else {
            panic!("accepted")
        };
        assert_eq!(
            e.to_string(),
            "'x' line 8: face refers to vertex 9 but the file defines only 3 vertices"
        );
        let scan = Scan::run("x", &text.replace("f 1 2 9\n", "")).unwrap();
        assert_eq!(scan.canonical, "v 0 0 0\nv 1 0 0\n\nv 0 1 0\nf 1 2 3\n\n\n");
        assert_eq!(scan.faces[0].line, 5);
        let empty = Scan::run("x", &TRI.replace('\n', "\r"));
        assert!(matches!(empty, Err(MeshError::EmptyMesh { .. })));
        // A backslash ending a comment continues nothing; one on the last line is a space.
        let commented = format!("# C:\\models\\\n{TRI}f 1 2 3 \\\n");
        let scan = Scan::run("x", &commented).unwrap();
        assert_eq!(scan.positions.len(), 3);
        assert_eq!(scan.faces[0].line, 5);
        // A statement continued over 200,000 lines (joined piece by piece, each once).
        let long = format!("{TRI}f 1 \\\n{}2 \\\n3\n", "\\\n".repeat(200_000));
        let scan = Scan::run("x", &long).unwrap();
        assert_eq!(scan.canonical.lines().count(), 200_006);
        assert_eq!(scan.faces[0].corners, 3);
        let mac = Scan::run("x", &format!("{TRI}f 1 2 3\n").replace('\n', "\r")).unwrap();
        assert_eq!(
            mac.canonical,
            Scan::run("x", &format!("{TRI}f 1 2 3\n"))
                .unwrap()
                .canonical
        );
    }

    #[test]
    fn out_of_range_indices_name_the_line() {
        assert_eq!(
            err(&format!("# c\n{TRI}f 1 2 3\nf 1 2 99\n")),
            "'x.obj' line 6: face refers to vertex 99 but the file defines only 3 vertices"
        );
        assert_eq!(
            err(&format!("{TRI}f 0 1 2\n")),
            "'x.obj' line 4: face refers to vertex 0 but OBJ indices start at 1"
        );
        assert_eq!(
            err(&format!("{TRI}f -1 -2 -4\n")),
            "'x.obj' line 4: face refers to vertex -4 (relative) but only 3 vertices are defined before this line"
        );
        assert!(matches!(
            load(&format!("{TRI}f 1 2 99\n")),
            Err(MeshError::IndexOutOfRange {
                line: Some(4),
                index: 99,
                count: 3,
                ..
            })
        ));
        assert_eq!(
            err(&format!("{TRI}f 1 2 99999999999999999999999\n")),
            "'x.obj' line 4: face vertex '99999999999999999999999' has an invalid position index"
        );
    }

    #[test]
    fn relative_and_forward_indices() {
        let (rel, _) = load(&format!("{TRI}f -3 -2 -1\n")).unwrap();
        let (abs, _) = load(&format!("{TRI}f 1 2 3\n")).unwrap();
        assert_eq!(rel, abs);
        // An absolute index may refer to a vertex defined later in the file.
        let (fwd, _) = load("v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n").unwrap();
        assert_eq!(fwd.triangles.len(), 1);
        // A relative one may not.
        assert_eq!(
            err("v 0 0 0\nv 1 0 0\nf -2 -1 -3\nv 0 1 0\n"),
            "'x.obj' line 3: face refers to vertex -3 (relative) but only 2 vertices are defined before this line"
        );
    }

    #[test]
    fn non_finite_coordinates_name_the_line() {
        for bad in ["nan", "NaN", "inf", "-infinity", "1e39"] {
            assert_eq!(
                err(&format!("v 0 0 0\nv {bad} 0 0\nv 0 1 0\nf 1 2 3\n")),
                "'x.obj' line 2: vertex coordinate is not finite in f32 (NaN, infinite, or beyond about ±3.4e38)",
                "{bad}"
            );
        }
        assert!(matches!(
            load("v 0 0 0\nv 0 0 nan\n"),
            Err(MeshError::NonFinite { line: Some(2), .. })
        ));
        assert_eq!(
            err("v 1 2 3 inf\n"),
            "'x.obj' line 1: vertex weight is not finite in f32 (NaN, infinite, or beyond about ±3.4e38)"
        );
        // Four finite numbers whose quotient is not: the division is named.
        assert_eq!(
            err("v 1 1 1 1e-45\n"),
            "'x.obj' line 1: vertex coordinate divided by its weight w is not finite in f32 (NaN, infinite, or beyond about ±3.4e38)"
        );
    }

    #[test]
    fn malformed_vertices() {
        assert_eq!(
            err("v 1 2\n"),
            "'x.obj' line 1: vertex has 2 coordinate(s) but 3 are needed"
        );
        assert_eq!(
            err("v 1 2 x\n"),
            "'x.obj' line 1: vertex coordinate 'x' is not a number"
        );
        assert_eq!(
            err("v 1 2 3 q\n"),
            "'x.obj' line 1: vertex weight 'q' is not a number"
        );
        assert_eq!(
            err("v 1 2 3 0\n"),
            "'x.obj' line 1: vertex weight w is zero"
        );
        assert_eq!(
            err("v 1 2 3 4 5\n"),
            "'x.obj' line 1: vertex has 5 values but 'x y z', 'x y z w' or 'x y z r g b' was expected"
        );
        // Weights divide, colours are ignored.
        let (m, _) = load("v 0 0 0 2\nv 2 0 0 2\nv 0 2 0 2 \nf 1 2 3\n").unwrap();
        assert_eq!(m.positions, vec![Vec3::ZERO, Vec3::X, Vec3::Y]);
        let (m, _) = load("v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        assert_eq!(m.positions.len(), 3);
    }

    #[test]
    fn malformed_faces() {
        assert_eq!(
            err(&format!("{TRI}f 1 2\n")),
            "'x.obj' line 4: face has 2 vertex reference(s) but at least 3 are needed"
        );
        assert_eq!(
            err(&format!("{TRI}f\n")),
            "'x.obj' line 4: face has 0 vertex reference(s) but at least 3 are needed"
        );
        assert_eq!(
            err(&format!("{TRI}f 1 2 a\n")),
            "'x.obj' line 4: face vertex 'a' has an invalid position index"
        );
        assert_eq!(
            err(&format!("{TRI}f 1 2 /3\n")),
            "'x.obj' line 4: face vertex '/3' has no position index"
        );
        assert_eq!(
            err(&format!("{TRI}f 1 2 3/1/1/1\n")),
            "'x.obj' line 4: face vertex '3/1/1/1' has more than three '/'-separated indices"
        );
        assert_eq!(
            err(&format!("{TRI}f 1 2 3/x\n")),
            "'x.obj' line 4: face vertex '3/x' has an invalid texture coordinate index"
        );
        assert_eq!(
            err(&format!("{TRI}vn 0 0 1\nf 1 2 3//x\n")),
            "'x.obj' line 5: face vertex '3//x' has an invalid normal index"
        );
    }

    #[test]
    fn empty_and_non_obj_inputs() {
        let not_obj = "'x.obj' is not a Wavefront OBJ file: it defines no vertices or faces";
        assert_eq!(err(""), not_obj);
        assert_eq!(err("\n\n"), not_obj);
        assert_eq!(err("# only a comment\n"), not_obj);
        assert_eq!(err("hello world\n"), not_obj);
        assert_eq!(err(TRI), "'x.obj' contains no triangles");
        assert_eq!(
            err("v 0 0 0\n\u{0}\u{1}"),
            "'x.obj' line 2: contains a NUL byte, so this is binary data, not a Wavefront OBJ file"
        );
    }

    #[test]
    fn texture_coordinates_are_validated_like_normals() {
        let vt = "vt 0 0\nvt 1 0\nvt 0 1\n";
        for (text, want) in [
            (
                format!("{TRI}f 1/0 2/0 3/0\n"),
                "'x.obj' line 4: face refers to texture coordinate 0 but OBJ indices start at 1",
            ),
            (
                format!("{TRI}f 1/2 2/2 3/2\n"),
                "'x.obj' line 4: face refers to texture coordinate 2 but the file defines no texture coordinates (no 'vt' lines)",
            ),
            (
                format!("{TRI}{vt}f 1/99/1 2/1 3/1\n"),
                "'x.obj' line 7: face refers to texture coordinate 99 but the file defines only 3 texture coordinate(s)",
            ),
            (
                format!("{TRI}{vt}f 1/-5 2/1 3/1\n"),
                "'x.obj' line 7: face refers to texture coordinate -5 (relative) but only 3 texture coordinate(s) are defined before this line",
            ),
            (
                format!("{TRI}vt abc def\nf 1 2 3\n"),
                "'x.obj' line 4: texture coordinate 'abc' is not a number",
            ),
            (
                format!("{TRI}vt nan 0\nf 1 2 3\n"),
                "'x.obj' line 4: texture coordinate is not finite in f32 (NaN, infinite, or beyond about ±3.4e38)",
            ),
            (
                format!("{TRI}vt 0 inf\nf 1 2 3\n"),
                "'x.obj' line 4: texture coordinate is not finite in f32 (NaN, infinite, or beyond about ±3.4e38)",
            ),
            (
                format!("{TRI}vt\nf 1 2 3\n"),
                "'x.obj' line 4: texture coordinate has 0 component(s) but 1 to 3 are needed",
            ),
            (
                format!("{TRI}vt 0 0 0 0\nf 1 2 3\n"),
                "'x.obj' line 4: texture coordinate has 4 component(s) but 1 to 3 are needed",
            ),
            (
                format!("{TRI}vt 0 0 w\nf 1 2 3\n"),
                "'x.obj' line 4: texture coordinate 'w' is not a number",
            ),
            (
                format!("{TRI}f 1//1 2//1 3//1\n"),
                "'x.obj' line 4: face refers to normal 1 but the file defines no normals (no 'vn' lines)",
            ),
        ] {
            assert_eq!(err(&text), want, "{text:?}");
        }
        // A relative index counts back from the line; a forward absolute one is fine.
        assert!(load(&format!("{TRI}{vt}f 1/-3 2/-2 3/-1\n")).is_ok());
        assert!(load(&format!("{TRI}f 1/1 2/1 3/1\nvt 0 0\n")).is_ok());
    }

    #[test]
    fn bad_normals_name_their_line() {
        assert_eq!(
            err(&format!("{TRI}vn 0 0 0\nf 1//1 2//1 3//1\n")),
            "'x.obj' line 4: the normal used by the face on line 5 reads as (0, 0, 0) in f32: it has zero length"
        );
        // Non-zero in the file, zero in f32: said so.
        assert_eq!(
            err(&format!("{TRI}vn 0 1e-50 0\nf 1//1 2//1 3//1\n")),
            "'x.obj' line 4: the normal used by the face on line 5 reads as (0, 0, 0) in f32: it has zero length"
        );
        assert_eq!(
            err(&format!("{TRI}vn 0 0 1\nvn nan 0 1\nf 1//1 2//1 3//2\n")),
            "'x.obj' line 5: normal (NaN, 0, 1) used by the face on line 6 is not finite in f32 (NaN, infinite, or beyond about ±3.4e38)"
        );
        // An unused bad normal is harmless, and so is one on a file whose normals are
        // recomputed because some faces have none.
        assert!(load(&format!("{TRI}vn 0 0 1\nvn 0 0 0\nf 1//1 2//1 3//1\n")).is_ok());
        assert!(load(&format!("{TRI}vn 0 0 0\nf 1//1 2//1 3\n")).is_ok());
        assert_eq!(
            err(&format!("{TRI}vn 0 0 1\nf 1//1 2//1 3//7\n")),
            "'x.obj' line 5: face refers to normal 7 but the file defines only 1 normal(s)"
        );
        assert_eq!(
            err(&format!("{TRI}vn 0 0 1\nf 1//1 2//1 3//0\n")),
            "'x.obj' line 5: face refers to normal 0 but OBJ indices start at 1"
        );
        assert_eq!(
            err(&format!("{TRI}vn 0 0 1\nf 1//-5 2//1 3//1\n")),
            "'x.obj' line 5: face refers to normal -5 (relative) but only 1 normal(s) are defined before this line"
        );
        assert_eq!(
            err(&format!("{TRI}vn 0 0\nf 1 2 3\n")),
            "'x.obj' line 4: normal has 2 component(s) but 3 are needed"
        );
        assert_eq!(
            err(&format!("{TRI}vn 0 0 1 5\nf 1 2 3\n")),
            "'x.obj' line 4: normal has 4 component(s) but 3 are needed"
        );
        assert_eq!(
            err(&format!("{TRI}vn 0 0 z\nf 1 2 3\n")),
            "'x.obj' line 4: normal component 'z' is not a number"
        );
    }
}
