//! The CPU side of a mesh ready to draw: the mesh and the records its elements are drawn from
//! ([`super::GpuMesh`] holds their GPU copy).

use crate::mesh::Mesh;
use crate::surface::{build_records, ElementRecord, RecordKind, Seams};

/// CPU-side data of a mesh ready to draw: the mesh and its elements' records.
#[derive(Clone, Debug)]
pub struct MeshData {
    pub mesh: Mesh,
    pub kind: RecordKind,
    /// The seams the records were built for.
    pub seams: Seams,
    pub records: Vec<ElementRecord>,
    /// Each element's texture coordinates (stored corner order), when every triangle has them.
    pub uvs: Option<Vec<[[f32; 2]; 3]>>,
    /// Mean longest texture-space edge of the elements (0 without coordinates).
    pub uv_extent: f32,
}

impl MeshData {
    pub fn new(mesh: Mesh, kind: RecordKind, seams: Seams) -> Self {
        let records = build_records(kind, &mesh, seams);
        let uvs: Option<Vec<[[f32; 2]; 3]>> = mesh
            .triangles
            .iter()
            .map(|t| {
                t.t.map(|c| c.map(|i| mesh.texcoords[i as usize].to_array()))
            })
            .collect();
        let uv_extent = uvs.as_ref().map_or(0.0, |uvs| {
            let longest = |t: &[[f32; 2]; 3]| {
                (0..3)
                    .map(|k| {
                        let (a, b) = (glam::Vec2::from(t[k]), glam::Vec2::from(t[(k + 1) % 3]));
                        (a - b).length() as f64
                    })
                    .fold(0.0, f64::max)
            };
            (uvs.iter().map(longest).sum::<f64>() / uvs.len().max(1) as f64) as f32
        });
        Self {
            mesh,
            kind,
            seams,
            records,
            uvs,
            uv_extent,
        }
    }
}
