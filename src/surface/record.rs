//! Element records: what a driver hands, unopened, to the surface for each element it samples.
//!
//! Every record is [`RECORD_BYTES`] bytes (`struct ElementRecord` in `glsl/include/records.glsl`:
//! seven `uvec4`), small enough to be pushed with the draw words inside the 128 bytes of push
//! constants every device offers. Drivers only move records around (push constants, a dynamic
//! uniform buffer, instance-rate vertex attributes, a texel buffer indexed by element); each surface owns the layout of the
//! bytes inside, how it builds them from the mesh, and decodes them itself.
//!
//! The local surfaces (`flat`, `phong`, `pn`) share one layout, [`CornerRecord`]: the coarse
//! triangle's corner positions and normals, each corner's *geometry normal* (see below) and the
//! corners' global vertex indices (the canonical ordering key).
//!
//! Geometry normals make PN triangles and Phong tessellation crack-free at split normals (a
//! position carrying several `vn`, a hard edge). Their geometry is built from normals, so two
//! triangles that meet along an edge with different normals at an end build different edge
//! curves: a crack. With [`Seams::Closed`] (the default):
//! - each corner at a split position also carries the position's own normal (area-weighted, the
//!   same for every triangle there), octahedral-encoded in the `w` components of `p` and `n` (`w`
//!   of `p` is [`SMOOTH_CORNER`] at smooth positions);
//! - each edge whose two sides disagree is flagged (`idx.w`, [`SeamFlags`]), the same for both
//!   triangles: on a flagged edge the geometry uses the position normals at its ends, so both
//!   sides build the same curve. PN flags an edge only where the two sides' PN control points
//!   really differ (a cube's straight edges under face normals stay unflagged, so the cube stays
//!   a cube); Phong flags every edge whose normals differ, and blends its corner normal between
//!   the choices of the corner's two edges inside the triangle (exactly one choice on an edge);
//! - displacement moves along the normal field of the position normals, shared by both sides.
//!
//! The corners' own normals still drive shading, so a hard edge stays hard in the light. With
//! [`Seams::Open`] the geometry uses the corners' own normals, as the papers do (and cracks).
//!
//! The `loop` surface's elements are M1 faces ([`RecordKind::LoopFaces`]): each record holds the
//! face and the owners of its edges and corners (`loop_::element_records`); the
//! control points and tables live in buffers of their own.

use super::{Seams, Surface};
use crate::mesh::Mesh;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// `p[i][3]` of a corner whose geometry normal is its own normal (outside the octahedral range).
pub const SMOOTH_CORNER: f32 = 2.0;

/// Octahedral encoding of a unit vector (two numbers in [-1, 1]). Mirror: `oct_decode` in
/// glsl/include/corners.glsl decodes it.
pub fn oct_encode(n: Vec3) -> [f32; 2] {
    let l1 = n.x.abs() + n.y.abs() + n.z.abs();
    let (x, y) = (n.x / l1, n.y / l1);
    if n.z >= 0.0 {
        [x, y]
    } else {
        let s = |v: f32| if v >= 0.0 { 1.0 } else { -1.0 };
        [(1.0 - y.abs()) * s(x), (1.0 - x.abs()) * s(y)]
    }
}

/// The unit vector of an octahedral encoding. Mirror of `oct_decode` in corners.glsl.
pub fn oct_decode(e: [f32; 2]) -> Vec3 {
    let mut v = Vec3::new(e[0], e[1], 1.0 - e[0].abs() - e[1].abs());
    if v.z < 0.0 {
        let s = |v: f32| if v >= 0.0 { 1.0 } else { -1.0 };
        let (x, y) = (v.x, v.y);
        v.x = (1.0 - y.abs()) * s(x);
        v.y = (1.0 - x.abs()) * s(y);
    }
    v.normalize()
}

/// Size of every element record, in bytes.
pub const RECORD_BYTES: usize = 112;

/// An element's record as drivers see it: opaque words.
#[repr(C, align(16))]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ElementRecord {
    pub words: [u32; RECORD_BYTES / 4],
}

const _: () = assert!(std::mem::size_of::<ElementRecord>() == RECORD_BYTES);

/// Record of the local surfaces (flat, phong, pn): 112 bytes, std140 = std430 = scalar layout.
/// Decoded in GLSL by `corner_record()` (glsl/include/corners.glsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct CornerRecord {
    /// Corner positions (`xyz`); `w`: [`SMOOTH_CORNER`], or the first number of the octahedral
    /// geometry normal.
    pub p: [[f32; 4]; 3],
    /// Corner unit normals (`xyz`); `w`: the second number of the geometry normal (0 if smooth).
    pub n: [[f32; 4]; 3],
    /// Global position index of each corner (the canonical ordering key), then the seam flags
    /// (`SeamFlags`).
    pub idx: [u32; 4],
}

const _: () = {
    assert!(std::mem::size_of::<CornerRecord>() <= RECORD_BYTES);
    assert!(std::mem::offset_of!(CornerRecord, p) == 0);
    assert!(std::mem::offset_of!(CornerRecord, n) == 48);
    assert!(std::mem::offset_of!(CornerRecord, idx) == 96);
};

impl CornerRecord {
    /// A triangle with smooth corners and no seam flags.
    pub fn new(p: [Vec3; 3], n: [Vec3; 3], idx: [u32; 3]) -> Self {
        Self {
            p: p.map(|v| v.extend(SMOOTH_CORNER).to_array()),
            n: n.map(|v| v.extend(0.0).to_array()),
            idx: [idx[0], idx[1], idx[2], 0],
        }
    }

    pub fn seam_flags(&self) -> SeamFlags {
        SeamFlags(self.idx[3])
    }

    /// Give `corner` a geometry normal of its own (a split-normal position, closed seams).
    pub fn set_geometry_normal(&mut self, corner: usize, g: Vec3) {
        let [a, b] = oct_encode(g);
        self.p[corner][3] = a;
        self.n[corner][3] = b;
    }

    /// The normal the surface's geometry uses at `corner`.
    pub fn geometry_normal(&self, corner: usize) -> Vec3 {
        let a = self.p[corner][3];
        if a == SMOOTH_CORNER {
            self.normal(corner)
        } else {
            oct_decode([a, self.n[corner][3]])
        }
    }

    pub fn position(&self, corner: usize) -> Vec3 {
        Vec3::from_slice(&self.p[corner][..3])
    }

    pub fn normal(&self, corner: usize) -> Vec3 {
        Vec3::from_slice(&self.n[corner][..3])
    }

    pub fn encode(&self) -> ElementRecord {
        let mut r = ElementRecord::zeroed();
        bytemuck::bytes_of_mut(&mut r)[..std::mem::size_of::<Self>()]
            .copy_from_slice(bytemuck::bytes_of(self));
        r
    }

    pub fn decode(r: &ElementRecord) -> Self {
        bytemuck::pod_read_unaligned(&bytemuck::bytes_of(r)[..std::mem::size_of::<Self>()])
    }
}

/// Which record layout a surface's elements use: surfaces of one kind share records.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RecordKind {
    /// [`CornerRecord`], one per coarse triangle.
    Corners,
    /// One record per face of M1 (src/subdiv/data.rs).
    LoopFaces,
}

impl Surface {
    /// The record layout of the surface's elements, from what it declares they are
    /// ([`super::SurfaceFacts::elements`]).
    pub fn record_kind(self) -> RecordKind {
        match self.facts().elements {
            super::Elements::CoarseTriangles => RecordKind::Corners,
            super::Elements::LoopFaces => RecordKind::LoopFaces,
        }
    }
}

/// The elements `kind` describes on `mesh`: for corners, one record per coarse triangle, in
/// triangle order, with geometry normals as `seams` says.
pub fn build_records(kind: RecordKind, mesh: &Mesh, seams: Seams) -> Vec<ElementRecord> {
    match kind {
        RecordKind::Corners => corner_records(mesh, seams)
            .iter()
            .map(CornerRecord::encode)
            .collect(),
        RecordKind::LoopFaces => super::loop_::element_records(mesh),
    }
}

/// Positions that carry more than one distinct normal (hard edges, split normals).
pub fn split_positions(mesh: &Mesh) -> Vec<bool> {
    let mut first: Vec<Option<[u32; 3]>> = vec![None; mesh.positions.len()];
    let mut split = vec![false; mesh.positions.len()];
    for t in &mesh.triangles {
        for k in 0..3 {
            let p = t.p[k] as usize;
            let n = mesh.normals[t.n[k] as usize].to_array().map(f32::to_bits);
            match first[p] {
                None => first[p] = Some(n),
                Some(f) if f != n => split[p] = true,
                _ => {}
            }
        }
    }
    split
}

/// Which edges of a triangle build their geometry from the position normals (closed seams).
/// Bit `k`: PN, stored edge `k` (corners `k`, `k + 1 mod 3`); bit `3 + k`: Phong, the same edge.
/// Mirror: `seam_pn` / `seam_phong` in glsl/include/corners.glsl.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SeamFlags(pub u32);

impl SeamFlags {
    pub fn pn(self, edge: usize) -> bool {
        self.0 >> edge & 1 == 1
    }
    pub fn phong(self, edge: usize) -> bool {
        self.0 >> (3 + edge) & 1 == 1
    }
}

/// One [`CornerRecord`] per triangle of `mesh`.
pub fn corner_records(mesh: &Mesh, seams: Seams) -> Vec<CornerRecord> {
    let mut records: Vec<CornerRecord> = mesh
        .triangles
        .iter()
        .map(|tri| {
            CornerRecord::new(
                tri.p.map(|i| mesh.positions[i as usize]),
                tri.n.map(|i| mesh.normals[i as usize]),
                tri.p,
            )
        })
        .collect();
    let split = split_positions(mesh);
    if seams == Seams::Open || !split.contains(&true) {
        return records;
    }
    let shared =
        crate::mesh::compute_area_weighted_normals(&mesh.positions, &mesh.position_indices());
    for (r, tri) in records.iter_mut().zip(&mesh.triangles) {
        for (k, &p) in tri.p.iter().enumerate() {
            if split[p as usize] {
                r.set_geometry_normal(k, shared[p as usize]);
            }
        }
    }
    // Every side of every edge, by the edge's positions: (triangle, stored edge).
    let mut sides: std::collections::HashMap<(u32, u32), Vec<(usize, usize)>> =
        std::collections::HashMap::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri.p[k], tri.p[(k + 1) % 3]);
            sides.entry((a.min(b), a.max(b))).or_default().push((t, k));
        }
    }
    // The normal side (t, k) has at position `p` (one end of its edge k).
    let normal_at = |(t, k): (usize, usize), p: u32| {
        let r = &records[t];
        let c = if r.idx[k] == p { k } else { (k + 1) % 3 };
        r.normal(c)
    };
    let mut flags = vec![0u32; records.len()];
    for (&(a, b), list) in &sides {
        if !split[a as usize] && !split[b as usize] {
            continue;
        }
        let (pa, pb) = (mesh.positions[a as usize], mesh.positions[b as usize]);
        let first = list[0];
        let differ = |f: &dyn Fn(Vec3, Vec3) -> [u32; 6]| {
            let key = |s| f(normal_at(s, a), normal_at(s, b));
            let k0 = key(first);
            list.iter().any(|&s| key(s) != k0)
        };
        // Phong: the normals at the ends differ between sides.
        let phong = differ(&|na, nb| {
            let (x, y) = (na.to_array(), nb.to_array());
            [x[0], x[1], x[2], y[0], y[1], y[2]].map(f32::to_bits)
        });
        // PN: the edge's two control points differ between sides.
        let pn = phong
            && differ(&|na, nb| {
                let (x, y) = (
                    super::pn::edge_point(pa, pb, na).to_array(),
                    super::pn::edge_point(pb, pa, nb).to_array(),
                );
                [x[0], x[1], x[2], y[0], y[1], y[2]].map(f32::to_bits)
            });
        for &(t, k) in list {
            flags[t] |= (pn as u32) << k | (phong as u32) << (3 + k);
        }
    }
    for (r, f) in records.iter_mut().zip(flags) {
        r.idx[3] = f;
    }
    records
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_support::load_model;

    /// A cube with face normals: every position is split, but its edges are perpendicular to
    /// every normal there, so no PN edge is flagged and pn keeps the cube exactly (every refined
    /// point on a face plane); Phong flags the edges whose normals differ.
    #[test]
    fn straight_hard_edges_are_left_alone_by_pn() {
        let (mesh, _) = load_model("cube_face_normals.obj");
        let records = corner_records(&mesh, Seams::Closed);
        assert!(records
            .iter()
            .all(|r| (0..3).all(|e| !r.seam_flags().pn(e))));
        assert!(records
            .iter()
            .any(|r| (0..3).any(|e| r.seam_flags().phong(e))));
        let params = super::super::SurfaceParams::default();
        let pn = super::super::Mirror::new(
            Surface::Pn,
            super::super::Displace::None,
            &Default::default(),
            &Default::default(),
        )
        .unwrap();
        for (t, r) in records.iter().enumerate() {
            let e = r.encode();
            for (u, v) in [(0.25f32, 0.25f32), (0.5, 0.0), (0.1, 0.7)] {
                let p = pn.eval(&params, t, &e, [1.0 - u - v, u, v]).position;
                let on_face = p.to_array().iter().any(|c| (c.abs() - 1.0).abs() < 1e-6);
                assert!(on_face, "{p} is off the cube");
            }
        }
    }

    /// The cylinder's rims (radial side normals, axial cap normals) are flagged for PN; the
    /// vertical side edges, whose two sides agree, are not; open seams flag nothing.
    #[test]
    fn only_disagreeing_edges_are_flagged() {
        let (mesh, _) = load_model("cylinder_hard_normals.obj");
        let closed = corner_records(&mesh, Seams::Closed);
        let flagged: usize = closed
            .iter()
            .map(|r| (0..3).filter(|&e| r.seam_flags().pn(e)).count())
            .sum();
        let split = split_positions(&mesh);
        let seam_edges: usize = closed
            .iter()
            .map(|r| {
                (0..3)
                    .filter(|&e| split[r.idx[e] as usize] && split[r.idx[(e + 1) % 3] as usize])
                    .count()
            })
            .sum();
        assert!(
            flagged > 0 && flagged <= seam_edges,
            "{flagged} of {seam_edges}"
        );
        assert!(corner_records(&mesh, Seams::Open)
            .iter()
            .all(|r| r.idx[3] == 0 && r.p.iter().all(|p| p[3] == SMOOTH_CORNER)));
    }

    #[test]
    fn octahedral_round_trip() {
        for n in [
            Vec3::X,
            -Vec3::Z,
            Vec3::new(0.3, -0.5, -0.8).normalize(),
            Vec3::new(-0.6, 0.1, 0.79).normalize(),
        ] {
            assert!((oct_decode(oct_encode(n)) - n).length() < 1e-6, "{n}");
        }
    }
}
