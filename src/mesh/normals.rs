//! Vertex normals and the per-triangle geometry tests shared by loading and animation.
//!
//! All cross products are taken in `f64`: `f32` inputs cannot overflow or lose the
//! zero-area decision there, whatever their magnitude.

use glam::{DVec3, Vec3};

/// The normal given to a vertex that no triangle uses (or whose surrounding triangles
/// cancel out exactly), so that every normal stays unit length.
pub const FALLBACK_NORMAL: Vec3 = Vec3::Z;

/// Area-weighted vertex normals: for each position, the normalized sum of the (unnormalized)
/// cross products of the triangles that use it, i.e. face normals weighted by twice their
/// area.
///
/// Returns one unit-length normal per position. A position used by no triangle, or whose
/// weighted sum vanishes, gets the sum of the unit face normals around it instead, and
/// [`FALLBACK_NORMAL`] if that vanishes too. Triangles with an index out of range are
/// ignored; this function never panics.
pub fn compute_area_weighted_normals(positions: &[Vec3], tris: &[[u32; 3]]) -> Vec<Vec3> {
    let mut weighted = vec![DVec3::ZERO; positions.len()];
    let mut unit = vec![DVec3::ZERO; positions.len()];
    for tri in tris {
        let Some([a, b, c]) = corners(positions, *tri) else {
            continue;
        };
        let cross = face_cross(a, b, c);
        let unit_cross = cross.try_normalize().unwrap_or(DVec3::ZERO);
        for &i in tri {
            weighted[i as usize] += cross;
            unit[i as usize] += unit_cross;
        }
    }
    weighted
        .iter()
        .zip(&unit)
        .map(|(w, u)| {
            w.try_normalize()
                .or_else(|| u.try_normalize())
                .map_or(FALLBACK_NORMAL, |n| n.as_vec3())
        })
        .collect()
}

/// The three corner positions of `tri`, or `None` if an index is out of range.
pub(crate) fn corners(positions: &[Vec3], tri: [u32; 3]) -> Option<[Vec3; 3]> {
    Some([
        *positions.get(tri[0] as usize)?,
        *positions.get(tri[1] as usize)?,
        *positions.get(tri[2] as usize)?,
    ])
}

/// `(b - a) x (c - a)` in double precision: its direction is the face normal of the
/// counter-clockwise triangle `a, b, c`, its length twice the area.
pub(crate) fn face_cross(a: Vec3, b: Vec3, c: Vec3) -> DVec3 {
    let (a, b, c) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
    (b - a).cross(c - a)
}

/// Whether a triangle has zero area: `|cross| <= 1e-12 * (longest edge)^2`.
pub(crate) fn is_zero_area(a: Vec3, b: Vec3, c: Vec3) -> bool {
    let (da, db, dc) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
    let longest_sq = (db - da)
        .length_squared()
        .max((dc - db).length_squared())
        .max((da - dc).length_squared());
    face_cross(a, b, c).length() <= 1e-12 * longest_sq
}

/// Why a triangle whose area is not zero is dropped as if it were ([`is_zero_area`]): a needle
/// whose normal and shading are at the mercy of rounding.
pub(crate) const SLIVER: &str =
    "is a sliver too thin to draw (twice its area is at most 1e-12 of its longest edge squared)";

/// Why the triangle `a, b, c` cannot be drawn, or `None`: it has zero area ([`is_zero_area`]:
/// exactly, or a [`SLIVER`]),
/// or its area or an edge is not representable as a normal `f32` (twice the area below
/// `f32::MIN_POSITIVE`, which underflows to a subnormal or zero where the GPU or a surface
/// computes it in single precision, or an edge or twice the area above `f32::MAX`, which
/// overflows to infinity).
pub(crate) fn degenerate_reason(a: Vec3, b: Vec3, c: Vec3) -> Option<&'static str> {
    if is_zero_area(a, b, c) {
        return Some(if face_cross(a, b, c) == DVec3::ZERO {
            "has zero area"
        } else {
            SLIVER
        });
    }
    let (da, db, dc) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
    let longest = (db - da)
        .length()
        .max((dc - db).length())
        .max((da - dc).length());
    let twice_area = face_cross(a, b, c).length();
    if twice_area < f64::from(f32::MIN_POSITIVE) {
        Some("has an area too small for f32 (it underflows)")
    } else if twice_area > f64::from(f32::MAX) || longest > f64::from(f32::MAX) {
        Some("has an area or edge too large for f32 (it overflows)")
    } else {
        None
    }
}

/// `v` scaled to unit length (computed in `f64`), or `None` if it is zero, NaN or infinite.
pub(crate) fn unit(v: Vec3) -> Option<Vec3> {
    v.as_dvec3().try_normalize().map(|n| n.as_vec3())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn assert_close(a: Vec3, b: Vec3) {
        assert!((a - b).length() < 1e-6, "{a} != {b}");
    }

    #[test]
    fn single_triangle_gets_its_face_normal() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let n = compute_area_weighted_normals(&p, &[[0, 1, 2]]);
        assert_eq!(n, vec![Vec3::Z; 3]);
        let n = compute_area_weighted_normals(&p, &[[0, 2, 1]]);
        assert_eq!(n, vec![-Vec3::Z; 3]);
    }

    #[test]
    fn weights_by_area() {
        // Two triangles sharing vertex 0: a big one in z = 0 and a small one in x = 0.
        let p = [
            Vec3::ZERO,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        ];
        // Crosses: big (0, 0, 4), small (-2, 0, 0); vertex 0 gets their sum.
        let n = compute_area_weighted_normals(&p, &[[0, 1, 2], [0, 3, 2]]);
        assert_close(n[0], Vec3::new(-2.0, 0.0, 4.0).normalize());
        assert_close(n[1], Vec3::Z);
        assert_close(n[3], -Vec3::X);
    }

    #[test]
    fn unused_and_cancelling_vertices_stay_unit_length() {
        // Vertex 3 is unused; the two triangles are the same face with opposite windings.
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::ONE];
        let n = compute_area_weighted_normals(&p, &[[0, 1, 2], [0, 2, 1]]);
        assert_eq!(n.len(), 4);
        for v in &n {
            assert!((v.length() - 1.0).abs() < 1e-6);
        }
        assert_eq!(n[3], FALLBACK_NORMAL);
    }

    #[test]
    fn out_of_range_triangles_are_ignored() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let n = compute_area_weighted_normals(&p, &[[0, 1, 2], [0, 1, 99], [u32::MAX, 0, 1]]);
        assert_eq!(n, vec![Vec3::Z; 3]);
        assert!(compute_area_weighted_normals(&[], &[[0, 1, 2]]).is_empty());
    }

    #[test]
    fn huge_and_tiny_coordinates_give_finite_normals() {
        for s in [1e30_f32, 1e-30] {
            let p = [Vec3::ZERO, Vec3::X * s, Vec3::Y * s];
            let n = compute_area_weighted_normals(&p, &[[0, 1, 2]]);
            assert_eq!(n, vec![Vec3::Z; 3], "scale {s}");
        }
    }

    #[test]
    fn zero_area_test() {
        let (a, b) = (Vec3::ZERO, Vec3::X);
        assert!(is_zero_area(a, b, Vec3::new(2.0, 0.0, 0.0)));
        assert!(is_zero_area(a, a, a));
        assert!(!is_zero_area(a, b, Vec3::Y));
        // Thin but real: area relative to the longest edge is well above 1e-12.
        assert!(!is_zero_area(a, b, Vec3::new(0.5, 1e-5, 0.0)));
        // Scale invariant.
        assert!(!is_zero_area(a, b * 1e-20, Vec3::Y * 1e-20));
        // Collinear corners have zero area; a needle far thinner than f32 resolves at its size
        // is named a sliver (its area is 7e14, its longest edge 1e15).
        assert_eq!(
            degenerate_reason(a, b, Vec3::new(2.0, 0.0, 0.0)),
            Some("has zero area")
        );
        let needle = degenerate_reason(Vec3::new(0.0, 0.0, 1e15), Vec3::X, Vec3::Y);
        assert_eq!(needle, Some(SLIVER));
    }

    #[test]
    fn unrepresentable_areas_are_degenerate() {
        let tri = |s: f32, offset: f32| {
            let o = Vec3::splat(offset);
            degenerate_reason(o, o + Vec3::X * s, o + Vec3::Y * s)
        };
        assert_eq!(tri(1.0, 0.0), None);
        assert_eq!(tri(1e-5, 0.0), None);
        assert_eq!(tri(1e-18, 0.0), None);
        assert_eq!(tri(1.0, 1e7), None);
        assert_eq!(tri(1e19, 0.0), None);
        // Twice the area 1e-40 is subnormal in f32; 1e-90 is zero there.
        assert_eq!(
            tri(1e-20, 0.0),
            Some("has an area too small for f32 (it underflows)")
        );
        let subnormal = [Vec3::X * 1e-45, Vec3::Y * 1e-45, Vec3::Z * 1e-45];
        assert!(degenerate_reason(subnormal[0], subnormal[1], subnormal[2]).is_some());
        assert_eq!(
            tri(2e19, 0.0),
            Some("has an area or edge too large for f32 (it overflows)")
        );
        let huge = Vec3::new(3e38, 0.0, 0.0);
        assert!(degenerate_reason(-huge, huge, Vec3::Y).is_some());
        // A small triangle far out is fine.
        let far = Vec3::X * 3e38;
        assert_eq!(degenerate_reason(far, far + Vec3::Y, far + Vec3::Z), None);
        assert_eq!(tri(0.0, 1.0), Some("has zero area"));
    }

    #[test]
    fn unit_rejects_zero_and_non_finite() {
        assert_eq!(unit(Vec3::new(0.0, 0.0, 2.0)), Some(Vec3::Z));
        assert_eq!(unit(Vec3::ZERO), None);
        assert_eq!(unit(Vec3::new(f32::NAN, 0.0, 1.0)), None);
        assert_eq!(unit(Vec3::new(f32::INFINITY, 0.0, 1.0)), None);
        assert!(unit(Vec3::new(1e-40, 0.0, 0.0)).is_some());
    }
}
