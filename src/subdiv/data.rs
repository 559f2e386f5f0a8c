//! The loop surface's data of one mesh, on the CPU (no Vulkan): M0's topology, the computational
//! entries that make M1 from it ([`stencils`]), M1's topology, its basis function tables
//! ([`bft`]) and, per M1 face, the words the drawing stages read (its table, control points and
//! orientation; the control points padded to fours as the tables' rows are), M1's one-rings for
//! its normals, and one element record per M1 face. `render::loop_gpu` uploads these as they
//! are; `surface::loop_` (glsl/include/loop.glsl's mirror) evaluates them. [`LoopFrame`] is M1's
//! positions and normals for one M0, as the GPU passes compute them.
//!
//! The records make the surface watertight by ownership: a sample on an M1 edge is evaluated
//! by the edge's *owner* (the lower numbered of its two faces), a sample on a corner by the
//! corner's owner (the lowest numbered face around the vertex); [`FaceRecord`] says who they are.
#![forbid(unsafe_code)]

use super::bft::{self, Lattice, Tables};
use super::{refined_faces, stencils, Boundary, Stencil, Topology, TopologyError};
use crate::mesh::Mesh;
use crate::surface::ElementRecord;
use glam::{DVec3, Vec3};

/// What the `loop` surface needs of one mesh topology and boundary rule, built once.
#[derive(Clone, Debug)]
pub struct LoopData {
    pub boundary: Boundary,
    pub m0_count: usize,
    /// M1 from M0: one computational entry per M1 vertex.
    pub stencils: Vec<Stencil>,
    pub m1: Topology,
    /// The tables; their faces' control points are in `control`, and each
    /// [`bft::FaceConfig::control`] here is left empty.
    pub tables: Tables,
    /// Per M1 face: (its table's first entry in `table_rows`, control points K | the table's
    /// column pairs ([`bft::Config::pairs`]) << 16, first control index, orientation
    /// ([`bft::Orient::bits`]) | the tables' level << 3).
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
pub struct FaceRecord {
    pub face: u32,
    pub edge_owner: [u32; 3],
    pub corner_owner: [u32; 3],
    pub packed: u32,
}

impl FaceRecord {
    pub fn encode(&self) -> ElementRecord {
        let mut words = [0u32; 28];
        words[0] = self.face;
        words[1..4].copy_from_slice(&self.edge_owner);
        words[4..7].copy_from_slice(&self.corner_owner);
        words[7] = self.packed;
        ElementRecord { words }
    }

    pub fn decode(r: &ElementRecord) -> Self {
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
        let m1 = Topology::new(&refined_faces(&topo0), stencils.len())?;
        bft::check_size(&m1)?;
        let mut tables = bft::build(&m1, boundary, lattice, progress)?;
        let mut faces = Vec::with_capacity(m1.faces.len());
        let listed = tables.faces.iter().map(|fc| padded(fc.control.len())).sum();
        let mut control = Vec::with_capacity(listed);
        for fc in &mut tables.faces {
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
            // Kept once, here (a face around a vertex of valence n lists n + 1 or more).
            fc.control = Vec::new();
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

    /// M1's positions from M0's. Mirror of glsl/loop/loop_step.comp.
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

    /// M1's one-ring normals. Mirror of glsl/loop/loop_normals.comp.
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
        super::limit_positions(&self.m1, &p1, self.boundary)
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
    Topology::new(&refined_faces(&topo0), topo0.vertex_count + edges)
}

/// Mirror of `ring_normal` in glsl/loop/loop_normals.comp.
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

/// `k` rounded up to a multiple of four: the stride of a configuration's table rows and of a
/// face's control points. Mirror of the `k4` in `loop_eval_face`.
pub fn padded(k: usize) -> usize {
    k.next_multiple_of(4)
}
