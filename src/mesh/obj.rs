//! Wavefront OBJ loading: a validating pre-scan, then `tobj` for triangulation.
//!
//! `tobj` 4 reports errors without line numbers and trusts its input more than a loader of
//! user files can: it accepts `nan`/`inf` coordinates, silently skips faces with fewer than
//! three vertices, silently invents a normal for a corner with normal index 0, and panics
//! (integer overflow, in builds with overflow checks) on a face whose relative normal or
//! texture index points before the first one (e.g. `f 1//-5 2//1 3//1`). So the text is
//! first scanned (`scan.rs`), line by line, and every problem is reported with its line. The
//! scan also rewrites the file into a canonical form that `tobj` cannot misread: only `v x y z`,
//! `vn x y z` and `f` lines with absolute, range-checked `v` or `v//vn` indices remain; every
//! other statement (groups, objects, materials, texture coordinates, lines, points) becomes
//! an empty line, which also merges all objects and groups into one mesh. Texture coordinates
//! are taken from the scan itself (validated there). `tobj` then parses that text and
//! fan-triangulates polygons (`0 1 2`, `0 2 3`, ...), whose corners are taken back from its fans
//! and triangulated again by their shape (src/mesh/polygon.rs: the same fan where convex).

use std::io::{Cursor, Read as _};
use std::path::Path;

use glam::Vec3;

use super::scan::{binary_data, parse_error, Scan};
use super::weld::{assemble, mesh_name, RawMesh, RawTriangle};
use super::{LoadReport, Mesh, MeshError, MAX_OBJ_BYTES};

/// Reads and parses an OBJ file. Bytes that are not UTF-8 are replaced (they can only
/// matter inside comments or names, which are ignored).
///
/// Only regular files are read: a directory, FIFO, socket or device (`/dev/zero`) is refused
/// from its metadata, before it is opened (opening a FIFO for reading blocks until a writer
/// comes). Files over [`MAX_OBJ_BYTES`] are refused from their size; the file is then read in
/// chunks, never more than that limit, and reading stops at the first NUL byte (binary data).
pub(crate) fn load_obj(path: &Path) -> Result<(Mesh, LoadReport), MeshError> {
    let shown = path.display().to_string();
    let bytes = read_obj_bytes(&shown, path)?;
    let text = String::from_utf8_lossy(&bytes);
    parse_obj(&shown, mesh_name(&shown), &text)
}

/// A UTF-8 byte order mark, which some Windows editors write at the start of a text file: not
/// part of its first line.
const BOM: &str = "\u{feff}";

use crate::paths::file_kind;

/// The bytes of a regular OBJ file of at most [`MAX_OBJ_BYTES`], read incrementally.
fn read_obj_bytes(shown: &str, path: &Path) -> Result<Vec<u8>, MeshError> {
    let io = |err| MeshError::Io {
        path: shown.into(),
        err,
    };
    let not_regular = |t: std::fs::FileType| {
        parse_error(
            shown,
            None,
            format!(
                "is {}, not a regular file: only OBJ files are read",
                file_kind(t)
            ),
        )
    };
    let too_large = |size: u64| MeshError::FileTooLarge {
        path: shown.into(),
        size,
    };
    // `metadata` follows symbolic links, so a link to a FIFO is refused too.
    let meta = std::fs::metadata(path).map_err(io)?;
    if !meta.is_file() {
        return Err(not_regular(meta.file_type()));
    }
    if meta.len() > MAX_OBJ_BYTES {
        return Err(too_large(meta.len()));
    }
    let mut file = std::fs::File::open(path).map_err(io)?;
    // The path may have been replaced between the two calls: check what was opened.
    let meta = file.metadata().map_err(io)?;
    if !meta.is_file() {
        return Err(not_regular(meta.file_type()));
    }
    let mut bytes = Vec::with_capacity(meta.len().min(MAX_OBJ_BYTES) as usize);
    let mut chunk = vec![0u8; 1 << 16];
    // Until the first statement is seen, every chunk's complete lines are checked, so a file
    // that is not an OBJ stops at its first line, not after a gigabyte.
    let mut head = Some(Head::default());
    loop {
        let n = match file.read(&mut chunk) {
            Ok(0) => break,
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(io(e)),
        };
        let chunk = &chunk[..n];
        // UTF-16 text (Notepad's "Unicode") holds NUL bytes: named as what it is.
        if bytes.is_empty()
            && (chunk.starts_with(&[0xff, 0xfe]) || chunk.starts_with(&[0xfe, 0xff]))
        {
            return Err(parse_error(
                shown,
                Some(1),
                "is UTF-16 text (it starts with a UTF-16 byte-order mark): save it as UTF-8, which Wavefront OBJ files are".into(),
            ));
        }
        if let Some(at) = chunk.iter().position(|&b| b == 0) {
            let newlines = |b: &[u8]| b.iter().filter(|&&c| c == b'\n').count();
            let line = newlines(&bytes) + newlines(&chunk[..at]) + 1;
            return Err(binary_data(shown, line));
        }
        if (bytes.len() + n) as u64 > MAX_OBJ_BYTES {
            // The file grew after its size was checked.
            return Err(too_large((bytes.len() + n) as u64));
        }
        bytes.extend_from_slice(chunk);
        if let Some(h) = &mut head {
            if h.check(shown, &bytes)? {
                head = None;
            }
        }
    }
    Ok(bytes)
}

/// Every statement keyword of the OBJ format (Wavefront's "Object Files (.obj)", appendix B1),
/// including those meshrefine ignores (groups, materials, free-form geometry).
pub(crate) const OBJ_KEYWORDS: &[&str] = &[
    "v",
    "vt",
    "vn",
    "vp",
    "f",
    "l",
    "p",
    "o",
    "g",
    "s",
    "mg",
    "usemtl",
    "mtllib",
    "cstype",
    "deg",
    "bmat",
    "step",
    "curv",
    "curv2",
    "surf",
    "parm",
    "trim",
    "hole",
    "scrv",
    "sp",
    "end",
    "con",
    "bevel",
    "c_interp",
    "d_interp",
    "lod",
    "shadow_obj",
    "trace_obj",
    "ctech",
    "stech",
    "maplib",
    "usemap",
    "call",
    "csh",
];

/// The check of a file's first statement while it is read.
#[derive(Default)]
struct Head {
    /// Bytes of complete lines already checked, and their count.
    checked: usize,
    lines: usize,
    /// Bytes past `checked` already searched for a line end (none there): each chunk is
    /// searched once, so a long first line costs its length, not its length squared.
    searched: usize,
}

impl Head {
    /// Checks the complete lines of `bytes` not checked yet: true once a first OBJ statement is
    /// found, an error at a first line that is not UTF-8 text or not an OBJ statement.
    fn check(&mut self, shown: &str, bytes: &[u8]) -> Result<bool, MeshError> {
        let not_obj = |line: usize, what: String| {
            parse_error(
                shown,
                Some(line),
                format!("{what}: this is not a Wavefront OBJ file"),
            )
        };
        loop {
            let from = self.searched.max(self.checked);
            let Some(at) = bytes[from..].iter().position(|&b| b == b'\n') else {
                self.searched = bytes.len();
                return Ok(false);
            };
            let end = from + at;
            let raw = &bytes[self.checked..end];
            self.checked = end + 1;
            self.lines += 1;
            let raw = if self.lines == 1 {
                raw.strip_prefix(BOM.as_bytes()).unwrap_or(raw)
            } else {
                raw
            };
            // Comments and statements are read whatever bytes follow their first word (a
            // comment in Latin-1, `o café` in CP1252), and split as further down the file (any
            // Unicode whitespace): bytes that are not UTF-8 read as U+FFFD, never a keyword.
            let text = String::from_utf8_lossy(raw);
            let line = text.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let word = line.split_whitespace().next().unwrap_or("");
            if word.contains('\u{fffd}') {
                return Err(not_obj(
                    self.lines,
                    "starts with bytes that are not UTF-8 text".into(),
                ));
            }
            if OBJ_KEYWORDS.contains(&word) {
                return Ok(true);
            }
            let shown_word = super::shown_word(word);
            return Err(not_obj(
                self.lines,
                format!("starts with '{shown_word}', which is no OBJ statement"),
            ));
        }
    }
}

/// Parses OBJ text; `path` is what messages call it.
pub(crate) fn parse_obj(
    path: &str,
    name: String,
    text: &str,
) -> Result<(Mesh, LoadReport), MeshError> {
    let text = text.strip_prefix(BOM).unwrap_or(text);
    let scan = Scan::run(path, text)?;
    let use_given_normals = scan.use_file_normals(path)?;

    let (positions, normals, p_idx, n_idx) = run_tobj(path, &scan.canonical)?;
    let expected: usize = scan.faces.iter().map(|f| f.corners - 2).sum();
    let consistent = p_idx.len() == expected * 3
        && (!use_given_normals || n_idx.len() == p_idx.len())
        && p_idx.iter().all(|&i| (i as usize) < positions.len())
        && (!use_given_normals || n_idx.iter().all(|&i| (i as usize) < normals.len()));
    if !consistent {
        return Err(parse_error(
            path,
            None,
            "could not be read consistently by the OBJ parser".into(),
        ));
    }
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(MeshError::NonFinite {
            path: path.into(),
            line: None,
            what: format!("coordinate of vertex {}", i + 1),
        });
    }

    let mut triangles = Vec::with_capacity(expected);
    // Lines of the polygons whose triangles do not cover them without turning over.
    let mut uncovered = Vec::new();
    let mut next = 0;
    for (face, info) in scan.faces.iter().enumerate() {
        // tobj's fan, corners (0, k-1, k) for k in 2..corners, back to the polygon's corners.
        let at = |k: usize| {
            if k < 3 {
                next + k
            } else {
                next + 3 * (k - 2) + 2
            }
        };
        let corner = |k: usize| (p_idx[at(k)], n_idx.get(at(k)).copied());
        let corners: Vec<(u32, Option<u32>)> = (0..info.corners).map(corner).collect();
        let shape: Vec<Vec3> = corners
            .iter()
            .map(|&(p, _)| positions[p as usize])
            .collect();
        let (split, covers) = super::polygon::triangulate(&shape);
        if !covers {
            uncovered.push(info.line);
        }
        for [a, b, c] in split {
            let p = [a, b, c].map(|k| corners[k].0);
            let n = if use_given_normals {
                [a, b, c].map(|k| corners[k].1.expect("checked: a normal per corner"))
            } else {
                p
            };
            let t = info.texcoords.as_ref().map(|t| [t[a], t[b], t[c]]);
            triangles.push(RawTriangle {
                p,
                n,
                t,
                face,
                line: Some(info.line),
            });
        }
        next += 3 * (info.corners - 2);
    }

    let polygons_triangulated = scan.faces.iter().filter(|f| f.corners > 3).count();
    let mut result = assemble(RawMesh {
        path: path.into(),
        name,
        positions,
        normals: use_given_normals.then_some(normals),
        triangles,
        texcoords: scan.texcoords,
        polygons_triangulated,
    })?;
    result.1.vertex_numbers = vertex_numbers(&result.0.positions, &scan.positions);
    result.1.uncovered_polygons = uncovered;
    log::debug!(
        "'{path}': {} vertices, {} triangles, normals {}",
        result.0.positions.len(),
        result.0.triangles.len(),
        if result.1.normals_computed {
            "computed"
        } else {
            "from the file"
        }
    );
    Ok(result)
}

/// For each welded position, the 1-based number of the first `v` statement that gives it (the
/// same bits after turning `-0.0` into `0.0`, as welding compares them).
fn vertex_numbers(welded: &[Vec3], file: &[Vec3]) -> Vec<usize> {
    let key = |p: Vec3| (p + Vec3::ZERO).to_array().map(f32::to_bits);
    let mut first: std::collections::HashMap<[u32; 3], usize> =
        std::collections::HashMap::with_capacity(file.len());
    for (i, &p) in file.iter().enumerate() {
        first.entry(key(p)).or_insert(i + 1);
    }
    welded
        .iter()
        .map(|&p| first.get(&key(p)).copied().unwrap_or(0))
        .collect()
}

type TobjOutput = (Vec<Vec3>, Vec<Vec3>, Vec<u32>, Vec<u32>);

/// Runs `tobj` on canonical text and merges its models: positions, normals, and per-corner
/// position and normal indices.
fn run_tobj(path: &str, canonical: &str) -> Result<TobjOutput, MeshError> {
    // Listing every field documents the choice; the update only covers fields that optional
    // tobj features add.
    #[allow(clippy::needless_update)]
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let (models, _materials) =
        tobj::load_obj_buf(&mut Cursor::new(canonical.as_bytes()), &options, |_| {
            Err(tobj::LoadError::OpenFileFailed)
        })
        .map_err(|e| {
            parse_error(
                path,
                None,
                format!("could not be read by the OBJ parser: {e}"),
            )
        })?;

    let (mut positions, mut normals, mut p_idx, mut n_idx) = (vec![], vec![], vec![], vec![]);
    let vec3s = |v: &[f32]| -> Vec<Vec3> { v.chunks_exact(3).map(Vec3::from_slice).collect() };
    for model in models {
        let m = model.mesh;
        let (p_base, n_base) = (positions.len() as u32, normals.len() as u32);
        positions.extend(vec3s(&m.positions));
        normals.extend(vec3s(&m.normals));
        p_idx.extend(m.indices.iter().map(|&i| p_base.saturating_add(i)));
        n_idx.extend(m.normal_indices.iter().map(|&i| n_base.saturating_add(i)));
    }
    Ok((positions, normals, p_idx, n_idx))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_support::{err, load, load_model, model_path, TRI};
    use crate::mesh::{DegenerateFace, MAX_OBJ_BYTES};

    /// The first-statement check searches each chunk once: a first line longer than many
    /// chunks (or a file with lone-CR line ends, which has no `\n` at all) is read in time
    /// proportional to its length, then checked whole.
    #[test]
    fn first_line_check_searches_each_byte_once() {
        let mut h = Head::default();
        let mut bytes = b"# ".to_vec();
        for _ in 0..4 {
            bytes.extend(std::iter::repeat_n(b'y', 1 << 16));
            assert!(!h.check("x", &bytes).unwrap());
            // Nothing before `searched` is searched again.
            assert_eq!((h.checked, h.searched), (0, bytes.len()));
        }
        bytes.extend_from_slice(b"\nv 0 0 0\n");
        assert!(h.check("x", &bytes).unwrap());
        assert_eq!(h.lines, 2);
    }

    #[test]
    fn loads_a_triangle() {
        let (mesh, report) = load(&format!("{TRI}f 1 2 3\n")).unwrap();
        assert_eq!(mesh.name, "x");
        assert_eq!(mesh.positions, vec![Vec3::ZERO, Vec3::X, Vec3::Y]);
        assert_eq!(mesh.normals, vec![Vec3::Z; 3]);
        assert_eq!(mesh.triangles.len(), 1);
        assert_eq!(mesh.triangles[0].p, mesh.triangles[0].n);
        assert!(report.normals_computed);
        assert_eq!(report.polygons_triangulated, 0);
        assert!(report.dropped_degenerate.is_empty());
    }

    #[test]
    fn missing_file_is_an_io_error() {
        let path = model_path("no_such_model.obj");
        let e = Mesh::load_obj(&path).unwrap_err();
        assert!(matches!(e, MeshError::Io { .. }));
        assert_eq!(
            e.to_string(),
            format!(
                "cannot read mesh file '{}': No such file or directory (os error 2)",
                path.display()
            )
        );
    }

    #[test]
    fn garbage_never_panics() {
        let long_face = format!("{TRI}f {}\n", "1 2 3 ".repeat(1000));
        let inputs: Vec<String> = vec![
            String::new(),
            "\n\n\n".into(),
            "# only a comment\n# another\n".into(),
            "hello world\nthis is not a mesh\n".into(),
            "\u{0}\u{1}\u{2}binary\u{ff}".into(),
            String::from_utf8_lossy(&[0x89, b'P', b'N', b'G', 13, 10, 26, 10, 0, 0]).into(),
            "v\nvn\nf\nvt\no\ng\ns\nusemtl\nmtllib\nl\np\n".into(),
            "f 1 2 3\n".into(),
            format!("{TRI}f 1 2 99\n"),
            "v nan 0 0\n".into(),
            "v inf 0 0\n".into(),
            format!("{TRI}f 0 1 2\n"),
            format!("{TRI}f 1 2\n"),
            format!("{TRI}vn 0 0 1\nf 1//-5 2//1 3//1\n"),
            format!("{TRI}vt 0 0\nf 1/-9 2/1 3/1\n"),
            format!("{TRI}vn 0 0 1\nf 1//1 2//1 3//7\n"),
            format!("{TRI}vn 0 0 1\nf 1//0 2//1 3//1\n"),
            format!("{TRI}f -9223372036854775808 1 2\n"),
            format!("{TRI}f 9223372036854775807 1 2\n"),
            format!("{TRI}f 1 2 3 # trailing comment\n"),
            "v 1e38 1e38 1e38\nv -1e38 -1e38 1e38\nv 1e38 -1e38 -1e38\nf 1 2 3\n".into(),
            "v 1e-45 0 0\nv 0 1e-45 0\nv 0 0 1e-45\nf 1 2 3\n".into(),
            "\r\n\r\nv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n".into(),
            long_face,
        ];
        for text in &inputs {
            let result = std::panic::catch_unwind(|| load(text));
            match result {
                Ok(Ok((m, _))) => {
                    assert!(!m.triangles.is_empty());
                    assert!(m.positions.iter().all(|p| p.is_finite()));
                    assert!(m.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-5));
                }
                Ok(Err(e)) => {
                    let msg = e.to_string();
                    assert!(msg.starts_with("'x.obj'"), "{msg}");
                    assert!(!msg.ends_with('.'), "{msg}");
                }
                Err(_) => panic!("panicked on {text:?}"),
            }
        }
    }

    #[test]
    fn mutated_files_never_panic() {
        // Deterministic mutations of a valid file with characters that matter to the parser.
        let base = std::fs::read_to_string(model_path("cube_tri.obj")).unwrap();
        let alphabet = b" \n/-+0123456789fvnte#.x\0";
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move |n: usize| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % n as u64) as usize
        };
        for _ in 0..3000 {
            let mut bytes = base.clone().into_bytes();
            for _ in 0..1 + next(4) {
                let at = next(bytes.len());
                let c = alphabet[next(alphabet.len())];
                match next(3) {
                    0 => bytes[at] = c,
                    1 => bytes.insert(at, c),
                    _ => {
                        bytes.remove(at);
                    }
                }
            }
            let text = String::from_utf8_lossy(&bytes).into_owned();
            let result = std::panic::catch_unwind(|| load(&text));
            match result {
                Ok(Ok((m, _))) => assert!(m.positions.iter().all(|p| p.is_finite())),
                Ok(Err(e)) => assert!(e.to_string().starts_with("'x.obj'")),
                Err(_) => panic!("panicked on {text:?}"),
            }
        }
    }

    /// A byte order mark before the first statement (Windows editors write one) is read past,
    /// not reported as an unknown statement.
    #[test]
    fn a_byte_order_mark_is_read_past() {
        let dir = std::env::temp_dir().join(format!("meshwork-bom-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("bom.obj");
        std::fs::write(&path, "\u{feff}v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        let loaded = Mesh::load_obj(&path);
        std::fs::remove_dir_all(&dir).ok();
        let (mesh, _) = loaded.unwrap();
        assert_eq!((mesh.positions.len(), mesh.triangles.len()), (3, 1));
    }

    #[test]
    fn binary_file_is_rejected() {
        let dir = std::env::temp_dir().join(format!("meshwork-bin-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("image.obj");
        std::fs::write(
            &path,
            [0x89, b'P', b'N', b'G', 13, 10, 26, 10, 0, 0, 0, 13, 0xff],
        )
        .unwrap();
        let e = Mesh::load_obj(&path).unwrap_err();
        std::fs::remove_dir_all(&dir).ok();
        // "\u{fffd}PNG\r\n", "\u{1a}\n", then the NUL bytes on line 3.
        assert!(matches!(e, MeshError::Parse { line: Some(3), .. }), "{e}");
    }

    #[test]
    fn only_regular_files_of_bounded_size_are_read() {
        let dir = std::env::temp_dir().join(format!("meshwork-kinds-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let msg = |p: &Path| Mesh::load_obj(p).unwrap_err().to_string();
        let d = dir.display();
        assert_eq!(
            msg(&dir),
            format!("'{d}' is a directory, not a regular file: only OBJ files are read")
        );
        assert!(msg(Path::new("/dev/zero")).contains("is a character device"));
        // A FIFO is refused from its metadata: opening it would block until a writer comes.
        let fifo = dir.join("f.obj");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            assert!(
                msg(&fifo).contains("is a FIFO (named pipe)"),
                "{}",
                msg(&fifo)
            );
        }
        // Over the size limit: refused from the size (a sparse file: nothing is written).
        let big = dir.join("big.obj");
        std::fs::File::create(&big)
            .unwrap()
            .set_len(MAX_OBJ_BYTES + 1)
            .unwrap();
        assert!(matches!(
            Mesh::load_obj(&big),
            Err(MeshError::FileTooLarge { size, .. }) if size == MAX_OBJ_BYTES + 1
        ));
        // A NUL byte past the first chunk stops reading there, with its line.
        let mut text = format!("{TRI}f 1 2 3\n").repeat(20_000).into_bytes();
        let at = text.len() - 3;
        text[at] = 0;
        let nul = dir.join("nul.obj");
        std::fs::write(&nul, &text).unwrap();
        assert!(
            matches!(
                Mesh::load_obj(&nul),
                Err(MeshError::Parse {
                    line: Some(80_000),
                    ..
                })
            ),
            "{}",
            msg(&nul)
        );
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn normals_from_the_file() {
        let text = format!("{TRI}vn 0 0 2\nf 1//1 2//1 3//1\n");
        let (m, report) = load(&text).unwrap();
        assert!(!report.normals_computed);
        assert_eq!(m.normals, vec![Vec3::Z]);
        assert_eq!(m.triangles[0].n, [0, 0, 0]);

        let text = format!("{TRI}vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/-1\n");
        let (m, report) = load(&text).unwrap();
        assert!(!report.normals_computed);
        assert_eq!(m.triangles[0].n, [0, 0, 0]);
    }

    #[test]
    fn texture_coordinates_are_loaded_per_corner() {
        // A quad fans into (1 2 3) and (1 3 4); the second face has no texture coordinates.
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n\
                    vt 0 0\nvt 1 0\nvt 1 1 0\nvt 0 1\nvt 0.5\n\
                    f 1/1 2/2 3/3 4/-2\nf 2 5 3\n";
        let (m, _) = load(text).unwrap();
        assert_eq!(m.texcoords.len(), 5);
        assert_eq!(m.texcoords[4], glam::Vec2::new(0.5, 0.0));
        let t: Vec<_> = m.triangles.iter().map(|t| t.t).collect();
        assert_eq!(t, vec![Some([0, 1, 2]), Some([0, 2, 3]), None]);
        // Without vt, nothing.
        let (m, _) = load(&format!("{TRI}f 1 2 3\n")).unwrap();
        assert!(m.texcoords.is_empty() && m.triangles[0].t.is_none());
    }

    #[test]
    fn partial_normals_are_recomputed() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 1 0 0\nf 1//1 2//1 3//1\nf 2 4 3\n";
        let (m, report) = load(text).unwrap();
        assert!(report.normals_computed);
        assert_eq!(m.normals, vec![Vec3::Z; 4]);
        // Missing on one corner only is partial too.
        let (_, report) = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 1 0 0\nf 1//1 2 3//1\n").unwrap();
        assert!(report.normals_computed);
    }

    #[test]
    fn objects_and_groups_merge_and_polygons_triangulate() {
        let text = "o a\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl red\nf 1 2 3 4\n\
                    g b\nv 2 0 0\nv 2 1 0\nl 2 5 6\nf 2 5 6 3\np 1\no c\nv 3 0 0\nf 5 7 6\n";
        let (m, report) = load(text).unwrap();
        assert_eq!(m.triangles.len(), 5);
        assert_eq!(m.positions.len(), 7);
        assert_eq!(report.polygons_triangulated, 2);
        let s = m.stats();
        assert_eq!(s.vertices, 7);
        assert!(s.is_manifold());
        assert_eq!(s.inconsistently_oriented_edges, 0);
    }

    #[test]
    fn duplicate_vertices_are_welded() {
        // Two triangles with their own copies of the shared edge, -0 vs 0 included.
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -0 0 0\nv 0 1 0\nv -1 0 0\nf 1 2 3\nf 4 5 6\n";
        let (m, _) = load(text).unwrap();
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.stats().boundary_edges, 4);
    }

    /// Far from the origin, vertices 0.005 apart in the file are one f32 point: the face
    /// through both is dropped as having two corners at one point, not as repeating an index.
    #[test]
    fn corners_single_precision_merges_are_named() {
        let text =
            "v 1000000 0 0\nv 1000000.005 0 0\nv 1000000 1 0\nv 1000001 0 0\nf 1 2 3\nf 1 4 3\n";
        let (m, report) = load(text).unwrap();
        assert_eq!(m.positions.len(), 3);
        let reasons: Vec<_> = report.dropped_degenerate.iter().map(|d| d.reason).collect();
        assert_eq!(reasons, [crate::mesh::COINCIDENT_CORNERS]);
    }

    #[test]
    fn degenerate_faces_are_dropped_and_reported() {
        let (mesh, report) = load_model("degenerate_faces.obj");
        let want = |face, line, reason| DegenerateFace {
            face,
            line: Some(line),
            reason,
        };
        assert_eq!(
            report.dropped_degenerate,
            vec![
                want(18, 40, "has zero area"),
                want(19, 41, "has zero area"),
                want(20, 42, "repeats a vertex index"),
            ]
        );
        assert_eq!(mesh.triangles.len(), 18);
        let path = model_path("degenerate_faces.obj");
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(text.lines().nth(41), Some("f 6 6 7"));
    }

    #[test]
    fn duplicate_triangles_are_dropped_in_any_rotation_or_orientation() {
        // Vertex 4 repeats vertex 1's position (welded), so `f 4 2 3` is `f 1 2 3` again.
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 0\nv 0 0 1\nf 1 2 3\nf 2 3 1\nf 1 3 2\nf 4 2 3\nf 1 2 5\n";
        let (mesh, report) = load(text).unwrap();
        assert_eq!(mesh.triangles.len(), 2);
        let dup = |face, line| DegenerateFace {
            face,
            line: Some(line),
            reason: "repeats the three vertices of an earlier face",
        };
        assert_eq!(
            report.dropped_degenerate,
            vec![dup(1, 7), dup(2, 8), dup(3, 9)]
        );
        // Kept faces keep their lines; welded positions are numbered by their first `v`.
        assert_eq!(report.triangle_lines, [6, 10]);
        assert_eq!(report.vertex_numbers, [1, 2, 3, 5]);
        assert_eq!(report.vertex(3), "vertex 5");
        assert_eq!(report.face(1), "the face at line 10");
    }

    #[test]
    fn all_faces_degenerate_is_an_empty_mesh() {
        assert_eq!(
            err("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n"),
            "'x.obj' contains no triangles that can be drawn: all 2 are degenerate (the first, at line 4, has zero area)"
        );
    }

    #[test]
    fn split_normals_are_kept() {
        let (m, report) = load_model("cylinder_hard_normals.obj");
        assert!(!report.normals_computed);
        assert_eq!(m.positions.len(), 50);
        assert!(m.normals.len() >= 3);
        // Some position is used with two different normals (the rims).
        let mut seen = std::collections::HashMap::new();
        let mut split = false;
        for t in &m.triangles {
            for k in 0..3 {
                let n = m.normals[t.n[k] as usize];
                let first = *seen.entry(t.p[k]).or_insert(n);
                split |= (first - n).length() > 1e-3;
            }
        }
        assert!(split);
    }

    #[test]
    fn every_model_loads_with_unit_normals() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/models");
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "obj") {
                let (m, report) = Mesh::load_obj(&path).unwrap_or_else(|e| panic!("{e}"));
                let has_vn = std::fs::read_to_string(&path).unwrap().contains("\nvn ");
                assert_eq!(report.normals_computed, !has_vn, "{}", path.display());
                assert!(m.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-5));
                for t in &m.triangles {
                    assert!(t.p.iter().all(|&i| (i as usize) < m.positions.len()));
                    assert!(t.n.iter().all(|&i| (i as usize) < m.normals.len()));
                }
            }
        }
    }
}
