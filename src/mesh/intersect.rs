//! Whether a triangle mesh intersects itself: two triangles that meet anywhere but along an
//! edge or at a corner they share. A closed mesh that does hides not all of its faces facing
//! away from an eye outside it (a fold shows its back side), so facing-away culling needs it not
//! to ([`super::Mesh::self_intersects`]).

use glam::DVec3;
use std::collections::{HashMap, HashSet};

/// Whether any two of `tris` (indices into `positions`) meet other than along a shared edge or
/// at a shared corner. Coplanar overlaps are not looked for. Candidate pairs come from a uniform
/// grid of cells about the mean triangle size, so the cost is about linear for meshes whose
/// triangles are of similar size.
pub fn self_intersects(positions: &[glam::Vec3], tris: &[[u32; 3]]) -> bool {
    let at = |i: u32| {
        positions
            .get(i as usize)
            .map_or(DVec3::ZERO, |p| p.as_dvec3())
    };
    let corners: Vec<[DVec3; 3]> = tris.iter().map(|t| t.map(at)).collect();
    if corners.len() < 2 {
        return false;
    }
    let boxes: Vec<(DVec3, DVec3)> = (corners.iter())
        .map(|c| (c[0].min(c[1]).min(c[2]), c[0].max(c[1]).max(c[2])))
        .collect();
    let lo = boxes.iter().fold(DVec3::INFINITY, |a, b| a.min(b.0));
    let hi = boxes.iter().fold(DVec3::NEG_INFINITY, |a, b| a.max(b.1));
    if !(lo.is_finite() && hi.is_finite()) {
        return false;
    }
    let mean = boxes.iter().map(|b| (b.1 - b.0).max_element()).sum::<f64>() / boxes.len() as f64;
    // Cells about a triangle's size, at most 256 along the largest side.
    let span = (hi - lo).max_element().max(f64::MIN_POSITIVE);
    let cell = mean.max(span / 256.0).max(f64::MIN_POSITIVE);
    let index = |p: DVec3| ((p - lo) / cell).floor().as_ivec3();
    let mut cells: HashMap<glam::IVec3, Vec<u32>> = HashMap::new();
    for (t, b) in boxes.iter().enumerate() {
        let (a, z) = (index(b.0), index(b.1));
        for x in a.x..=z.x {
            for y in a.y..=z.y {
                for w in a.z..=z.z {
                    cells
                        .entry(glam::IVec3::new(x, y, w))
                        .or_default()
                        .push(t as u32);
                }
            }
        }
    }
    let scale = span;
    let mut tested: HashSet<(u32, u32)> = HashSet::new();
    for list in cells.values() {
        for (k, &i) in list.iter().enumerate() {
            for &j in &list[k + 1..] {
                let (i, j) = (i.min(j), i.max(j));
                let (bi, bj) = (boxes[i as usize], boxes[j as usize]);
                if (bi.1.cmplt(bj.0) | bj.1.cmplt(bi.0)).any() || !tested.insert((i, j)) {
                    continue;
                }
                let (ti, tj) = (tris[i as usize], tris[j as usize]);
                if pair_meets(&corners[i as usize], &ti, &corners[j as usize], &tj, scale) {
                    return true;
                }
            }
        }
    }
    false
}

/// Whether triangles `a` and `b` (their position indices `ai`, `bi`) meet other than along a
/// shared edge or at a shared corner: an edge of one crosses the other (two non-coplanar
/// triangles that meet do so along a segment whose ends lie on their edges).
fn pair_meets(a: &[DVec3; 3], ai: &[u32; 3], b: &[DVec3; 3], bi: &[u32; 3], scale: f64) -> bool {
    // Corners shared by index or by position (a mesh may repeat a position, as at a seam).
    let shared: Vec<DVec3> = (0..3)
        .filter(|&k| bi.contains(&ai[k]) || b.contains(&a[k]))
        .map(|k| a[k])
        .collect();
    if shared.len() >= 2 {
        // Two triangles on one edge meet only along it unless coplanar.
        return false;
    }
    let corner = shared.first().copied();
    let near = 1e-6 * scale;
    for (tri, other) in [(a, b), (b, a)] {
        for k in 0..3 {
            if let Some(hit) = segment_hit(tri[k], tri[(k + 1) % 3], other) {
                if corner.is_none_or(|c| (hit - c).length() > near) {
                    return true;
                }
            }
        }
    }
    false
}

/// Where segment `p q` crosses triangle `t` (Möller and Trumbore), if it does; a segment in
/// the triangle's plane does not count.
fn segment_hit(p: DVec3, q: DVec3, t: &[DVec3; 3]) -> Option<DVec3> {
    let dir = q - p;
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let pvec = dir.cross(e2);
    let det = e1.dot(pvec);
    if det.abs() <= 1e-12 * e1.length() * e2.length() * dir.length() {
        return None;
    }
    let inv = 1.0 / det;
    let tvec = p - t[0];
    let u = tvec.dot(pvec) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let qvec = tvec.cross(e1);
    let v = dir.dot(qvec) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let s = e2.dot(qvec) * inv;
    (0.0..=1.0).contains(&s).then(|| p + dir * s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_support::load_model;
    use glam::Vec3;

    /// Closed meshes of the models that do not fold do not intersect themselves; two
    /// tetrahedra pushed into each other do, two apart do not, and Spot's cage does.
    #[test]
    fn self_intersections_are_found() {
        for file in [
            "tetrahedron.obj",
            "icosahedron.obj",
            "uvsphere12.obj",
            "torus_16x8.obj",
        ] {
            let m = load_model(file).0;
            assert!(
                !self_intersects(&m.positions, &m.position_indices()),
                "{file}"
            );
        }
        let tet = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
        let faces = [[0u32, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        let two = |offset: Vec3| {
            let mut p = tet.to_vec();
            p.extend(tet.iter().map(|v| *v + offset));
            let mut t = faces.to_vec();
            t.extend(faces.iter().map(|f| f.map(|i| i + 4)));
            (p, t)
        };
        let (p, t) = two(Vec3::splat(0.2));
        assert!(self_intersects(&p, &t));
        let (p, t) = two(Vec3::new(3.0, 0.0, 0.0));
        assert!(!self_intersects(&p, &t));
        // Spot's control cage folds where the head meets the body (a face facing away is seen
        // there from outside, before one facing the eye).
        let spot = load_model("spot_control_tri.obj").0;
        assert!(self_intersects(&spot.positions, &spot.position_indices()));
    }
}
