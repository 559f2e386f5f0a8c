//! Splitting chosen triangles at their centroids (1-to-3), for surfaces whose restrictions a
//! triangle breaks (scalar-tagged PN allows at most two crease corners per triangle: each of the
//! three new triangles has two of the old corners and the new, smooth, centroid vertex).
//!
//! The old edges are kept as they are, so every neighbour still shares them with the same two
//! corners: refinement stays watertight. The new vertex takes the mean of the corners' normals
//! (normalized) and texture coordinates; orientation is kept.
#![forbid(unsafe_code)]

use super::{Mesh, Triangle};
use glam::Vec3;

impl Mesh {
    /// Splits each triangle of `which` (indices into [`Mesh::triangles`], each once) at its
    /// centroid. The first of its three triangles replaces it, the other two are appended, in
    /// the order of `which`; returns, for every triangle of the result, the index of the
    /// triangle it came from. Fails (changing nothing) when a centroid falls on an existing
    /// position, which positions being unique forbids, or its normal mean is zero.
    pub fn split_at_centroids(&mut self, which: &[usize]) -> Result<Vec<usize>, String> {
        let existing: std::collections::HashSet<[u32; 3]> = self
            .positions
            .iter()
            .map(|p| p.to_array().map(f32::to_bits))
            .collect();
        let computed =
            self.normals.len() == self.positions.len() && self.triangles.iter().all(|t| t.n == t.p);
        let mut new_positions = Vec::with_capacity(which.len());
        let mut new_normals = Vec::with_capacity(which.len());
        let mut new_uvs = Vec::new();
        for &i in which {
            let t = self.triangles[i];
            let [a, b, c] = t.p.map(|k| self.positions[k as usize].as_dvec3());
            let centroid = ((a + b + c) / 3.0).as_vec3() + Vec3::ZERO;
            if existing.contains(&centroid.to_array().map(f32::to_bits)) {
                return Err(format!(
                    "the centroid of triangle {i} (0-based) is already a vertex"
                ));
            }
            let n: Vec3 = t.n.iter().map(|&k| self.normals[k as usize]).sum();
            let n = n.normalize_or_zero();
            if n == Vec3::ZERO {
                return Err(format!(
                    "the corners' normals of triangle {i} (0-based) cancel out"
                ));
            }
            new_positions.push(centroid);
            new_normals.push(n);
            if let Some(uv) = t.t {
                let uv = uv.map(|k| self.texcoords[k as usize]);
                new_uvs.push((uv[0] + uv[1] + uv[2]) / 3.0);
            }
        }
        let mut origin: Vec<usize> = (0..self.triangles.len()).collect();
        let mut uv_next = self.texcoords.len() as u32;
        for (k, &i) in which.iter().enumerate() {
            let t = self.triangles[i];
            let p = self.positions.len() as u32;
            self.positions.push(new_positions[k]);
            let n = if computed {
                debug_assert_eq!(self.normals.len() as u32, p);
                p
            } else {
                self.normals.len() as u32
            };
            self.normals.push(new_normals[k]);
            let uv = t.t.map(|_| {
                uv_next += 1;
                uv_next - 1
            });
            let corner = |j: usize, l: usize| Triangle {
                p: [t.p[j], t.p[l], p],
                n: [t.n[j], t.n[l], n],
                t: t.t.zip(uv).map(|(tt, u)| [tt[j], tt[l], u]),
            };
            self.triangles[i] = corner(0, 1);
            self.triangles.push(corner(1, 2));
            self.triangles.push(corner(2, 0));
            origin.extend([i, i]);
        }
        self.texcoords.extend(new_uvs);
        Ok(origin)
    }
}

#[cfg(test)]
mod tests {
    use crate::mesh::test_support::load_model;
    use glam::Vec3;

    #[test]
    fn split_triangles_keep_the_edges_orientation_and_area() {
        let (mesh, _) = load_model("grid_uv_8x8.obj");
        let mut split = mesh.clone();
        let origin = split.split_at_centroids(&[0, 5]).unwrap();
        assert_eq!(split.triangles.len(), mesh.triangles.len() + 4);
        assert_eq!(split.positions.len(), mesh.positions.len() + 2);
        assert_eq!(&origin[mesh.triangles.len()..], [0, 0, 5, 5]);
        let area = |m: &crate::mesh::Mesh, t: usize| {
            let [a, b, c] = m.triangles[t].p.map(|i| m.positions[i as usize]);
            (b - a).cross(c - a)
        };
        for i in [0, 5] {
            let parts: Vec<usize> = (0..split.triangles.len())
                .filter(|&t| origin[t] == i)
                .collect();
            assert_eq!(parts.len(), 3);
            let sum: Vec3 = parts.iter().map(|&t| area(&split, t)).sum();
            // Same orientation and total area as the triangle split (within rounding).
            assert!(
                (sum - area(&mesh, i)).length() < 1e-5 * area(&mesh, i).length(),
                "{sum}"
            );
            for &t in &parts {
                assert!(area(&split, t).dot(area(&mesh, i)) > 0.0);
                // Each part keeps one old edge whole, with its two corners in order.
                let old = mesh.triangles[i].p;
                let new = split.triangles[t].p;
                assert!((0..3).any(|k| new[0] == old[k] && new[1] == old[(k + 1) % 3]));
                assert!(split.triangles[t].t.is_some());
            }
        }
        // The rest is untouched; the topology stays closed where it was (no new boundary).
        assert_eq!(split.stats().boundary_edges, mesh.stats().boundary_edges);
        assert_eq!(split.stats().nonmanifold_edges, 0);
        assert!(split
            .normals
            .iter()
            .all(|n| (n.length() - 1.0).abs() < 1e-5));
    }
}
