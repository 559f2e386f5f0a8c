//! The `loop` surface (Holländer & Boubekeur 2010): the limit surface of Loop subdivision over
//! every face of M1 (one Loop step of the coarse mesh, M0), evaluated from basis function tables
//! ([`crate::subdiv::bft`]); normals by subdivision shading (the same weights applied to M1's
//! one-ring normals, then normalized). Mirror of `glsl/include/loop.glsl`, the file of the same
//! name; what it reads is [`LoopData`] and [`LoopFrame`], built in [`crate::subdiv`].
//!
//! Elements are M1 faces. A sample is evaluated on the face's table: a lattice point is one row
//! (the exact limit point), any other point interpolates the rows of the lattice triangle around
//! it (the paper's "linear interpolation on the fine triangles").
//!
//! Watertight by ownership: a sample on an M1 edge is evaluated by the edge's *owner* (the lower
//! numbered of its two faces), a sample on a corner by the corner's owner (the lowest numbered
//! face around the vertex), with the same weights on the same vertices. Both sides of an edge make
//! the very same call, so its points are bit-identical from either side, in every driver; the
//! tangents there are the owner's (another parametrization of the same tangent plane).
#![forbid(unsafe_code)]

use super::facts::{Elements, FragmentNormals, PrePass, SurfaceFacts};
use super::{ElementRecord, SurfacePoint};
use crate::mesh::Mesh;
use crate::subdiv::bft::Orient;
use crate::subdiv::{padded, FaceRecord};
use glam::Vec3;

#[path = "loop_bound.rs"]
pub mod bound;

/// What the rest of the crate names of Loop subdivision (`crate::subdiv`), through this surface:
/// its boundary rule and table levels (build options), the per-mesh data and M1 the mirror
/// reads, the error of a mesh Loop cannot subdivide, and the tables' progress reports.
pub use crate::subdiv::bft::{progress_line, throttled, Lattice, Progress, DEFAULT_LMAX, MAX_LMAX};
pub use crate::subdiv::{Boundary, LoopData, LoopFrame, TopologyError};

/// The level from which the normal field is summed per fragment instead of per vertex: 153
/// pattern vertices per M1 face, about as many refined vertices as pixels for Spot at 1280×720.
pub const FRAGMENT_NORMALS_FROM: u32 = 16;

/// What `loop` declares about itself (docs/architecture.md, "Surfaces as plug-ins").
pub const FACTS: SurfaceFacts = SurfaceFacts {
    name: "loop",
    help: "The limit surface of Loop subdivision (Holländer & Boubekeur 2010): elements are the faces of one Loop step M1, evaluated from basis function tables (src/surface/loop.rs)",
    elements: Elements::LoopFaces,
    pre_pass: Some(PrePass::LoopStep),
    options: &["boundary", "bft_level"],
    texture_coordinates: false,
    needs_every_face: true,
    tags: false,
    fragment_normals: FragmentNormals::FromLevel(FRAGMENT_NORMALS_FROM),
    bindings: &[
        "BINDING_LOOP_P1",
        "BINDING_LOOP_N1",
        "BINDING_LOOP_FACES",
        "BINDING_LOOP_CONTROL",
        "BINDING_LOOP_TABLES",
        "BINDING_LOOP_ROWS",
    ],
    bound: crate::surface::bounds::SurfaceBound::Own {
        element: bound::element,
        edge: bound::edge,
    },
};

/// What the mirror reads besides the record: the mesh's tables and M1.
pub type Inputs<'a> = (&'a LoopData, &'a LoopFrame);

/// The surface's elements: one record per face of M1 (the faces and the owners of their edges
/// and corners), none for a mesh Loop cannot subdivide (`LoopData::new`, which the scene builds
/// first, says why).
pub fn element_records(mesh: &Mesh) -> Vec<ElementRecord> {
    crate::subdiv::m1_topology(mesh)
        .map(|m1| crate::subdiv::face_records(&m1))
        .unwrap_or_default()
}

/// Which face evaluates sample `bary` of `rec`'s face, and with which weights on its corners:
/// the owner of the edge or corner the sample lies on, the face itself inside.
/// Mirror of `loop_owner` in loop.glsl.
pub fn owner(rec: &ElementRecord, bary: [f32; 3]) -> (u32, [f32; 3]) {
    let r = FaceRecord::decode(rec);
    let zeros = bary.iter().filter(|&&b| b == 0.0).count();
    let mut b = [0.0f32; 3];
    if zeros >= 2 {
        let i = (0..3).find(|&i| bary[i] != 0.0).unwrap_or(0);
        b[((r.packed >> (12 + 2 * i)) & 3) as usize] = bary[i];
        (r.corner_owner[i], b)
    } else if zeros == 1 {
        let e = (0..3).find(|&e| bary[(e + 2) % 3] == 0.0).unwrap();
        b[((r.packed >> (4 * e)) & 3) as usize] = bary[e];
        b[((r.packed >> (4 * e + 2)) & 3) as usize] = bary[(e + 1) % 3];
        (r.edge_owner[e], b)
    } else {
        (r.face, bary)
    }
}

/// Evaluate the `loop` surface at sample `bary` of the face whose record is `rec`.
/// Mirror of `loop_eval` in loop.glsl.
pub fn eval(
    data: &LoopData,
    frame: &LoopFrame,
    rec: &ElementRecord,
    bary: [f32; 3],
) -> SurfacePoint {
    let (g, b) = owner(rec, bary);
    eval_face(data, frame, g, b)
}

/// The exact limit point of M1 face `rec` at its stored lattice point `(i, j)` (weight `i/S` on
/// stored corner 1, `j/S` on corner 2), strictly inside the face: the one table row there summed
/// over the control vertices, as [`eval`] sums it at that point (the same bits up to the sign of
/// a zero: `eval` weighs the cell's other two rows by zero), without the normal and tangents.
/// What the bounds read at every lattice point ([`bound`]), through [`FaceRows`].
pub fn interior_point(
    data: &LoopData,
    frame: &LoopFrame,
    rec: &ElementRecord,
    i: u32,
    j: u32,
) -> Vec3 {
    FaceRows::new(data, frame, rec).point(i, j)
}

/// [`interior_point`] at many points of one face: the face's record and tables read once.
pub struct FaceRows<'a> {
    data: &'a LoopData,
    frame: &'a LoopFrame,
    base: usize,
    k: usize,
    pairs: usize,
    first: usize,
    o: Orient,
    lattice: Lattice,
}

impl<'a> FaceRows<'a> {
    pub fn new(data: &'a LoopData, frame: &'a LoopFrame, rec: &ElementRecord) -> Self {
        let g = FaceRecord::decode(rec).face as usize;
        let [base, kp, first, orient] = data.faces[g];
        Self {
            data,
            frame,
            base: base as usize,
            k: (kp & 0xffff) as usize,
            pairs: (kp >> 16) as usize,
            first: first as usize,
            o: Orient {
                rot: (orient & 3) as u8,
                mirror: orient & 4 != 0,
            },
            lattice: Lattice::new(orient >> 3),
        }
    }

    /// [`interior_point`] at `(i, j)`.
    pub fn point(&self, i: u32, j: u32) -> Vec3 {
        let mut p = [Vec3::ZERO];
        self.points(i, j, &mut p);
        p[0]
    }

    /// [`interior_point`] at `(i, j)`, `(i + 1, j)`, ... into `out` (at most [`FaceRows::RUN`]
    /// points): each point's sum in its own order, the same bits as alone, the runs' sums
    /// interleaved so that they do not wait on each other.
    pub fn points(&self, i: u32, j: u32, out: &mut [Vec3]) {
        let s = self.lattice.segments();
        let m = out.len();
        debug_assert!(
            m <= Self::RUN && i > 0 && j > 0 && i + m as u32 + j <= s,
            "({i}.., {j}) is not inside the face"
        );
        // Canonical lattice coordinates, as `eval_face` takes them from the barycentrics.
        let packed = &self.data.tables.packed;
        let mut at = [(0, false); Self::RUN];
        for (q, a) in at.iter_mut().enumerate().take(m) {
            let i = i + q as u32;
            let stored = [s - i - j, i, j];
            let row = (self.lattice).row(stored[self.o.stored(1)], stored[self.o.stored(2)]);
            *a = packed.entry(self.base + row);
        }
        let mut p = [Vec3::ZERO; Self::RUN];
        for c in 0..padded(self.k) {
            let v = self.data.control[self.first + c] as usize;
            let position = self.frame.positions[v];
            for q in 0..m {
                p[q] += position * packed.weight(at[q], c, self.pairs);
            }
        }
        out.copy_from_slice(&p[..m]);
    }

    /// The most points [`FaceRows::points`] takes at once.
    pub const RUN: usize = 4;
}

/// The lattice triangle around canonical lattice coordinates (x, y) (units of 1/S): its
/// three rows, their interpolation weights, and the rows whose differences are d/dx and d/dy
/// (`(plus, minus)` index pairs into the three). Mirror of `bft_cell` in loop.glsl.
pub fn cell(lattice: Lattice, x: f32, y: f32) -> ([usize; 3], [f32; 3], [[usize; 2]; 2]) {
    // d: indices into the three rows.
    let s = lattice.segments() as f32;
    let mut i0 = x.floor().clamp(0.0, s);
    let mut j0 = y.floor().clamp(0.0, s);
    let mut fx = x - i0;
    let mut fy = y - j0;
    // On (or, by rounding, beyond) the far edge i + j = S: step into the last cell.
    if i0 + j0 >= s {
        if i0 > 0.0 {
            i0 -= 1.0;
            fx += 1.0;
        } else {
            j0 -= 1.0;
            fy += 1.0;
        }
    }
    let (i, j) = (i0 as u32, j0 as u32);
    if fx + fy > 1.0 && i + j + 2 <= lattice.segments() {
        // Upper triangle: (i+1, j+1), (i, j+1), (i+1, j).
        let a = lattice.row(i + 1, j + 1);
        let b = lattice.row(i, j + 1);
        let c = lattice.row(i + 1, j);
        (
            [a, b, c],
            [fx + fy - 1.0, 1.0 - fx, 1.0 - fy],
            [[0, 1], [0, 2]],
        )
    } else {
        let a = lattice.row(i, j);
        let b = lattice.row(i + 1, j);
        let c = lattice.row(i, j + 1);
        ([a, b, c], [1.0 - fx - fy, fx, fy], [[1, 0], [2, 0]])
    }
}

/// Whether control vertex `a` (weight, normal) weighs more than `b`, the larger normal (x,
/// then y, then z) on a tie. Mirror: the comparison in `loop_heaviest_normal`.
fn heavier_normal(a: (f32, Vec3), b: (f32, Vec3)) -> bool {
    let (m, n) = (a.1, b.1);
    let larger = if m.x != n.x {
        m.x > n.x
    } else if m.y != n.y {
        m.y > n.y
    } else {
        m.z > n.z
    };
    a.0 > b.0 || (a.0 == b.0 && larger)
}

/// Where face `g` is read at weights `b` of its stored corners: its control vertices, the
/// lattice triangle around the point (the three rows, where each starts in the packed tables
/// and whether it is read mirrored, their interpolation weights, the rows whose differences are
/// the tangents) and the orientation. The first half of `loop_eval_face`.
struct FaceCell {
    /// Control vertices: padded count, column pairs, first index into `LoopData::control`.
    k: usize,
    pairs: usize,
    first: usize,
    rows: [(usize, bool); 3],
    l: [f32; 3],
    d: [[usize; 2]; 2],
    o: Orient,
    s: f32,
}

impl FaceCell {
    fn new(data: &LoopData, g: u32, b: [f32; 3]) -> Self {
        let [base, kp, first, orient] = data.faces[g as usize];
        let o = Orient {
            rot: (orient & 3) as u8,
            mirror: orient & 4 != 0,
        };
        let lattice = Lattice::new(orient >> 3);
        // Canonical corner i is stored corner o.stored(i).
        let s = lattice.segments() as f32;
        let x = b[o.stored(1)] * s;
        let y = b[o.stored(2)] * s;
        let (rows, l, d) = cell(lattice, x, y);
        debug_assert!(rows.iter().all(|&r| r < lattice.rows()));
        let packed = &data.tables.packed;
        FaceCell {
            k: padded((kp & 0xffff) as usize),
            pairs: (kp >> 16) as usize,
            first: first as usize,
            rows: rows.map(|r| packed.entry(base as usize + r)),
            l,
            d,
            o,
            s,
        }
    }

    /// Control vertex `c`'s weight in each of the three rows.
    fn weights(&self, data: &LoopData, c: usize) -> [f32; 3] {
        self.rows
            .map(|at| data.tables.packed.weight(at, c, self.pairs))
    }

    /// The weight interpolated at the point.
    fn weight(&self, w3: [f32; 3]) -> f32 {
        w3[0] * self.l[0] + w3[1] * self.l[1] + w3[2] * self.l[2]
    }
}

/// The position alone of [`eval`] at sample `bary` of `rec`'s face, the same bits, without the
/// normal and tangents: what the bounds read on edges and corners ([`bound`]).
pub fn position(data: &LoopData, frame: &LoopFrame, rec: &ElementRecord, bary: [f32; 3]) -> Vec3 {
    let (g, b) = owner(rec, bary);
    let cell = FaceCell::new(data, g, b);
    let mut p = Vec3::ZERO;
    for c in 0..cell.k {
        let v = data.control[cell.first + c] as usize;
        p += frame.positions[v] * cell.weight(cell.weights(data, c));
    }
    p
}

/// The position of [`eval`] at sample `bary` of `rec`'s face, the same bits, and the sum of
/// M1's normals there before it is normalized (what a displacement moves along, divided by its
/// length): what the bounds of a displaced `loop` read ([`bound`]).
pub fn position_and_field(
    data: &LoopData,
    frame: &LoopFrame,
    rec: &ElementRecord,
    bary: [f32; 3],
) -> (Vec3, Vec3) {
    let (g, b) = owner(rec, bary);
    let cell = FaceCell::new(data, g, b);
    let (mut p, mut n) = (Vec3::ZERO, Vec3::ZERO);
    for c in 0..cell.k {
        let v = data.control[cell.first + c] as usize;
        let w = cell.weight(cell.weights(data, c));
        p += frame.positions[v] * w;
        n += frame.normals[v] * w;
    }
    (p, n)
}

/// Evaluate face `g` at weights `b` of its stored corners. Mirror of `loop_eval_face`.
pub fn eval_face(data: &LoopData, frame: &LoopFrame, g: u32, b: [f32; 3]) -> SurfacePoint {
    let cell = FaceCell::new(data, g, b);
    let (o, s, d) = (cell.o, cell.s, cell.d);
    // The three rows' weights interpolated first, then one weighted sum, and two for the
    // tangents (the lattice triangle's edges).
    let (mut p, mut n, mut dx, mut dy) = (Vec3::ZERO, Vec3::ZERO, Vec3::ZERO, Vec3::ZERO);
    // Padded columns too, as the GPU sums them (weight zero: the sum keeps its value).
    // The heaviest control vertex with a normal, for where M1's normals cancel.
    let mut heaviest = (-3.0e38f32, Vec3::Z);
    for c in 0..cell.k {
        let v = data.control[cell.first + c] as usize;
        let (pv, nv) = (frame.positions[v], frame.normals[v]);
        let w3 = cell.weights(data, c);
        let w = cell.weight(w3);
        if nv != Vec3::ZERO && heavier_normal((w, nv), heaviest) {
            heaviest = (w, nv);
        }
        p += pv * w;
        n += nv * w;
        dx += pv * (w3[d[0][0]] - w3[d[0][1]]);
        dy += pv * (w3[d[1][0]] - w3[d[1][1]]);
    }
    let position = p;
    // Where M1's normals cancel (a fold of the mesh): the heaviest's
    // (`loop_heaviest_normal`, from the weights and normals alone, so the two faces sharing an
    // edge choose the same one there).
    let normal = if super::dot3(n, n) > super::FIELD_MIN2 {
        n.normalize()
    } else {
        heaviest.1
    };
    let (dx, dy) = (dx * s, dy * s);
    let canon = [Vec3::ZERO, dx, dy];
    let mut grad = [Vec3::ZERO; 3];
    for (i, &c) in canon.iter().enumerate() {
        grad[o.stored(i)] = c;
    }
    SurfacePoint {
        position,
        normal,
        direction: normal,
        dpdu: grad[1] - grad[0],
        dpdv: grad[2] - grad[0],
        uv: glam::Vec2::ZERO,
        duv: [glam::Vec2::ZERO; 2],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_support::load_model;
    use crate::pattern::weight;

    fn setup(file: &str, boundary: Boundary) -> (Mesh, LoopData, LoopFrame) {
        let (mesh, _) = load_model(file);
        let data = LoopData::new(&mesh, boundary, Lattice::default(), |_| {}).unwrap();
        let frame = data.frame(&mesh.positions);
        (mesh, data, frame)
    }

    /// The records `build_records` makes for loop (topology only) are the ones `LoopData` holds.
    #[test]
    fn face_records_need_only_the_topology() {
        for file in ["spot_open.obj", "tetrahedron.obj"] {
            let (mesh, data, _) = setup(file, Boundary::EdgeAndCorner);
            let records = crate::surface::build_records(
                crate::surface::RecordKind::LoopFaces,
                &mesh,
                Default::default(),
            );
            assert_eq!(records, data.records, "{file}");
        }
    }

    /// Every M1 edge, sampled at every level-n point from both of its faces, gives bit-identical
    /// positions and normals; so does every corner from every face around it.
    #[test]
    fn shared_edges_and_corners_are_bit_identical() {
        for file in [
            "spot_control_tri.obj",
            "fan24_open.obj",
            "halfdisc17_open.obj",
            "tetrahedron.obj",
        ] {
            let (_, data, frame) = setup(file, Boundary::EdgeOnly);
            let m1 = &data.m1;
            for n in [3u32, 8, 37] {
                for f in 0..m1.faces.len() {
                    for e in 0..3 {
                        let Some(h) = m1.twin[3 * f + e] else {
                            continue;
                        };
                        let (g, eg) = (h as usize / 3, h as usize % 3);
                        for k in 0..=n {
                            // Face f: corner e gets (n-k)/n, corner e+1 gets k/n; face g sees the
                            // edge the other way round.
                            let mut bf = [0.0; 3];
                            bf[e] = weight(n - k, n);
                            bf[(e + 1) % 3] = weight(k, n);
                            let mut bg = [0.0; 3];
                            bg[eg] = weight(k, n);
                            bg[(eg + 1) % 3] = weight(n - k, n);
                            let pf = eval(&data, &frame, &data.records[f], bf);
                            let pg = eval(&data, &frame, &data.records[g], bg);
                            assert_eq!(
                                pf.position.to_array().map(f32::to_bits),
                                pg.position.to_array().map(f32::to_bits),
                                "{file} n {n} faces {f}/{g} k {k}"
                            );
                            assert_eq!(pf.normal, pg.normal);
                        }
                    }
                }
            }
        }
    }

    /// What the bounds read is `eval`'s position, on every face (regular and extraordinary,
    /// both boundary rules, tables read mirrored): `position` the same bits at every lattice
    /// point and at points between them, `interior_point` equal as numbers (a zero's sign may
    /// differ) at the lattice points strictly inside.
    #[test]
    fn bound_points_are_eval_positions() {
        let bits = |p: Vec3| p.to_array().map(f32::to_bits);
        let mut mirrored = 0;
        for (file, boundary) in [
            ("spot_control_tri.obj", Boundary::EdgeOnly),
            ("fan24_open.obj", Boundary::EdgeAndCorner),
            ("halfdisc17_open.obj", Boundary::EdgeOnly),
            ("tetrahedron.obj", Boundary::EdgeOnly),
        ] {
            let (_, data, frame) = setup(file, boundary);
            for rec in &data.records {
                let g = FaceRecord::decode(rec).face as usize;
                let orient = data.faces[g][3];
                mirrored += usize::from(orient & 4 != 0);
                let s = Lattice::new(orient >> 3).segments();
                for n in [s, 37] {
                    for j in 0..=n {
                        for i in 0..=n - j {
                            let b = [weight(n - i - j, n), weight(i, n), weight(j, n)];
                            let want = eval(&data, &frame, rec, b).position;
                            let at = format!("{file} face {g} ({i}, {j})/{n}");
                            assert_eq!(bits(position(&data, &frame, rec, b)), bits(want), "{at}");
                            if n == s && i > 0 && j > 0 && i + j < s {
                                let got = interior_point(&data, &frame, rec, i, j);
                                assert!(got == want, "{at}: {got} != {want}");
                            }
                        }
                    }
                }
            }
        }
        assert!(mirrored > 0, "no table read mirrored");
    }

    /// At lattice points (level 32 and every level dividing it) the surface is the limit of
    /// M^(1 + 5): checked at the corners against the exact limit positions of M1's vertices, and
    /// interior points lie between (continuity across lattice cells).
    #[test]
    fn corners_are_the_limit_positions() {
        for (file, boundary) in [
            ("spot_control_tri.obj", Boundary::EdgeOnly),
            ("fan24_open.obj", Boundary::EdgeAndCorner),
            ("grid_open_8x8.obj", Boundary::EdgeOnly),
        ] {
            let (mesh, data, frame) = setup(file, boundary);
            let limit = data.m1_limit(&mesh.positions);
            let (lo, hi) = mesh.bounds();
            let diag = (hi - lo).length();
            for (f, t) in data.m1.faces.iter().enumerate() {
                for i in 0..3 {
                    let mut b = [0.0; 3];
                    b[i] = 1.0;
                    let p = eval(&data, &frame, &data.records[f], b).position;
                    let d = (p.as_dvec3() - limit[t[i] as usize]).length() as f32;
                    assert!(d < 2e-6 * diag, "{file} face {f} corner {i}: {d}");
                }
            }
        }
    }

    /// Off its lattice a sample interpolates the lattice triangle around it (docs/loop.md):
    /// within the limit's second derivative (by the face's parameters) times 1/S² of the limit.
    /// At table level 3 (S = 8), samples off its lattice are compared with the same samples at
    /// table level 7 (S = 128, whose own interpolation is 256 times closer), the second
    /// derivative measured independently, as second differences of the fine table's lattice
    /// points in the lattice's three directions.
    #[test]
    fn off_lattice_samples_are_within_the_interpolation_bound() {
        let (mesh, _) = load_model("spot_control_tri.obj");
        let data = |lmax| {
            let d = LoopData::new(&mesh, Boundary::EdgeOnly, Lattice::new(lmax), |_| {}).unwrap();
            let f = d.frame(&mesh.positions);
            (d, f)
        };
        let ((coarse, cf), (fine, ff)) = (data(3), data(7));
        let mut worst = 0.0f32;
        for (t, rec) in coarse.records.iter().enumerate().step_by(5) {
            let at = |u: f32, v: f32| eval(&fine, &ff, rec, [1.0 - u - v, u, v]).position;
            // The second derivative over the face: second differences at lattice points of the
            // fine table (steps of 1/32, lattice points at S = 128) along u, v and u - v.
            let d = 1.0 / 32.0;
            let mut m2 = 0.0f32;
            for i in 1..31 {
                for j in 1..(31 - i) {
                    let (u, v) = (i as f32 * d, j as f32 * d);
                    let p = at(u, v);
                    for (du, dv) in [(d, 0.0), (0.0, d), (d, -d)] {
                        let second = at(u + du, v + dv) - 2.0 * p + at(u - du, v - dv);
                        m2 = m2.max(second.length() / (d * d));
                    }
                }
            }
            let bound = m2 / 64.0;
            for (u, v) in [(0.21f32, 0.33f32), (0.6, 0.1), (0.1, 0.85), (0.49, 0.37)] {
                let bary = [1.0 - u - v, u, v];
                let off = eval(&coarse, &cf, rec, bary).position;
                let limit = eval(&fine, &ff, rec, bary).position;
                let e = off.distance(limit);
                assert!(
                    e <= bound,
                    "face {t} at ({u}, {v}): {e} from the limit, bound {bound}"
                );
                worst = worst.max(e / bound);
            }
        }
        // Interpolation's error is a sizeable share of the bound somewhere: it is not idle.
        eprintln!("off-lattice samples at S = 8: at most {worst:.3} of the bound");
        assert!(worst > 0.05, "largest share of the bound {worst}");
    }

    /// Interpolated (off-lattice) samples are continuous: a point just inside a lattice cell's
    /// edge agrees with the edge point, and tangents are the derivatives of the interpolation.
    #[test]
    fn off_lattice_interpolation_is_continuous_with_tangents() {
        let (_, data, frame) = setup("spot_control_tri.obj", Boundary::EdgeOnly);
        let rec = &data.records[5];
        let h = 1e-3;
        for (u, v) in [(0.21f32, 0.33f32), (0.6, 0.1), (0.1, 0.85), (0.49, 0.49)] {
            let at = |u: f32, v: f32| eval(&data, &frame, rec, [1.0 - u - v, u, v]);
            let p = at(u, v);
            let du = (at(u + h, v).position - at(u - h, v).position) / (2.0 * h);
            let dv = (at(u, v + h).position - at(u, v - h).position) / (2.0 * h);
            let tol = 0.05 * (p.dpdu.length() + p.dpdv.length());
            assert!(
                (du - p.dpdu).length() < tol,
                "({u}, {v}): {du} vs {}",
                p.dpdu
            );
            assert!(
                (dv - p.dpdv).length() < tol,
                "({u}, {v}): {dv} vs {}",
                p.dpdv
            );
        }
    }
}
