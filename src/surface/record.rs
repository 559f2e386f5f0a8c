//! The per-coarse-triangle record, identical in Rust and GLSL (`struct CoarseTri` in
//! `glsl/include/records.glsl`). Drivers hand it to the evaluation stage as push constants (`push`),
//! a dynamic uniform buffer (`ubo`) or a storage buffer entry (`instanced`, `tess`).

use crate::mesh::Mesh;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// 112 bytes, std140 = std430 = scalar layout (only `vec4`/`uvec4`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct CoarseTri {
    /// Corner positions (`xyz`, `w` = 1).
    pub p: [[f32; 4]; 3],
    /// Corner normals (`xyz`, `w` = 0).
    pub n: [[f32; 4]; 3],
    /// Global position index of each corner (canonical ordering key), then the triangle's index.
    pub idx: [u32; 4],
}

const _: () = {
    assert!(std::mem::size_of::<CoarseTri>() == 112);
    assert!(std::mem::offset_of!(CoarseTri, p) == 0);
    assert!(std::mem::offset_of!(CoarseTri, n) == 48);
    assert!(std::mem::offset_of!(CoarseTri, idx) == 96);
};

impl CoarseTri {
    pub fn new(p: [Vec3; 3], n: [Vec3; 3], idx: [u32; 3], triangle: u32) -> Self {
        Self {
            p: p.map(|v| v.extend(1.0).to_array()),
            n: n.map(|v| v.extend(0.0).to_array()),
            idx: [idx[0], idx[1], idx[2], triangle],
        }
    }
}

/// One record per triangle of `mesh`, in triangle order.
pub fn build_records(mesh: &Mesh) -> Vec<CoarseTri> {
    mesh.triangles
        .iter()
        .enumerate()
        .map(|(t, tri)| {
            CoarseTri::new(
                tri.p.map(|i| mesh.positions[i as usize]),
                tri.n.map(|i| mesh.normals[i as usize]),
                tri.p,
                t as u32,
            )
        })
        .collect()
}
