//! Random but consistent per-element levels for the adaptive drawing tests.

use meshrefine::lod::levels::ElementLevels;
use meshrefine::render::Scene;
use meshrefine::surface::Surface;
use std::collections::HashMap;

/// A small deterministic generator (xorshift) for the random levels.
pub struct Rng(pub u32);

impl Rng {
    pub fn unit(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 17;
        self.0 ^= self.0 << 5;
        (self.0 >> 8) as f32 / (1 << 24) as f32
    }
}

/// The corners (global vertex indices) of each element `surface` draws in `scene`: coarse
/// triangles, or Loop's M1 faces (prepared).
pub fn element_corners(scene: &Scene, surface: Surface) -> Vec<[u32; 3]> {
    match &scene.loop_ {
        Some(l) if surface.uses_loop_faces() => l.data.m1.faces.clone(),
        _ => scene.data.mesh.triangles.iter().map(|t| t.p).collect(),
    }
}

/// Random but consistent levels up to `max`: one random (real) level per unique edge, shared by
/// the elements on both sides, an inner level at least the largest of its edges', and a fraction
/// `culled` of the elements culled (inner level 0, edges kept).
pub fn random_levels(corners: &[[u32; 3]], max: u32, culled: f32, seed: u32) -> Vec<ElementLevels> {
    let mut rng = Rng(seed | 1);
    let mut edge: HashMap<(u32, u32), f32> = HashMap::new();
    corners
        .iter()
        .map(|c| {
            let edges = [0, 1, 2].map(|k| {
                let (a, b) = (c[k], c[(k + 1) % 3]);
                *edge
                    .entry((a.min(b), a.max(b)))
                    .or_insert_with(|| 1.0 + rng.unit() * (max as f32 - 1.0))
            });
            let top = edges.iter().fold(1.0f32, |m, &e| m.max(e));
            let inner = top + rng.unit() * (max as f32 - top);
            let inner = if rng.unit() < culled { 0.0 } else { inner };
            ElementLevels { edges, inner }
        })
        .collect()
}

/// Distinct vertices of a crack-free tessellation of `corners` at `levels`, each element's
/// outer and inner tessellation levels given by `tess` (`tess::outer_levels`, or
/// `tess::morph::morph_levels` when geomorphing): every corner once, each unique edge its own
/// level's inner samples, each element the inner rings of its inner level.
pub fn crack_free_vertices(
    corners: &[[u32; 3]],
    levels: &[ElementLevels],
    tess: impl Fn(&ElementLevels) -> Option<([u32; 3], u32)>,
) -> usize {
    let mut vertices = std::collections::HashSet::new();
    let mut edge_samples = HashMap::new();
    let mut inside = 0;
    for (c, l) in corners.iter().zip(levels) {
        let (outer, inner) = tess(l).unwrap();
        inside += (meshrefine::render::tess::tess_vertex_count(inner) - 3 * inner) as usize;
        for i in 0..3 {
            vertices.insert(c[i]);
            // gl_TessLevelOuter[i]: stored edge i + 1, corners i + 1 and i + 2.
            let (a, b) = (c[(i + 1) % 3], c[(i + 2) % 3]);
            edge_samples.insert((a.min(b), a.max(b)), outer[i] as usize - 1);
        }
    }
    vertices.len() + edge_samples.values().sum::<usize>() + inside
}

/// Welded edges (vertex ids `.0` of each corner) shared by other than two triangles: 0 for a
/// closed mesh.
pub fn open_edges(triangles: &[[(u32, u32); 3]]) -> usize {
    let mut count: HashMap<(u32, u32), u32> = HashMap::new();
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k].0, t[(k + 1) % 3].0);
            *count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    count.values().filter(|&&c| c != 2).count()
}
