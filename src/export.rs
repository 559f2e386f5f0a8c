//! `meshrefine export`: the refined mesh as the GPU evaluated it. The vertices come from the
//! capture variant of the chosen driver's real drawing pipeline; here they are welded (equal
//! position bits become one vertex: shared coarse edges weld because refinement is watertight)
//! and connected with the pattern's triangles.
#![forbid(unsafe_code)]

use crate::pattern::Pattern;
use crate::render::CaptureResult;
use glam::Vec3;
use std::collections::HashMap;
use std::fmt::Write as _;

/// A welded triangle mesh with separately indexed normals (OBJ's `v`/`vn`).
#[derive(Clone, Debug, Default)]
pub struct RefinedMesh {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    /// Per corner: (position index, normal index).
    pub triangles: Vec<[(u32, u32); 3]>,
}

/// Weld captured vertices. Fails if the capture misses a vertex (its `w` was never set to 1).
pub fn weld(capture: &CaptureResult, pattern: &Pattern) -> Result<RefinedMesh, String> {
    let pv = capture.pattern_vertex_count as usize;
    if pattern.bary.len() != pv {
        return Err(format!(
            "capture holds {pv} vertices per triangle, the pattern {}",
            pattern.bary.len()
        ));
    }
    let mut out = RefinedMesh::default();
    let mut pos_index: HashMap<[u32; 3], u32> = HashMap::new();
    let mut nrm_index: HashMap<[u32; 3], u32> = HashMap::new();
    let bits = |v: Vec3| {
        (v + Vec3::ZERO)
            .to_array()
            .map(|x| if x == 0.0 { 0 } else { x.to_bits() })
    };
    let mut remap = Vec::with_capacity(capture.vertices.len());
    for (k, v) in capture.vertices.iter().enumerate() {
        if v.position[3] != 1.0 {
            return Err(format!(
                "the GPU did not write vertex {} of coarse triangle {}",
                k % pv,
                k / pv
            ));
        }
        let p = Vec3::from_slice(&v.position[..3]);
        let n = Vec3::from_slice(&v.normal[..3]);
        let pi = *pos_index.entry(bits(p)).or_insert_with(|| {
            out.positions.push(p);
            out.positions.len() as u32 - 1
        });
        let ni = *nrm_index.entry(bits(n)).or_insert_with(|| {
            out.normals.push(n);
            out.normals.len() as u32 - 1
        });
        remap.push((pi, ni));
    }
    let local = pattern.triangles();
    for t in 0..capture.vertices.len() / pv {
        for tri in &local {
            out.triangles.push(tri.map(|i| remap[t * pv + i as usize]));
        }
    }
    Ok(out)
}

/// Wavefront OBJ text (`v`, `vn`, `f v//vn`), with `header` lines as comments.
pub fn to_obj(mesh: &RefinedMesh, header: &[String]) -> String {
    let mut s = String::with_capacity(mesh.positions.len() * 40 + mesh.triangles.len() * 30);
    for h in header {
        let _ = writeln!(s, "# {h}");
    }
    for p in &mesh.positions {
        let _ = writeln!(s, "v {} {} {}", p.x, p.y, p.z);
    }
    for n in &mesh.normals {
        let _ = writeln!(s, "vn {} {} {}", n.x, n.y, n.z);
    }
    for t in &mesh.triangles {
        let _ = writeln!(
            s,
            "f {}//{} {}//{} {}//{}",
            t[0].0 + 1,
            t[0].1 + 1,
            t[1].0 + 1,
            t[1].1 + 1,
            t[2].0 + 1,
            t[2].1 + 1
        );
    }
    s
}
