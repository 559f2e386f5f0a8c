//! Turning validated raw geometry into a [`Mesh`]: welding, dropping degenerate triangles,
//! and choosing or computing normals. Shared by the OBJ loader and [`Mesh::from_parts`].

use std::collections::{HashMap, HashSet};

use glam::{Vec2, Vec3};

use super::normals::{compute_area_weighted_normals, corners, degenerate_reason, unit};
use super::{DegenerateFace, LoadReport, Mesh, MeshError, Triangle, FALLBACK_NORMAL, MAX_INDICES};

/// A triangle before welding, with where it came from.
pub(crate) struct RawTriangle {
    /// Indices into the raw positions.
    pub p: [u32; 3],
    /// Indices into the given normals (ignored when normals are computed).
    pub n: [u32; 3],
    /// Indices into the texture coordinates, if the face has them.
    pub t: Option<[u32; 3]>,
    /// 0-based face index in file (or input) order.
    pub face: usize,
    /// 1-based line of the face, for OBJ input.
    pub line: Option<usize>,
}

/// Geometry that the caller has already validated: finite positions, indices in range,
/// given normals finite and non-zero, counts within [`MAX_INDICES`].
pub(crate) struct RawMesh {
    /// What errors and warnings call the input (the path as displayed).
    pub path: String,
    pub name: String,
    pub positions: Vec<Vec3>,
    /// `Some` to keep these normals (indexed by [`RawTriangle::n`]), `None` to compute them.
    pub normals: Option<Vec<Vec3>>,
    pub triangles: Vec<RawTriangle>,
    /// Indexed by [`RawTriangle::t`] (validated).
    pub texcoords: Vec<Vec2>,
    pub polygons_triangulated: usize,
}

/// Welds, drops degenerate and duplicate triangles (with a debug line each), and sets up
/// normals.
pub(crate) fn assemble(raw: RawMesh) -> Result<(Mesh, LoadReport), MeshError> {
    let path = raw.path;
    let (positions, remap) = weld(&raw.positions);
    let mut dropped = Vec::new();
    let mut triangles = Vec::with_capacity(raw.triangles.len());
    let mut triangle_lines = Vec::new();
    // The vertex sets of the triangles kept so far: a triangle on the same three vertices as an
    // earlier one (any rotation or orientation) adds nothing but overdraw and, for Loop, an
    // edge shared by more than two faces after one step.
    let mut seen: HashSet<[u32; 3]> = HashSet::with_capacity(raw.triangles.len());
    for t in &raw.triangles {
        let p = t.p.map(|i| remap[i as usize]);
        let repeats = |q: [u32; 3]| q[0] == q[1] || q[1] == q[2] || q[2] == q[0];
        let reason = if repeats(t.p) {
            Some("repeats a vertex index")
        } else if repeats(p) {
            // Distinct vertices of the file at one point: equal coordinates, or ones that only
            // single precision makes equal (a mesh far from the origin).
            Some(super::COINCIDENT_CORNERS)
        } else {
            match corners(&positions, p) {
                Some([a, b, c]) => degenerate_reason(a, b, c),
                None => Some("has zero area"),
            }
        };
        let reason = reason.or_else(|| {
            let mut key = p;
            key.sort_unstable();
            (!seen.insert(key)).then_some(super::DUPLICATE_FACE)
        });
        match reason {
            Some(reason) => {
                // One line per face only at debug level: a file can hold millions of them.
                // Callers summarize `LoadReport::dropped_degenerate` (see `DegenerateFace`).
                let at = t.line.map_or(String::new(), |l| format!(" at line {l}"));
                log::debug!(
                    "'{path}': dropping face {} (0-based){at}: it {reason}",
                    t.face
                );
                dropped.push(DegenerateFace {
                    face: t.face,
                    line: t.line,
                    reason,
                });
            }
            None => {
                triangles.push(Triangle { p, n: t.n, t: t.t });
                triangle_lines.extend(t.line);
            }
        }
    }
    if let Some(first) = dropped.first().filter(|_| triangles.is_empty()) {
        return Err(MeshError::NoDrawableTriangles {
            path,
            count: dropped.len(),
            first: first.describe(),
        });
    }

    if triangle_lines.len() != triangles.len() {
        triangle_lines.clear();
    }
    let normals_computed = raw.normals.is_none();
    let normals = match raw.normals {
        Some(given) => given
            .into_iter()
            .map(|n| unit(n).unwrap_or(FALLBACK_NORMAL))
            .collect(),
        None => {
            let tris: Vec<[u32; 3]> = triangles.iter().map(|t| t.p).collect();
            for t in &mut triangles {
                t.n = t.p;
            }
            compute_area_weighted_normals(&positions, &tris)
        }
    };
    debug_assert!(positions.len() <= MAX_INDICES);
    let mesh = Mesh {
        name: raw.name,
        positions,
        normals,
        triangles,
        texcoords: raw.texcoords,
    };
    let report = LoadReport {
        dropped_degenerate: dropped,
        normals_computed,
        polygons_triangulated: raw.polygons_triangulated,
        triangle_lines,
        vertex_numbers: Vec::new(),
        uncovered_polygons: Vec::new(),
    };
    Ok((mesh, report))
}

/// [`Mesh::from_parts`]: validates, then assembles like the OBJ loader.
pub(crate) fn from_parts(
    name: &str,
    positions: Vec<Vec3>,
    normals: Option<Vec<Vec3>>,
    tris: Vec<[u32; 3]>,
) -> Result<(Mesh, LoadReport), MeshError> {
    let path = name.to_string();
    let corners = tris.len().saturating_mul(3);
    for (what, count) in [("vertices", positions.len()), ("triangle corners", corners)] {
        if count > MAX_INDICES {
            return Err(MeshError::TooLarge { path, what, count });
        }
    }
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(MeshError::NonFinite {
            path,
            line: None,
            what: format!("coordinate of vertex {i} (0-based)"),
        });
    }
    if let Some(normals) = &normals {
        if normals.len() != positions.len() {
            return Err(MeshError::BadNormal {
                path,
                line: None,
                msg: format!(
                    "{} normals are given for {} vertices",
                    normals.len(),
                    positions.len()
                ),
            });
        }
        if let Some(i) = normals.iter().position(|&n| unit(n).is_none()) {
            let n = normals[i];
            return Err(MeshError::BadNormal {
                path,
                line: None,
                msg: format!(
                    "normal {i} (0-based) ({}, {}, {}) is zero, NaN or infinite",
                    n.x, n.y, n.z
                ),
            });
        }
    }
    if let Some(&i) = tris
        .iter()
        .flatten()
        .find(|&&i| i as usize >= positions.len())
    {
        return Err(MeshError::IndexOutOfRange {
            path,
            line: None,
            index: i64::from(i),
            count: positions.len(),
        });
    }
    if tris.is_empty() {
        return Err(MeshError::EmptyMesh { path });
    }
    let triangles = tris
        .into_iter()
        .enumerate()
        .map(|(face, p)| RawTriangle {
            p,
            n: p,
            t: None,
            face,
            line: None,
        })
        .collect();
    assemble(RawMesh {
        path,
        name: mesh_name(name),
        positions,
        normals,
        triangles,
        texcoords: Vec::new(),
        polygons_triangulated: 0,
    })
}

/// Merges exactly equal positions (bitwise, after turning -0.0 into 0.0), keeping the order
/// of first occurrence. Returns the unique positions and the old-to-new index map.
pub(crate) fn weld(positions: &[Vec3]) -> (Vec<Vec3>, Vec<u32>) {
    let mut unique = Vec::with_capacity(positions.len());
    let mut index: HashMap<[u32; 3], u32> = HashMap::with_capacity(positions.len());
    let remap = positions
        .iter()
        .map(|&p| {
            // Adding +0.0 turns -0.0 into +0.0 and leaves every other value unchanged.
            let p = p + Vec3::ZERO;
            let key = p.to_array().map(f32::to_bits);
            *index.entry(key).or_insert_with(|| {
                unique.push(p);
                (unique.len() - 1) as u32
            })
        })
        .collect();
    (unique, remap)
}

/// The mesh name for a path or name: its file stem, or "default" when it has none.
pub(crate) fn mesh_name(path: &str) -> String {
    std::path::Path::new(path)
        .file_stem()
        .and_then(|s| s.to_str())
        .filter(|s| !s.is_empty())
        .unwrap_or("default")
        .to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weld_merges_exact_duplicates_and_signed_zeros() {
        let p = [
            Vec3::new(0.0, 1.0, 2.0),
            Vec3::new(-0.0, 1.0, 2.0),
            Vec3::new(0.0, 1.0, 2.000_000_2),
            Vec3::new(0.0, 1.0, 2.0),
        ];
        let (unique, remap) = weld(&p);
        assert_eq!(unique.len(), 2);
        assert_eq!(remap, vec![0, 0, 1, 0]);
        assert!(unique[0].x.is_sign_positive());
    }

    #[test]
    fn names_are_file_stems() {
        assert_eq!(mesh_name("/a/b/spot.obj"), "spot");
        assert_eq!(mesh_name("spot"), "spot");
        assert_eq!(mesh_name(""), "default");
        assert_eq!(mesh_name("/"), "default");
        assert_eq!(mesh_name(".."), "default");
    }

    fn raw(positions: Vec<Vec3>, tris: &[[u32; 3]]) -> RawMesh {
        RawMesh {
            path: "t".into(),
            name: "t".into(),
            positions,
            normals: None,
            triangles: tris
                .iter()
                .enumerate()
                .map(|(face, &p)| RawTriangle {
                    p,
                    n: p,
                    t: None,
                    face,
                    line: None,
                })
                .collect(),
            texcoords: Vec::new(),
            polygons_triangulated: 0,
        }
    }

    #[test]
    fn welding_can_make_a_face_degenerate() {
        // Vertices 1 and 3 coincide, so face 1 has two corners at one point after welding.
        let p = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::X, Vec3::Z];
        let (mesh, report) = assemble(raw(p, &[[0, 1, 2], [0, 1, 3], [0, 2, 4]])).unwrap();
        assert_eq!(mesh.positions.len(), 4);
        assert_eq!(mesh.triangles.len(), 2);
        assert_eq!(
            report.dropped_degenerate,
            vec![DegenerateFace {
                face: 1,
                line: None,
                reason: crate::mesh::COINCIDENT_CORNERS
            }]
        );
        assert!(report.normals_computed);
        assert!(mesh.triangles.iter().all(|t| t.n == t.p));
    }

    #[test]
    fn from_parts_validates() {
        let p = || vec![Vec3::ZERO, Vec3::X, Vec3::Y];
        let msg = |r: Result<(Mesh, LoadReport), MeshError>| r.unwrap_err().to_string();
        assert_eq!(
            msg(from_parts("m", p(), None, vec![[0, 1, 3]])),
            "'m': a triangle refers to vertex index 3 but only 3 vertices exist"
        );
        assert_eq!(
            msg(from_parts("m", p(), None, vec![])),
            "'m' contains no triangles"
        );
        let mut bad = p();
        bad[2].y = f32::NAN;
        assert_eq!(
            msg(from_parts("m", bad, None, vec![[0, 1, 2]])),
            "'m': coordinate of vertex 2 (0-based) is not finite in f32 (NaN, infinite, or beyond about ±3.4e38)"
        );
        assert_eq!(
            msg(from_parts(
                "m",
                p(),
                Some(vec![Vec3::Z; 2]),
                vec![[0, 1, 2]]
            )),
            "'m': 2 normals are given for 3 vertices"
        );
        assert_eq!(
            msg(from_parts(
                "m",
                p(),
                Some(vec![Vec3::Z, Vec3::ZERO, Vec3::Z]),
                vec![[0, 1, 2]]
            )),
            "'m': normal 1 (0-based) (0, 0, 0) is zero, NaN or infinite"
        );
    }

    #[test]
    fn from_parts_keeps_given_normals_per_original_position() {
        // Positions 1 and 3 coincide but carry different normals (a hard edge).
        let p = vec![
            Vec3::ZERO,
            Vec3::X,
            Vec3::Y,
            Vec3::X,
            Vec3::new(1.0, 0.0, -1.0),
        ];
        let n = vec![Vec3::Z * 3.0, Vec3::Z, Vec3::Z, -Vec3::Y, -Vec3::Y];
        let (mesh, report) =
            from_parts("parts.obj", p, Some(n), vec![[0, 1, 2], [0, 4, 3]]).unwrap();
        assert_eq!(mesh.name, "parts");
        assert!(!report.normals_computed);
        assert_eq!(mesh.positions.len(), 4);
        assert_eq!(mesh.triangles[1].p, [0, 3, 1]);
        assert_eq!(mesh.triangles[1].n, [0, 4, 3]);
        assert_eq!(mesh.normals[0], Vec3::Z);
        assert_eq!(mesh.normals[mesh.triangles[1].n[2] as usize], -Vec3::Y);
    }

    #[test]
    fn all_degenerate_is_empty() {
        let p = vec![Vec3::ZERO, Vec3::X, Vec3::X * 2.0];
        let err = assemble(raw(p, &[[0, 1, 2]])).unwrap_err();
        assert_eq!(
            err.to_string(),
            "'t' contains no triangles that can be drawn: all 1 are degenerate (the first, face 0, has zero area)"
        );
    }
}
