//! The `loop` surface (Holländer & Boubekeur 2010): the limit surface of Loop subdivision over
//! every face of M1 (one Loop step of the coarse mesh, M0), evaluated from basis function tables
//! ([`crate::subdiv::bft`]); normals by subdivision shading (the same weights applied to M1's
//! one-ring normals, then normalized). Mirror of `glsl/include/loop.glsl`.
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

use super::{ElementRecord, SurfacePoint};
use crate::mesh::Mesh;
use crate::subdiv::bft::{self, Lattice, Orient, Tables};
use crate::subdiv::{stencils, Boundary, Stencil, Topology, TopologyError};
use glam::{DVec3, Vec3};

/// What the `loop` surface needs of one mesh topology and boundary rule, built once.
#[derive(Clone, Debug)]
pub struct LoopData {
    pub boundary: Boundary,
    pub m0_count: usize,
    /// M1 from M0: one computational entry per M1 vertex.
    pub stencils: Vec<Stencil>,
    pub m1: Topology,
    pub tables: Tables,
    /// Per M1 face: (its table's first entry in `table_rows`, control points K | the table's
    /// column pairs ([`bft::Config::pairs`]) << 16, first control index, orientation
    /// ([`crate::subdiv::bft::Orient::bits`]) | the tables' level << 3).
    pub faces: Vec<[u32; 4]>,
    /// Control points of every face, M1 vertex indices, [`padded`]`(K)` a face (the padding
    /// repeats the face's first control point, with weight zero), so that the drawing stages
    /// read them four at a time, as the tables' rows ([`bft::Packed`]: each at a multiple of
    /// four, at least [`padded`]`(K)` weights long for every table that reads it).
    pub control: Vec<u32>,
    /// Per M1 vertex: the start of its one-ring in `rings` (bit 31: on the boundary), plus one
    /// end entry.
    pub ring_offsets: Vec<u32>,
    pub rings: Vec<u32>,
    /// One record per M1 face.
    pub records: Vec<ElementRecord>,
}

/// Bit 31 of a ring offset: the vertex is on the boundary.
pub const RING_BOUNDARY: u32 = 1 << 31;

/// M1's positions and normals, as the GPU passes compute them (f32, same order of operations).
#[derive(Clone, Debug, Default)]
pub struct LoopFrame {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
}

/// A face's record: words 0 face, 1-3 the owners of edges 0-2 (edge e joins corners e, e + 1),
/// 4-6 the owners of corners 0-2, 7 where those corners are in the owners (2 bits each: edge e's
/// two corners at bits 4e and 4e + 2, corner i at bit 12 + 2i).
struct FaceRecord {
    face: u32,
    edge_owner: [u32; 3],
    corner_owner: [u32; 3],
    packed: u32,
}

impl FaceRecord {
    fn encode(&self) -> ElementRecord {
        let mut words = [0u32; 28];
        words[0] = self.face;
        words[1..4].copy_from_slice(&self.edge_owner);
        words[4..7].copy_from_slice(&self.corner_owner);
        words[7] = self.packed;
        ElementRecord { words }
    }

    fn decode(r: &ElementRecord) -> Self {
        let w = &r.words;
        Self {
            face: w[0],
            edge_owner: [w[1], w[2], w[3]],
            corner_owner: [w[4], w[5], w[6]],
            packed: w[7],
        }
    }
}

impl LoopData {
    /// Topology, M1, configurations and tables of `mesh` (positions welded by index); `progress`
    /// hears how far the tables are ([`bft::Progress`]).
    pub fn new(
        mesh: &Mesh,
        boundary: Boundary,
        lattice: Lattice,
        progress: impl FnMut(bft::Progress),
    ) -> Result<Self, TopologyError> {
        let topo0 = Topology::of_mesh(mesh)?;
        let stencils = stencils(&topo0, boundary);
        let m1 = Topology::new(&crate::subdiv::refined_faces(&topo0), stencils.len())?;
        let tables = bft::build(&m1, boundary, lattice, progress)?;
        let mut faces = Vec::with_capacity(m1.faces.len());
        let mut control = Vec::new();
        for fc in &tables.faces {
            let c = &tables.configs[fc.config as usize];
            debug_assert!(c.control < 1 << 16);
            faces.push([
                fc.config * lattice.rows() as u32,
                c.control as u32 | (c.pairs as u32) << 16,
                control.len() as u32,
                fc.orient.bits() | lattice.lmax << 3,
            ]);
            control.extend(&fc.control);
            let k4 = padded(fc.control.len());
            control.extend(std::iter::repeat_n(fc.control[0], k4 - fc.control.len()));
        }
        let mut ring_offsets = Vec::with_capacity(m1.vertex_count + 1);
        let mut rings = Vec::new();
        for v in 0..m1.vertex_count as u32 {
            let (ring, b) = m1.one_ring(v);
            ring_offsets.push(rings.len() as u32 | if b { RING_BOUNDARY } else { 0 });
            rings.extend(ring);
        }
        ring_offsets.push(rings.len() as u32);
        let records = face_records(&m1);
        Ok(Self {
            boundary,
            m0_count: topo0.vertex_count,
            stencils,
            m1,
            tables,
            faces,
            control,
            ring_offsets,
            rings,
            records,
        })
    }

    /// Bytes of the basis function tables: their distinct rows (f32, padded to multiples of
    /// four) and the tables' row maps.
    pub fn table_bytes(&self) -> u64 {
        self.tables.bytes()
    }

    /// M1's positions from M0's. Mirror of glsl/subdiv/loop_step.comp.
    pub fn m1_positions(&self, m0: &[Vec3]) -> Vec<Vec3> {
        self.stencils
            .iter()
            .map(|s| {
                let mut p = Vec3::ZERO;
                for (&i, &w) in s.parents.iter().zip(&s.weights) {
                    p += m0[i as usize] * (w as f32);
                }
                p
            })
            .collect()
    }

    /// M1's one-ring normals. Mirror of glsl/subdiv/loop_normals.comp.
    pub fn m1_normals(&self, p1: &[Vec3]) -> Vec<Vec3> {
        (0..self.m1.vertex_count)
            .map(|v| {
                let (start, end) = (
                    self.ring_offsets[v] & !RING_BOUNDARY,
                    self.ring_offsets[v + 1] & !RING_BOUNDARY,
                );
                let boundary = self.ring_offsets[v] & RING_BOUNDARY != 0;
                ring_normal(
                    p1,
                    p1[v],
                    &self.rings[start as usize..end as usize],
                    boundary,
                )
            })
            .collect()
    }

    /// M1's positions and normals for M0 positions `m0`.
    pub fn frame(&self, m0: &[Vec3]) -> LoopFrame {
        let positions = self.m1_positions(m0);
        let normals = self.m1_normals(&positions);
        LoopFrame { positions, normals }
    }

    /// The faces' valences and boundary cases, for reports: (valence, on a boundary) pairs with
    /// how many configurations each.
    pub fn valences(&self) -> Vec<(usize, bool, usize)> {
        let mut v: Vec<(usize, bool, usize)> = Vec::new();
        for c in &self.tables.configs {
            match v
                .iter_mut()
                .find(|(n, b, _)| *n == c.valence && *b == c.boundary)
            {
                Some(e) => e.2 += 1,
                None => v.push((c.valence, c.boundary, 1)),
            }
        }
        v.sort();
        v
    }

    /// The exact limit position of every M1 vertex (f64), for tests and reports.
    pub fn m1_limit(&self, m0: &[Vec3]) -> Vec<DVec3> {
        let p0: Vec<DVec3> = m0.iter().map(|p| p.as_dvec3()).collect();
        let p1: Vec<DVec3> = self.stencils.iter().map(|s| s.apply(&p0)).collect();
        crate::subdiv::limit_positions(&self.m1, &p1, self.boundary)
    }
}

/// One record per face of M1 (`m1`): the face, the owners of its edges (the lower numbered of
/// the two faces) and corners (the lowest numbered face around the vertex), and where its
/// corners are in them. Topology only: the same for either boundary rule.
pub fn face_records(m1: &Topology) -> Vec<ElementRecord> {
    let mut vertex_owner = vec![u32::MAX; m1.vertex_count];
    for (f, t) in m1.faces.iter().enumerate() {
        for &v in t {
            vertex_owner[v as usize] = vertex_owner[v as usize].min(f as u32);
        }
    }
    let corner_in =
        |g: u32, v: u32| m1.faces[g as usize].iter().position(|&x| x == v).unwrap() as u32;
    (0..m1.faces.len())
        .map(|f| {
            let t = m1.faces[f];
            let mut packed = 0;
            let edge_owner = [0, 1, 2].map(|e| {
                let g = m1.twin[3 * f + e].map_or(f as u32, |h| (h / 3).min(f as u32));
                packed |= corner_in(g, t[e]) << (4 * e);
                packed |= corner_in(g, t[(e + 1) % 3]) << (4 * e + 2);
                g
            });
            let corner_owner = [0, 1, 2].map(|i| {
                let h = vertex_owner[t[i] as usize];
                packed |= corner_in(h, t[i]) << (12 + 2 * i);
                h
            });
            FaceRecord {
                face: f as u32,
                edge_owner,
                corner_owner,
                packed,
            }
            .encode()
        })
        .collect()
}

/// M1's topology from `mesh` (one Loop step of its position topology).
pub fn m1_topology(mesh: &Mesh) -> Result<Topology, TopologyError> {
    let topo0 = Topology::of_mesh(mesh)?;
    let edges = (topo0.twin.iter().enumerate())
        .filter(|&(h, t)| t.is_none_or(|t| t as usize > h))
        .count();
    Topology::new(
        &crate::subdiv::refined_faces(&topo0),
        topo0.vertex_count + edges,
    )
}

/// Mirror of `ring_normal` in glsl/subdiv/loop_normals.comp.
fn ring_normal(p: &[Vec3], c: Vec3, ring: &[u32], boundary: bool) -> Vec3 {
    let n = ring.len();
    let pairs = if boundary { n.saturating_sub(1) } else { n };
    let mut s = Vec3::ZERO;
    for k in 0..pairs {
        let a = p[ring[k] as usize] - c;
        let b = p[ring[(k + 1) % n] as usize] - c;
        s += a.cross(b);
    }
    let l = s.length();
    if l > 0.0 {
        s / l
    } else {
        Vec3::ZERO
    }
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

/// `k` rounded up to a multiple of four: the stride of a configuration's table rows and of a
/// face's control points. Mirror of the `k4` in `loop_eval_face`.
pub fn padded(k: usize) -> usize {
    k.next_multiple_of(4)
}

/// Evaluate face `g` at weights `b` of its stored corners. Mirror of `loop_eval_face`.
pub fn eval_face(data: &LoopData, frame: &LoopFrame, g: u32, b: [f32; 3]) -> SurfacePoint {
    let [base, kp, first, orient] = data.faces[g as usize];
    let (k, pairs) = ((kp & 0xffff) as usize, (kp >> 16) as usize);
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
    // The three rows' weights interpolated first, then one weighted sum, and two for the
    // tangents (the lattice triangle's edges).
    let (mut p, mut n, mut dx, mut dy) = (Vec3::ZERO, Vec3::ZERO, Vec3::ZERO, Vec3::ZERO);
    // Each row: where it starts, and whether it is read as its mirror image (column pairs
    // swapped).
    let packed = &data.tables.packed;
    let rows = rows.map(|r| packed.entry(base as usize + r));
    // Padded columns too, as the GPU sums them (weight zero: the sum keeps its value).
    for c in 0..padded(k) {
        let v = data.control[first as usize + c] as usize;
        let (pv, nv) = (frame.positions[v], frame.normals[v]);
        let w3 = rows.map(|at| packed.weight(at, c, pairs));
        let w = w3[0] * l[0] + w3[1] * l[1] + w3[2] * l[2];
        p += pv * w;
        n += nv * w;
        dx += pv * (w3[d[0][0]] - w3[d[0][1]]);
        dy += pv * (w3[d[1][0]] - w3[d[1][1]]);
    }
    let position = p;
    let normal = n.normalize_or_zero();
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
