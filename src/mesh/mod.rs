//! Triangle meshes: loading (Wavefront OBJ), validation, normals and topology statistics.
//!
//! # Design
//!
//! A [`Mesh`] is an indexed triangle mesh with separate index sets for positions and
//! normals, so that a vertex can carry several normals (hard edges) while its position is
//! shared by every triangle around it, which is what subdivision and adjacency need. It is
//! built only through [`Mesh::load_obj`], [`Mesh::from_obj_str`], [`Mesh::from_parts`] and
//! [`default_mesh`], which all run the same pipeline:
//!
//! 1. validate the input (OBJ text is pre-scanned line by line, see `scan.rs`, so every error
//!    names its file and line; `tobj` then parses canonical text and triangulates polygons
//!    as fans);
//! 2. weld: positions that are bitwise equal (after turning `-0.0` into `0.0`) become one
//!    index, in order of first use;
//! 3. drop degenerate triangles, those that repeat a position index after welding, or the
//!    three positions of an earlier triangle (in any rotation or orientation), or whose
//!    area is zero (`|cross| <= 1e-12 * longest_edge^2`), or whose area or an edge is not
//!    representable as a normal `f32` (twice the area below `f32::MIN_POSITIVE` or above
//!    `f32::MAX`), each with a `log::debug!` and an entry in
//!    [`LoadReport::dropped_degenerate`] (callers summarize them); if none is left the load
//!    fails with [`MeshError::NoDrawableTriangles`];
//! 4. normals: an OBJ whose every face corner has a `vn` keeps those (normalized); otherwise
//!    (none, or only some faces, which also logs a warning) area-weighted vertex normals are
//!    computed per welded position.
//!
//! # Invariants of a loaded mesh
//!
//! - at least one triangle; every `p` index is `< positions.len()`, every `n` index is
//!   `< normals.len()`, every `t` index is `< texcoords.len()`, and all indices are at most `u32::MAX / 2` ([`MAX_INDICES`]);
//! - positions are finite and unique; normals are finite and unit length;
//! - no triangle repeats a position index or has zero area;
//! - when normals were computed, `normals.len() == positions.len()` and `n == p` for every
//!   triangle;
//! - positions used by no triangle may remain (from [`Mesh::from_parts`]);
//!   [`MeshStats::vertices`] counts only the positions used by at least one triangle.
//!
//! Loading does not require a manifold; techniques that do call [`Mesh::require_manifold`].
//! Errors are single lower-case sentences naming the file and, where possible, the line.

#![forbid(unsafe_code)]

mod animate;
mod error;
pub mod generate;
mod intersect;
mod normals;
mod obj;
mod polygon;
pub use polygon::MAX_CLIPPED_CORNERS;
mod scan;
mod split;
mod topology;
mod weld;

use std::collections::BTreeMap;
use std::path::Path;

use glam::{Vec2, Vec3};

pub use error::{shown_word, MeshError, MAX_INDICES, MAX_OBJ_BYTES};
pub use normals::{compute_area_weighted_normals, FALLBACK_NORMAL};
pub use topology::{mesh_stats, pieces};

/// Welded triangle mesh. Positions are unique (welded: exactly-equal positions merged to one
/// index). See the module documentation for the invariants.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// File stem, or "default" when the path has none.
    pub name: String,
    /// Unique, finite vertex positions.
    pub positions: Vec<Vec3>,
    /// Unit length.
    pub normals: Vec<Vec3>,
    /// At least one; none degenerate.
    pub triangles: Vec<Triangle>,
    /// Texture coordinates `(u, v)` from the file's `vt` lines (finite), indexed by
    /// [`Triangle::t`]; empty when the input has none.
    pub texcoords: Vec<Vec2>,
}

/// One triangle: position indices and normal indices per corner, in input order
/// (counter-clockwise seen from the front, by OBJ convention).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Triangle {
    /// Indices into [`Mesh::positions`].
    pub p: [u32; 3],
    /// Indices into [`Mesh::normals`].
    pub n: [u32; 3],
    /// Indices into [`Mesh::texcoords`], when every corner of the face gave one.
    pub t: Option<[u32; 3]>,
}

/// What loading did besides building the mesh.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LoadReport {
    /// Degenerate triangles that were left out, in input order.
    pub dropped_degenerate: Vec<DegenerateFace>,
    /// Whether the normals were computed (true) or taken from the input (false).
    pub normals_computed: bool,
    /// Faces with more than three corners that were split into triangles.
    pub polygons_triangulated: usize,
    /// Lines of the polygons whose triangles may overlap or turn over (src/mesh/polygon.rs:
    /// a polygon crossing or touching itself, or concave with more corners than are clipped).
    pub uncovered_polygons: Vec<usize>,
    /// For OBJ input, the line of each kept triangle's face, indexed like [`Mesh::triangles`]
    /// (empty otherwise): messages name faces as the file does.
    pub triangle_lines: Vec<usize>,
    /// For OBJ input, the 1-based number of the first `v` statement that gave each welded
    /// position, indexed like [`Mesh::positions`] (empty otherwise): messages name vertices
    /// as the file numbers them.
    pub vertex_numbers: Vec<usize>,
}

impl LoadReport {
    /// "vertex 7" in the file's numbering (or "vertex 6 (0-based)" without one).
    pub fn vertex(&self, v: u32) -> String {
        match self.vertex_numbers.get(v as usize) {
            Some(n) => format!("vertex {n}"),
            None => format!("vertex {v} (0-based)"),
        }
    }

    /// "the face at line 12" (or "triangle 3 (0-based)" without lines).
    pub fn face(&self, t: usize) -> String {
        match self.triangle_lines.get(t) {
            Some(l) => format!("the face at line {l}"),
            None => format!("triangle {t} (0-based)"),
        }
    }
}

/// [`DegenerateFace::reason`] of a triangle on the same three vertices as an earlier one.
pub const DUPLICATE_FACE: &str = "repeats the three vertices of an earlier face";

/// Why a face whose corners are distinct vertices of the file but lie at one point (equal
/// coordinates, welded into one vertex) is dropped; far from the origin, coordinates a little
/// apart in the file can be one single-precision number.
pub const COINCIDENT_CORNERS: &str =
    "has two corners at one point (their coordinates are equal in single precision)";

/// A triangle dropped because it is degenerate. A polygon's fan triangles share its `face`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DegenerateFace {
    /// 0-based face index in file order (triangle index for [`Mesh::from_parts`]).
    pub face: usize,
    /// 1-based line of the face in the OBJ text.
    pub line: Option<usize>,
    /// "repeats a vertex index", [`COINCIDENT_CORNERS`], "has zero area" (or is a sliver too
    /// thin to draw: twice its area at most `1e-12` of its longest edge squared), or that its area is
    /// not representable in `f32` ("has an area too small for f32 (it underflows)", "has an
    /// area or edge too large for f32 (it overflows)"), or "repeats the three vertices of an
    /// earlier face" (an exact duplicate in any rotation or orientation).
    pub reason: &'static str,
}

impl DegenerateFace {
    /// "at line 40, has zero area" (or "face 18, ..." without a line), for messages.
    pub fn describe(&self) -> String {
        match self.line {
            Some(l) => format!("at line {l}, {}", self.reason),
            None => format!("face {}, {}", self.face, self.reason),
        }
    }
}

/// Topology statistics, see [`Mesh::stats`] and [`mesh_stats`] for the definitions.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MeshStats {
    /// Positions used by at least one triangle.
    pub vertices: usize,
    /// Number of triangles.
    pub triangles: usize,
    /// Distinct edges (unordered position-index pairs).
    pub edges: usize,
    /// Edges used by exactly one triangle.
    pub boundary_edges: usize,
    /// Edges used by more than two triangles.
    pub nonmanifold_edges: usize,
    /// Vertices whose triangles do not form one edge-connected fan, or that lie on a
    /// non-manifold edge.
    pub nonmanifold_vertices: usize,
    /// Interior edges that both of their triangles traverse in the same direction.
    pub inconsistently_oriented_edges: usize,
    /// Vertices on at least one boundary edge.
    pub boundary_vertices: usize,
    /// Valence (number of distinct neighbouring vertices) -> number of vertices.
    pub valence_histogram: BTreeMap<u32, usize>,
    /// The same over interior vertices only (those on no boundary edge).
    pub interior_valence_histogram: BTreeMap<u32, usize>,
}

impl Mesh {
    /// Loads a Wavefront OBJ file (all objects and groups merged into one mesh).
    pub fn load_obj(path: &Path) -> Result<(Mesh, LoadReport), MeshError> {
        obj::load_obj(path)
    }

    /// Parses OBJ text. `name` is used in messages like a path, and its file stem names the
    /// mesh.
    pub fn from_obj_str(name: &str, text: &str) -> Result<(Mesh, LoadReport), MeshError> {
        obj::parse_obj(name, weld::mesh_name(name), text)
    }

    /// Builds a mesh from raw arrays with the same validation, welding and degenerate-face
    /// handling as loading. `normals`, if given, has one entry per position (indices of
    /// `tris` then index them too, and survive welding); otherwise normals are computed.
    /// Indices are 0-based.
    pub fn from_parts(
        name: &str,
        positions: Vec<Vec3>,
        normals: Option<Vec<Vec3>>,
        tris: Vec<[u32; 3]>,
    ) -> Result<(Mesh, LoadReport), MeshError> {
        weld::from_parts(name, positions, normals, tris)
    }

    /// Topology statistics (computed on demand, O(triangles)).
    pub fn stats(&self) -> MeshStats {
        mesh_stats(self.positions.len(), &self.position_indices())
    }

    /// The volume the triangles enclose, signed: positive when they wind counter-clockwise seen
    /// from outside (their normals point outwards), negative for an inside-out mesh. Meaningful
    /// for a closed, consistently oriented mesh; summed in f64 about the bounds' centre.
    pub fn signed_volume(&self) -> f64 {
        self.piece_volumes().iter().sum()
    }

    /// [`Mesh::signed_volume`] of each connected piece ([`pieces`]), in their order.
    pub fn piece_volumes(&self) -> Vec<f64> {
        let (lo, hi) = self.bounds();
        let c = ((lo + hi) * 0.5).as_dvec3();
        let at = |i: u32| {
            self.positions
                .get(i as usize)
                .map_or(glam::DVec3::ZERO, |p| p.as_dvec3() - c)
        };
        let tris = self.position_indices();
        let piece = pieces(self.positions.len(), &tris);
        let mut volumes = vec![0.0f64; piece.iter().map(|&p| p as usize + 1).max().unwrap_or(0)];
        for (t, &k) in tris.iter().zip(&piece) {
            volumes[k as usize] += at(t[0]).dot(at(t[1]).cross(at(t[2]))) / 6.0;
        }
        volumes
    }

    /// Closed, consistently oriented and every connected piece wound outwards (a positive
    /// [`Mesh::piece_volumes`]): only such a mesh hides the faces that face away from an eye
    /// outside it, so only there does adaptive drawing cull them (`render::Scene::closed`, and
    /// `info`'s report), and only while the eye is outside it ([`Mesh::winding_number`],
    /// `lod::cull::eye_outside`). A mesh with an inside-out piece shows that piece's faces
    /// that face away.
    pub fn closed_outward(&self) -> bool {
        let stats = self.stats();
        stats.is_closed()
            && stats.inconsistently_oriented_edges == 0
            && self.piece_volumes().iter().all(|&v| v > 0.0)
    }

    /// Whether every corner's normal points out of the surface as the winding says: a
    /// non-negative dot product with its face's normal from the winding, or with its vertex's
    /// area-weighted normal (the faces around the vertex, wound). Computed normals always do;
    /// a file's may point inwards, which fails both. Either suffices: where a closed surface
    /// folds sharply (Spot's ears, say) a smooth normal may point against a steep face of its
    /// own, and at a sharp edge (a wedge, a thin shell) a face's own normal may point against
    /// its vertex's average. With
    /// [`Mesh::closed_outward`], the normals then point out of the surface, so the side of a
    /// triangle the eye sees says on which side of the surface it is (the fragment stage's
    /// lighting: `render::FrameUniforms::light_dir`).
    pub fn normals_point_out(&self) -> bool {
        let outward =
            normals::compute_area_weighted_normals(&self.positions, &self.position_indices());
        self.triangles.iter().all(|t| {
            let [a, b, c] = t.p.map(|i| self.positions[i as usize]);
            let face = (b - a).cross(c - a);
            t.p.iter().zip(&t.n).all(|(&p, &n)| {
                let out = outward.get(p as usize).copied().unwrap_or(Vec3::ZERO);
                self.normals
                    .get(n as usize)
                    .is_some_and(|n| n.dot(face) >= 0.0 || n.dot(out) >= 0.0)
            })
        })
    }

    /// The generalized winding number of the triangles about `p`: the signed solid angle they
    /// subtend at `p` over 4π (A. van Oosterom and J. Strackee's formula, in f64). For a closed
    /// mesh wound outwards: 0 outside, 1 inside (an integer up to rounding away from the
    /// surface; -1 inside an inside-out mesh).
    pub fn winding_number(&self, p: Vec3) -> f64 {
        let p = p.as_dvec3();
        let at = |i: u32| {
            self.positions
                .get(i as usize)
                .map_or(glam::DVec3::ZERO, |q| q.as_dvec3() - p)
        };
        let total: f64 = self
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.p.map(at);
                let (la, lb, lc) = (a.length(), b.length(), c.length());
                let det = a.dot(b.cross(c));
                let div = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
                2.0 * det.atan2(div)
            })
            .sum();
        total / (4.0 * std::f64::consts::PI)
    }

    /// Whether two triangles meet other than along a shared edge or at a shared corner
    /// (`src/mesh/intersect.rs`): a closed mesh that does may show faces facing away from an
    /// eye outside it, so culling them is off for such a `flat` surface.
    pub fn self_intersects(&self) -> bool {
        intersect::self_intersects(&self.positions, &self.position_indices())
    }

    /// The position indices of every triangle (e.g. for an index buffer).
    pub fn position_indices(&self) -> Vec<[u32; 3]> {
        self.triangles.iter().map(|t| t.p).collect()
    }

    /// Axis-aligned bounds `(min, max)` of the positions used by triangles (of all
    /// positions if no triangle uses any; `(0, 0)` for no positions).
    pub fn bounds(&self) -> (Vec3, Vec3) {
        let used = self
            .triangles
            .iter()
            .flat_map(|t| t.p)
            .filter_map(|i| self.positions.get(i as usize));
        let (lo, hi) = used.fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
        if lo.cmple(hi).all() {
            return (lo, hi);
        }
        let (lo, hi) = self
            .positions
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        if lo.cmple(hi).all() {
            (lo, hi)
        } else {
            (Vec3::ZERO, Vec3::ZERO)
        }
    }

    /// Half the diagonal of [`Mesh::bounds`] (the radius the camera frames).
    pub fn bounding_radius(&self) -> f32 {
        let (lo, hi) = self.bounds();
        ((hi - lo) * 0.5).length()
    }

    /// The transform of [`Mesh::for_viewing`]: drawn = (mesh − centre) · scale.
    pub fn viewing_transform(&self) -> (glam::DVec3, f64) {
        let (lo, hi) = self.bounds();
        let (lo, hi) = (lo.as_dvec3(), hi.as_dvec3());
        let centre = (lo + hi) * 0.5;
        let radius = ((hi - lo) * 0.5).length();
        let scale = if radius > 0.0 && radius.is_finite() {
            1.0 / radius
        } else {
            1.0
        };
        (centre, scale)
    }

    /// A copy for drawing: translated and scaled, in `f64`, so that the bounding box's centre
    /// is the origin and its half diagonal is 1. An image is the same for a mesh and a camera
    /// moved together, but the GPU's single-precision view transform is not: a unit mesh at
    /// 1e7 loses all its detail there, edges of 1e-5 or 1e19 and coordinates near 3e38 leave
    /// `f32` range in the view and projection matrices. Normals (directions) are unchanged;
    /// triangles, texture coordinates and the name are kept.
    pub fn for_viewing(&self) -> Mesh {
        let (centre, scale) = self.viewing_transform();
        let mut out = self.clone();
        for p in &mut out.positions {
            *p = ((p.as_dvec3() - centre) * scale).as_vec3();
        }
        out
    }

    /// CPU deformation for the demo's animation: a travelling sine wave that moves each
    /// position by at most `amplitude` along its area-weighted vertex normal, periodic in
    /// `time` (seconds) with period 2 and deterministic. Triangles are unchanged. Normals are
    /// recomputed only if they were computed, which is recognized as `n == p` for every
    /// triangle and normals exactly equal to the area-weighted normals of the positions;
    /// normals from the input are kept as they are. A zero or non-finite `time` or
    /// `amplitude` returns an unchanged copy.
    pub fn animated(&self, time: f32, amplitude: f32) -> Mesh {
        animate::animated(self, time, amplitude)
    }

    /// The window demo's animation at `time`: [`Mesh::animated`] moving each position by at
    /// most [`WOBBLE`] times this mesh's [`Mesh::bounding_radius`], whatever its units.
    pub fn wobbled(&self, time: f32) -> Mesh {
        self.animated(time, WOBBLE * self.bounding_radius())
    }

    /// `Ok` if the mesh has no non-manifold edge or vertex, else [`MeshError::NonManifold`]
    /// (named by [`Mesh::name`]).
    pub fn require_manifold(&self) -> Result<(), MeshError> {
        let s = self.stats();
        if s.is_manifold() {
            Ok(())
        } else {
            Err(MeshError::NonManifold {
                path: self.name.clone(),
                edges: s.nonmanifold_edges,
                vertices: s.nonmanifold_vertices,
            })
        }
    }
}

/// The largest move of the window demo's animation ([`Mesh::wobbled`]), as a share of the
/// mesh's bounding radius.
pub const WOBBLE: f32 = 0.03;

/// The default model: the control mesh of "Spot" (Spot by Keenan Crane, released into the
/// public domain), triangulated, with area-weighted normals given in the file; 188
/// vertices, 372 triangles, closed. Embedded from `assets/models/spot_control_tri_vn.obj`
/// at compile time. Named "spot".
pub fn default_mesh() -> Mesh {
    const SPOT_OBJ: &str = include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/models/spot_control_tri_vn.obj"
    ));
    let (mut mesh, _) =
        Mesh::from_obj_str("spot_control_tri_vn.obj", SPOT_OBJ).expect("embedded mesh is valid");
    mesh.name = "spot".to_string();
    mesh
}

#[cfg(test)]
pub(crate) mod test_support {
    use super::{LoadReport, Mesh};
    use std::path::PathBuf;

    pub fn model_path(file: &str) -> PathBuf {
        PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/models")).join(file)
    }

    pub fn load_model(file: &str) -> (Mesh, LoadReport) {
        Mesh::load_obj(&model_path(file)).unwrap_or_else(|e| panic!("{e}"))
    }

    /// Three vertices of a unit right triangle, to prefix face lines with.
    pub const TRI: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

    /// Load OBJ text as if it were the file `x.obj`.
    pub fn load(text: &str) -> Result<(Mesh, LoadReport), super::MeshError> {
        Mesh::from_obj_str("x.obj", text)
    }

    /// The error message of OBJ text that must not load.
    pub fn err(text: &str) -> String {
        match load(text) {
            Ok(_) => panic!("{text:?} loaded"),
            Err(e) => e.to_string(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::test_support::load_model;
    use super::*;

    #[test]
    fn default_mesh_is_spot() {
        let mesh = default_mesh();
        assert_eq!(mesh.name, "spot");
        let s = mesh.stats();
        assert_eq!((s.vertices, s.triangles), (188, 372));
        assert!(s.is_closed());
        assert!(mesh.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-5));
        let (from_file, report) = load_model("spot_control_tri_vn.obj");
        assert!(!report.normals_computed);
        assert_eq!(mesh.positions, from_file.positions);
        assert_eq!(mesh.triangles, from_file.triangles);
    }

    #[test]
    fn names_come_from_file_stems() {
        assert_eq!(load_model("tetrahedron.obj").0.name, "tetrahedron");
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        assert_eq!(Mesh::from_obj_str("", text).unwrap().0.name, "default");
        assert_eq!(
            Mesh::from_obj_str("/tmp/a/thing.obj", text).unwrap().0.name,
            "thing"
        );
    }

    #[test]
    fn bounds_cover_used_positions() {
        let (mesh, _) = load_model("tetrahedron.obj");
        assert_eq!(mesh.bounds(), (Vec3::splat(-1.0), Vec3::splat(1.0)));
        let p = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::splat(100.0)];
        let (mesh, _) = Mesh::from_parts("m", p, None, vec![[0, 1, 2]]).unwrap();
        assert_eq!(mesh.bounds(), (Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0)));
        let empty = Mesh {
            name: "e".into(),
            positions: vec![],
            normals: vec![],
            triangles: vec![],
            texcoords: vec![],
        };
        assert_eq!(empty.bounds(), (Vec3::ZERO, Vec3::ZERO));
        assert_eq!(empty.stats(), MeshStats::default());
    }

    #[test]
    fn meshes_for_viewing_are_centred_with_unit_radius() {
        let tet = "v 1 1 1\nv -1 -1 1\nv -1 1 -1\nv 1 -1 -1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n";
        let (unit, _) = Mesh::from_obj_str("t.obj", tet).unwrap();
        let unit = unit.for_viewing();
        for (scale, offset) in [(1e-5, 0.0), (1.0, 1e7), (5e18, 0.0), (1e-18, 0.0)] {
            let text = tet
                .lines()
                .map(|l| match l.strip_prefix("v ") {
                    Some(v) => {
                        let c: Vec<f64> = v.split(' ').map(|x| x.parse().unwrap()).collect();
                        let f = |x: f64| (x * scale + offset) as f32;
                        format!("v {} {} {}\n", f(c[0]), f(c[1]), f(c[2]))
                    }
                    None => format!("{l}\n"),
                })
                .collect::<String>();
            let (mesh, report) = Mesh::from_obj_str("t.obj", &text).unwrap();
            assert!(report.dropped_degenerate.is_empty(), "{scale} {offset}");
            let viewed = mesh.for_viewing();
            let (lo, hi) = viewed.bounds();
            assert!(((lo + hi) * 0.5).length() < 1e-6, "{scale} {offset}");
            assert!(
                (((hi - lo) * 0.5).length() - 1.0).abs() < 1e-6,
                "{scale} {offset}"
            );
            for (a, b) in viewed.positions.iter().zip(&unit.positions) {
                assert!((*a - *b).length() < 1e-6, "{scale} {offset}: {a} vs {b}");
            }
            assert_eq!(viewed.normals, mesh.normals);
            assert_eq!(viewed.triangles, mesh.triangles);
        }
        // Near the largest f32: what differs is drawable, and comes out at unit size.
        let far = "v 3e38 1 1\nv 3e38 -1 1\nv 3e38 -1 -1\nf 1 2 3\n";
        let (lo, hi) = Mesh::from_obj_str("f.obj", far)
            .unwrap()
            .0
            .for_viewing()
            .bounds();
        assert_eq!(
            (lo, hi),
            (
                Vec3::new(0.0, -0.70710677, -0.70710677),
                Vec3::new(0.0, 0.70710677, 0.70710677)
            )
        );
    }

    #[test]
    fn computed_normals_point_outwards_on_closed_models() {
        for file in ["tetrahedron.obj", "icosahedron.obj", "uvsphere12.obj"] {
            let (mesh, report) = load_model(file);
            assert!(report.normals_computed);
            let (lo, hi) = mesh.bounds();
            let centre = (lo + hi) / 2.0;
            for t in &mesh.triangles {
                for k in 0..3 {
                    let p = mesh.positions[t.p[k] as usize];
                    assert!(
                        mesh.normals[t.n[k] as usize].dot(p - centre) > 0.0,
                        "{file}"
                    );
                }
            }
        }
    }

    #[test]
    fn signed_volume_is_the_enclosed_volume_negative_inside_out() {
        // The cube [0, 2]^3, wound counter-clockwise seen from outside: volume 8.
        let p: Vec<Vec3> = (0..8)
            .map(|i| Vec3::new((i & 1) as f32, (i >> 1 & 1) as f32, (i >> 2) as f32) * 2.0)
            .collect();
        let quads = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        let tris: Vec<[u32; 3]> = quads
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect();
        let flipped: Vec<[u32; 3]> = tris.iter().map(|t| [t[0], t[2], t[1]]).collect();
        let (cube, _) = Mesh::from_parts("cube", p.clone(), None, tris).unwrap();
        let (inside_out, _) = Mesh::from_parts("cube", p, None, flipped).unwrap();
        assert!(cube.stats().is_closed());
        assert_eq!(cube.signed_volume(), 8.0);
        assert_eq!(inside_out.signed_volume(), -8.0);
        for file in ["tetrahedron.obj", "icosahedron.obj", "uvsphere12.obj"] {
            assert!(load_model(file).0.signed_volume() > 0.0, "{file}");
        }
        // The cube beside an inside-out copy of itself moved along x: two pieces, one volume
        // each, and not wound outwards as a whole although their sum is positive.
        let mut p2: Vec<Vec3> = cube.positions.clone();
        p2.extend(
            cube.positions
                .iter()
                .map(|p| *p * 0.5 + Vec3::new(5.0, 0.0, 0.0)),
        );
        let mut t2 = cube.position_indices();
        t2.extend(
            cube.position_indices()
                .iter()
                .map(|t| [t[0] + 8, t[2] + 8, t[1] + 8]),
        );
        let (two, _) = Mesh::from_parts("two cubes", p2, None, t2).unwrap();
        assert_eq!(
            pieces(16, &two.position_indices()),
            [[0; 12], [1; 12]].concat()
        );
        let v = two.piece_volumes();
        assert!(v.len() == 2 && (v[0] - 8.0).abs() < 1e-9 && (v[1] + 1.0).abs() < 1e-9);
        assert!(cube.closed_outward() && !inside_out.closed_outward() && !two.closed_outward());
    }

    /// Computed normals point out; a file's pointing inwards do not. Spot's (computed, and its
    /// file's) do, though at 42 corners they point against a steep face of their own.
    #[test]
    fn normals_point_out_unless_a_file_turns_them_in() {
        let tet = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
        let faces = "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
        let (computed, _) = Mesh::from_obj_str("t.obj", &format!("{tet}{faces}")).unwrap();
        assert!(computed.closed_outward() && computed.normals_point_out());
        // One normal a corner, pointing into the tetrahedron.
        let inward = "vn 1 1 1\nvn -1 -1 -1\nf 1//1 3//1 2//1\nf 1//1 2//1 4//1\nf 1//1 4//1 3//1\nf 2//2 3//2 4//2\n";
        let (turned, _) = Mesh::from_obj_str("t.obj", &format!("{tet}{inward}")).unwrap();
        assert!(turned.closed_outward() && !turned.normals_point_out());
        // Split normals (each face's own) point out too.
        let split = "vn 0 0 -1\nvn 0 -1 0\nvn -1 0 0\nvn 1 1 1\nf 1//1 3//1 2//1\nf 1//2 2//2 4//2\nf 1//3 4//3 3//3\nf 2//4 3//4 4//4\n";
        let (split, _) = Mesh::from_obj_str("t.obj", &format!("{tet}{split}")).unwrap();
        assert!(split.normals_point_out());
        // A sliver tetrahedron, one normal a face: at its sharp edges a face's own normal
        // points against its vertex's average, and still out of the surface.
        let sliver = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0.3 0.3 0.01\n";
        let (sliver, _) = Mesh::from_obj_str("s.obj", &format!("{sliver}{faces}")).unwrap();
        let faces_own: String = (sliver.triangles.iter())
            .map(|t| {
                let [a, b, c] = t.p.map(|i| sliver.positions[i as usize]);
                let n = (b - a).cross(c - a).normalize();
                format!("vn {} {} {}\n", n.x, n.y, n.z)
            })
            .collect();
        let split_faces =
            "f 1//1 3//1 2//1\nf 1//2 2//2 4//2\nf 1//3 4//3 3//3\nf 2//4 3//4 4//4\n";
        let text = format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0.3 0.3 0.01\n{faces_own}{split_faces}");
        let (sliver, _) = Mesh::from_obj_str("s.obj", &text).unwrap();
        assert!(sliver.closed_outward() && sliver.normals_point_out());
        for file in ["spot_control_tri.obj", "spot_control_tri_vn.obj"] {
            let (spot, _) = test_support::load_model(file);
            assert!(spot.closed_outward() && spot.normals_point_out(), "{file}");
            let against = (spot.triangles.iter())
                .flat_map(|t| {
                    let [a, b, c] = t.p.map(|i| spot.positions[i as usize]);
                    let face = (b - a).cross(c - a);
                    t.n.map(|n| spot.normals[n as usize].dot(face) < 0.0)
                })
                .filter(|&against| against)
                .count();
            assert_eq!(against, 42, "{file}");
        }
    }

    /// The winding number is 1 inside a closed mesh wound outwards, 0 outside (however close),
    /// -1 inside it wound inside out.
    #[test]
    fn winding_numbers_tell_inside_from_outside() {
        let (sphere, _) = load_model("uvsphere12.obj");
        let (spot, _) = load_model("spot_control_tri.obj");
        let (lo, hi) = spot.bounds();
        let inside_out = {
            let mut m = sphere.clone();
            m.triangles.iter_mut().for_each(|t| t.p.swap(1, 2));
            m
        };
        let w = |m: &Mesh, p: Vec3| m.winding_number(p);
        assert!((w(&sphere, Vec3::ZERO) - 1.0).abs() < 1e-9);
        assert!((w(&inside_out, Vec3::ZERO) + 1.0).abs() < 1e-9);
        assert!((w(&spot, (lo + hi) * 0.5) - 1.0).abs() < 1e-9);
        for far in [
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(0.0, 1.001, 0.0),
            Vec3::splat(1e6),
        ] {
            assert!(w(&sphere, far).abs() < 1e-9, "{far}");
        }
    }

    #[test]
    fn given_normals_match_computed_ones_where_they_should() {
        // The _vn icosahedron has exact sphere normals, which the symmetric mesh reproduces.
        let (given, _) = load_model("icosahedron_vn.obj");
        let (computed, _) = load_model("icosahedron.obj");
        assert_eq!(given.positions, computed.positions);
        for (g, c) in given.triangles.iter().zip(&computed.triangles) {
            for k in 0..3 {
                let a = given.normals[g.n[k] as usize];
                let b = computed.normals[c.n[k] as usize];
                assert!(a.dot(b) > 0.9999, "{a} vs {b}");
            }
        }
    }
}
