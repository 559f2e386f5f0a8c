//! Triangulating an OBJ polygon (a face of more than three corners): a convex polygon as a fan
//! from its first corner (`0 1 2`, `0 2 3`, ...: what `tobj` makes, and what a reader of the file
//! expects), a concave one by ear clipping in its plane, so that its triangles cover it exactly,
//! without overlapping or turning over where a fan would.
#![forbid(unsafe_code)]

use glam::{DVec2, DVec3, Vec3};

/// Polygons with more corners than this are fanned whatever their shape (ear clipping takes a
/// time that grows with the cube of the corners in the worst case).
pub const MAX_CLIPPED_CORNERS: usize = 1024;

/// The triangles of the polygon with corner positions `corners` (in the face's order), as
/// triples of corner numbers wound as the polygon is: a fan where the polygon is convex (or
/// has no plane: every corner on a line, or more corners than [`MAX_CLIPPED_CORNERS`]), else
/// its ears clipped one by one.
pub fn triangulate(corners: &[Vec3]) -> Vec<[usize; 3]> {
    let n = corners.len();
    let fan = || (2..n).map(|k| [0, k - 1, k]).collect();
    if n <= 3 || n > MAX_CLIPPED_CORNERS {
        return fan();
    }
    let Some(flat) = in_plane(corners) else {
        return fan();
    };
    let turn = |a: usize, b: usize, c: usize| cross(flat[b] - flat[a], flat[c] - flat[b]);
    if (0..n).all(|i| turn((i + n - 1) % n, i, (i + 1) % n) >= 0.0) {
        return fan();
    }
    clip_ears(&flat).unwrap_or_else(fan)
}

/// The corners in the polygon's plane (Newell's normal: counter-clockwise seen from it), in
/// `f64`; `None` where the polygon has no area to give a plane.
fn in_plane(corners: &[Vec3]) -> Option<Vec<DVec2>> {
    let p: Vec<DVec3> = corners.iter().map(|c| c.as_dvec3()).collect();
    let centre = p.iter().sum::<DVec3>() / p.len() as f64;
    let mut normal = DVec3::ZERO;
    for (i, &a) in p.iter().enumerate() {
        let b = p[(i + 1) % p.len()];
        normal += (a - centre).cross(b - centre);
    }
    let normal = normal.try_normalize()?;
    let u = normal.any_orthonormal_vector();
    let v = normal.cross(u);
    Some(
        p.iter()
            .map(|&q| DVec2::new((q - centre).dot(u), (q - centre).dot(v)))
            .collect(),
    )
}

fn cross(a: DVec2, b: DVec2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Whether `p` lies inside triangle `a b c` (counter-clockwise) or on its sides.
fn inside(p: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    cross(b - a, p - a) >= 0.0 && cross(c - b, p - b) >= 0.0 && cross(a - c, p - c) >= 0.0
}

/// Ear clipping of a counter-clockwise polygon: each step cuts off a corner that turns left and
/// whose triangle holds no other remaining corner (a corner on a line with its neighbours is
/// cut off last, as a sliver, where nothing else is left to cut). `None` where no corner can be
/// cut (the polygon crosses itself).
fn clip_ears(p: &[DVec2]) -> Option<Vec<[usize; 3]>> {
    let mut left: Vec<usize> = (0..p.len()).collect();
    let mut out = Vec::with_capacity(p.len() - 2);
    while left.len() > 3 {
        let m = left.len();
        let corner = |k: usize| (left[(k + m - 1) % m], left[k], left[(k + 1) % m]);
        let ear = |k: usize, strict: bool| {
            let (a, b, c) = corner(k);
            let turn = cross(p[b] - p[a], p[c] - p[b]);
            let turns = if strict { turn > 0.0 } else { turn >= 0.0 };
            turns
                && left.iter().all(|&q| {
                    q == a
                        || q == b
                        || q == c
                        || p[q] == p[a]
                        || p[q] == p[b]
                        || p[q] == p[c]
                        || !inside(p[q], p[a], p[b], p[c])
                })
        };
        let k = (0..m)
            .find(|&k| ear(k, true))
            .or_else(|| (0..m).find(|&k| ear(k, false)))?;
        let (a, b, c) = corner(k);
        out.push([a, b, c]);
        left.remove(k);
    }
    out.push([left[0], left[1], left[2]]);
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Twice the signed area of triangle `t` of `p` in the plane z = 0.
    fn area(p: &[Vec3], t: [usize; 3]) -> f64 {
        let [a, b, c] = t.map(|i| p[i].as_dvec3().truncate());
        cross(b - a, c - a)
    }

    fn polygon_area(p: &[Vec3]) -> f64 {
        (0..p.len())
            .map(|i| {
                cross(
                    p[i].as_dvec3().truncate(),
                    p[(i + 1) % p.len()].as_dvec3().truncate(),
                )
            })
            .sum()
    }

    #[test]
    fn convex_polygons_are_fans() {
        let hexagon: Vec<Vec3> = (0..6)
            .map(|k| {
                let a = k as f32 * std::f32::consts::TAU / 6.0;
                Vec3::new(a.cos(), a.sin(), 0.3)
            })
            .collect();
        assert_eq!(
            triangulate(&hexagon),
            vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]]
        );
        // A quad with a corner on the line of its neighbours is still a fan.
        let quad = [
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
        ];
        assert_eq!(triangulate(&quad), vec![[0, 1, 2], [0, 2, 3]]);
    }

    /// A star and an arrow, counter-clockwise and clockwise: their triangles are as many as a
    /// fan's, wound as the polygon is, and cover exactly its area (no overlap, none turned
    /// over), in any plane.
    #[test]
    fn concave_polygons_are_covered_exactly() {
        let star: Vec<Vec3> = (0..10)
            .map(|k| {
                let (r, a) = (
                    if k % 2 == 0 { 1.0 } else { 0.3 },
                    k as f32 * 0.2 * std::f32::consts::PI,
                );
                Vec3::new(r * a.cos(), r * a.sin(), 0.0)
            })
            .collect();
        let arrow = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(2.0, 1.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
            Vec3::new(0.7, 1.0, 0.0),
        ];
        for shape in [star, arrow] {
            for reversed in [false, true] {
                let mut p = shape.clone();
                if reversed {
                    p.reverse();
                }
                let tris = triangulate(&p);
                assert_eq!(tris.len(), p.len() - 2);
                let whole = polygon_area(&p);
                let sum: f64 = tris.iter().map(|&t| area(&p, t)).sum();
                assert!((sum - whole).abs() < 1e-6 * whole.abs(), "{sum} {whole}");
                for &t in &tris {
                    assert!(area(&p, t) * whole > 0.0, "{t:?} turned over");
                }
                // Tilted out of z = 0 (a rotation keeps which triangles it makes).
                let q = glam::Quat::from_rotation_x(0.7) * glam::Quat::from_rotation_y(-1.2);
                let tilted: Vec<Vec3> = p.iter().map(|&v| q * v + Vec3::splat(5.0)).collect();
                assert_eq!(triangulate(&tilted), tris);
            }
        }
    }

    #[test]
    fn polygons_without_a_plane_are_fans() {
        let line = [
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
        ];
        assert_eq!(triangulate(&line), vec![[0, 1, 2], [0, 2, 3]]);
    }
}
