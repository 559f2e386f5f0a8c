//! Element records: what a driver hands, unopened, to the surface for each element it samples.
//!
//! Every record is [`RECORD_BYTES`] bytes (`struct ElementRecord` in `glsl/include/records.glsl`:
//! seven `uvec4`), small enough to be pushed with the draw words inside the 128 bytes of push
//! constants every device offers. Drivers only move records around (push constants, a dynamic
//! uniform buffer, a storage buffer indexed by element); each surface owns the layout of the
//! bytes inside, how it builds them from the mesh, and decodes them itself.
//!
//! The local surfaces (`flat`, `phong`, `pn`) share one layout, [`CornerRecord`]: the coarse
//! triangle's corner positions and normals and the corners' global vertex indices (the canonical
//! ordering key). Loop's elements will be M1 faces whose record holds one-ring indices into a
//! buffer of its own.

use super::Surface;
use crate::mesh::Mesh;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

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
    /// Corner positions (`xyz`, `w` = 1).
    pub p: [[f32; 4]; 3],
    /// Corner unit normals (`xyz`, `w` = 0).
    pub n: [[f32; 4]; 3],
    /// Global position index of each corner (the canonical ordering key), then the triangle's
    /// index in the mesh.
    pub idx: [u32; 4],
}

const _: () = {
    assert!(std::mem::size_of::<CornerRecord>() <= RECORD_BYTES);
    assert!(std::mem::offset_of!(CornerRecord, p) == 0);
    assert!(std::mem::offset_of!(CornerRecord, n) == 48);
    assert!(std::mem::offset_of!(CornerRecord, idx) == 96);
};

impl CornerRecord {
    pub fn new(p: [Vec3; 3], n: [Vec3; 3], idx: [u32; 3], triangle: u32) -> Self {
        Self {
            p: p.map(|v| v.extend(1.0).to_array()),
            n: n.map(|v| v.extend(0.0).to_array()),
            idx: [idx[0], idx[1], idx[2], triangle],
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
}

impl Surface {
    pub fn record_kind(self) -> RecordKind {
        match self {
            Surface::Flat | Surface::Phong | Surface::Pn => RecordKind::Corners,
        }
    }
}

/// The elements `kind` describes on `mesh`: for corners, one record per coarse triangle, in
/// triangle order.
pub fn build_records(kind: RecordKind, mesh: &Mesh) -> Vec<ElementRecord> {
    match kind {
        RecordKind::Corners => corner_records(mesh)
            .iter()
            .map(CornerRecord::encode)
            .collect(),
    }
}

/// One [`CornerRecord`] per triangle of `mesh`.
pub fn corner_records(mesh: &Mesh) -> Vec<CornerRecord> {
    mesh.triangles
        .iter()
        .enumerate()
        .map(|(t, tri)| {
            CornerRecord::new(
                tri.p.map(|i| mesh.positions[i as usize]),
                tri.n.map(|i| mesh.normals[i as usize]),
                tri.p,
                t as u32,
            )
        })
        .collect()
}
