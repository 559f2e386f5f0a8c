//! The error type of mesh loading and validation.
//!
//! Every message is a single lower-case sentence without a trailing period that names the
//! file (or the name given to [`Mesh::from_obj_str`](super::Mesh::from_obj_str) /
//! [`Mesh::from_parts`](super::Mesh::from_parts)), the 1-based line where one is known, and
//! what is wrong.

use thiserror::Error;

/// The largest number of vertices, normals or triangle corners a mesh may have
/// (`u32::MAX / 2`), so that every index fits comfortably in a `u32` index buffer.
pub const MAX_INDICES: usize = (u32::MAX / 2) as usize;

/// The largest OBJ file read, in bytes (1 GiB). Larger files are refused from their size before
/// anything is read: loading holds the text, a canonical copy and the parsed arrays at once,
/// several times the file's size.
pub const MAX_OBJ_BYTES: u64 = 1 << 30;

/// Why a mesh could not be loaded or does not meet a requirement.
#[derive(Debug, Error)]
pub enum MeshError {
    /// The file could not be read.
    #[error("cannot read mesh file '{path}': {err}")]
    Io {
        /// The file path as displayed, or the name given instead of one.
        path: String,
        /// The underlying I/O error.
        err: std::io::Error,
    },
    /// The file is larger than [`MAX_OBJ_BYTES`].
    #[error("'{path}' is too large to load: {size} bytes, over the limit of {max} bytes (1 GiB) for an OBJ file", max = MAX_OBJ_BYTES)]
    FileTooLarge {
        /// The file path as displayed.
        path: String,
        /// Its size in bytes (or what was read before it grew past the limit).
        size: u64,
    },
    /// The text is not a well-formed Wavefront OBJ file.
    #[error("{}", parse_message(.path, .line, .msg))]
    Parse {
        /// The file path as displayed, or the name given instead of one.
        path: String,
        /// 1-based line in the OBJ text, where known.
        line: Option<usize>,
        /// What is wrong, continuing the sentence after the location.
        msg: String,
    },
    /// No triangle is left (none in the file, or all of them degenerate).
    #[error("'{path}' contains no triangles")]
    EmptyMesh {
        /// The file path as displayed, or the name given instead of one.
        path: String,
    },
    /// Every triangle was dropped as degenerate.
    #[error("'{path}' contains no triangles that can be drawn: all {count} are degenerate (the first, {first})")]
    NoDrawableTriangles {
        /// The file path as displayed, or the name given instead of one.
        path: String,
        /// How many triangles were dropped.
        count: usize,
        /// The first one and why, as [`DegenerateFace::describe`](super::DegenerateFace::describe).
        first: String,
    },
    /// A face refers to a vertex that does not exist. `index` is the index as written
    /// (1-based, or negative for relative OBJ indices; 0-based for
    /// [`Mesh::from_parts`](super::Mesh::from_parts)), `count` the number of vertices it
    /// could refer to.
    #[error("{}", index_message(.path, .line, *.index, *.count))]
    IndexOutOfRange {
        /// The file path as displayed, or the name given instead of one.
        path: String,
        /// 1-based line in the OBJ text, where known.
        line: Option<usize>,
        /// The index as written.
        index: i64,
        /// How many there are (vertices it could refer to, or items for `TooLarge`).
        count: usize,
    },
    /// A coordinate is NaN or infinite; `what` names the value (e.g. "vertex coordinate").
    #[error("{}: {what} is not finite in f32 (NaN, infinite, or beyond about ±3.4e38)", at(.path, .line))]
    NonFinite {
        /// The file path as displayed, or the name given instead of one.
        path: String,
        /// 1-based line in the OBJ text, where known.
        line: Option<usize>,
        /// The value that is not finite.
        what: String,
    },
    /// A given normal cannot be used (zero length, NaN, infinite, or wrong count).
    #[error("{}: {msg}", at(.path, .line))]
    BadNormal {
        /// The file path as displayed, or the name given instead of one.
        path: String,
        /// 1-based line in the OBJ text, where known.
        line: Option<usize>,
        /// What is wrong, continuing the sentence after the location.
        msg: String,
    },
    /// More than [`MAX_INDICES`] vertices, normals or triangle corners.
    #[error("'{path}' is too large: it has {count} {what} but at most {max} are supported", max = MAX_INDICES)]
    TooLarge {
        /// The file path as displayed, or the name given instead of one.
        path: String,
        /// What there is too much of: "vertices", "normals" or "triangle corners".
        what: &'static str,
        /// How many there are (vertices it could refer to, or items for `TooLarge`).
        count: usize,
    },
    /// Returned by [`Mesh::require_manifold`](super::Mesh::require_manifold).
    #[error("'{path}' is not a manifold mesh: {edges} edge(s) shared by more than two triangles, {vertices} non-manifold vertex(es)")]
    NonManifold {
        /// The file path as displayed, or the name given instead of one.
        path: String,
        /// Edges shared by more than two triangles.
        edges: usize,
        /// Non-manifold vertices.
        vertices: usize,
    },
}

/// "'path' line N" or "'path'".
fn at(path: &str, line: &Option<usize>) -> String {
    match line {
        Some(n) => format!("'{path}' line {n}"),
        None => format!("'{path}'"),
    }
}

/// With a line: "'path' line N: msg"; without one the message continues the sentence
/// ("'path' is not a Wavefront OBJ file: ...").
fn parse_message(path: &str, line: &Option<usize>, msg: &str) -> String {
    match line {
        Some(n) => format!("'{path}' line {n}: {msg}"),
        None => format!("'{path}' {msg}"),
    }
}

fn index_message(path: &str, line: &Option<usize>, index: i64, count: usize) -> String {
    let plural = |n: usize| if n == 1 { "vertex" } else { "vertices" };
    match line {
        Some(n) if index == 0 => {
            format!("'{path}' line {n}: face refers to vertex 0 but OBJ indices start at 1")
        }
        Some(n) if index < 0 => format!(
            "'{path}' line {n}: face refers to vertex {index} (relative) but only {count} {} defined before this line",
            if count == 1 { "vertex is" } else { "vertices are" }
        ),
        Some(n) => format!(
            "'{path}' line {n}: face refers to vertex {index} but the file defines only {count} {}",
            plural(count)
        ),
        None => format!(
            "'{path}': a triangle refers to vertex index {index} but only {count} {} exist",
            plural(count)
        ),
    }
}

/// A word of a file as a message quotes it: its first 40 characters, then "…" and how many
/// there are in all, so that one sentence stays one short line whatever the file holds.
pub fn shown_word(word: &str) -> String {
    const SHOWN: usize = 40;
    match word.char_indices().nth(SHOWN) {
        None => word.to_string(),
        Some((at, _)) => format!("{}… ({} characters)", &word[..at], word.chars().count()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_words_are_shortened() {
        assert_eq!(shown_word("1.5x"), "1.5x");
        let long = "9".repeat(5000);
        assert_eq!(
            shown_word(&long),
            format!("{}… (5000 characters)", &long[..40])
        );
        assert_eq!(
            shown_word(&"é".repeat(41)),
            format!("{}… (41 characters)", "é".repeat(40))
        );
    }

    #[test]
    fn messages_are_single_lower_case_sentences() {
        let io = std::io::Error::from(std::io::ErrorKind::NotFound);
        let cases = [
            (
                MeshError::Io {
                    path: "x.obj".into(),
                    err: io,
                },
                "cannot read mesh file 'x.obj': entity not found",
            ),
            (
                MeshError::Parse {
                    path: "x.obj".into(),
                    line: Some(12),
                    msg: "vertex coordinate 'a' is not a number".into(),
                },
                "'x.obj' line 12: vertex coordinate 'a' is not a number",
            ),
            (
                MeshError::Parse {
                    path: "x.obj".into(),
                    line: None,
                    msg: "is not a Wavefront OBJ file: it defines no vertices or faces".into(),
                },
                "'x.obj' is not a Wavefront OBJ file: it defines no vertices or faces",
            ),
            (
                MeshError::FileTooLarge {
                    path: "x.obj".into(),
                    size: 1 << 34,
                },
                "'x.obj' is too large to load: 17179869184 bytes, over the limit of 1073741824 bytes (1 GiB) for an OBJ file",
            ),
            (
                MeshError::EmptyMesh {
                    path: "x.obj".into(),
                },
                "'x.obj' contains no triangles",
            ),
            (
                MeshError::IndexOutOfRange {
                    path: "x.obj".into(),
                    line: Some(7),
                    index: 99,
                    count: 8,
                },
                "'x.obj' line 7: face refers to vertex 99 but the file defines only 8 vertices",
            ),
            (
                MeshError::NonFinite {
                    path: "x.obj".into(),
                    line: Some(3),
                    what: "vertex coordinate".into(),
                },
                "'x.obj' line 3: vertex coordinate is not finite in f32 (NaN, infinite, or beyond about ±3.4e38)",
            ),
            (
                MeshError::NonManifold {
                    path: "x.obj".into(),
                    edges: 1,
                    vertices: 2,
                },
                "'x.obj' is not a manifold mesh: 1 edge(s) shared by more than two triangles, 2 non-manifold vertex(es)",
            ),
        ];
        for (err, want) in cases {
            assert_eq!(err.to_string(), want);
        }
    }

    #[test]
    fn io_error_is_one_sentence() {
        let err = MeshError::Io {
            path: "x.obj".into(),
            err: std::io::Error::from(std::io::ErrorKind::NotFound),
        };
        // The OS error is part of the message, not a separate cause (printed once by anyhow).
        assert!(std::error::Error::source(&err).is_none());
    }

    #[test]
    fn index_messages_cover_zero_relative_and_parts() {
        let msg = |line, index, count| {
            MeshError::IndexOutOfRange {
                path: "m".into(),
                line,
                index,
                count,
            }
            .to_string()
        };
        assert_eq!(
            msg(Some(4), 0, 3),
            "'m' line 4: face refers to vertex 0 but OBJ indices start at 1"
        );
        assert_eq!(
            msg(Some(4), -9, 1),
            "'m' line 4: face refers to vertex -9 (relative) but only 1 vertex is defined before this line"
        );
        assert_eq!(
            msg(None, 5, 3),
            "'m': a triangle refers to vertex index 5 but only 3 vertices exist"
        );
    }
}
