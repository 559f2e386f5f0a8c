//! Surfaces: the functions that map a barycentric sample of a coarse triangle to a point and a
//! normal. Each surface is written once in GLSL (`glsl/include/<surface>.glsl`) and once here, its
//! Rust mirror; the GPU tests pin the two together by reading back what the drawing pipelines
//! evaluated.
//!
//! Every driver evaluates a sample through [`eval`], which first puts the triangle's corners in a
//! canonical order ([`canonical`]): by global vertex index, with the corners whose weight is zero
//! moved last. A point on a shared coarse edge is then computed from the same two corners, in the
//! same order, with the same weights, by both triangles: refinement is watertight by construction
//! (bit-identical positions), whatever the surface.
#![forbid(unsafe_code)]

pub mod flat;
mod record;

pub use record::{build_records, CoarseTri};

use glam::Vec3;

/// The surface a coarse triangle defines. The discriminant is the `SURFACE` specialization
/// constant of every driver's evaluation stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[repr(u32)]
pub enum Surface {
    /// Linear interpolation of the coarse triangle's positions and normals.
    #[default]
    Flat = 0,
}

impl Surface {
    pub const ALL: [Surface; 1] = [Surface::Flat];

    pub fn name(self) -> &'static str {
        match self {
            Surface::Flat => "flat",
        }
    }
}

/// A point of the refined surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    pub position: Vec3,
    /// Unit normal.
    pub normal: Vec3,
}

/// Corner data of a coarse triangle in canonical order, with the sample's weights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Corners {
    pub p: [Vec3; 3],
    pub n: [Vec3; 3],
    /// Barycentric weight of each corner.
    pub w: [f32; 3],
}

/// Canonical corner order for barycentric sample `bary = (w, u, v)` (weights of corners 0, 1, 2):
/// ascending global vertex index, then zero-weight corners moved last (stable).
/// Mirror of `canonical()` in `glsl/include/bary.glsl`.
pub fn canonical(rec: &CoarseTri, bary: [f32; 3]) -> Corners {
    let mut order = [0usize, 1, 2];
    // Sorting key: zero weights last, then global index.
    let key = |c: usize| ((bary[c] == 0.0) as u64) << 32 | rec.idx[c] as u64;
    order.sort_by_key(|&c| key(c));
    Corners {
        p: order.map(|c| Vec3::from_slice(&rec.p[c][..3])),
        n: order.map(|c| Vec3::from_slice(&rec.n[c][..3])),
        w: order.map(|c| bary[c]),
    }
}

/// Evaluate `surface` at barycentric sample `bary` of the coarse triangle `rec`.
/// Mirror of `surface_eval()` in `glsl/include/surface.glsl`.
pub fn eval(surface: Surface, rec: &CoarseTri, bary: [f32; 3]) -> SurfacePoint {
    let c = canonical(rec, bary);
    match surface {
        Surface::Flat => flat::eval(&c),
    }
}

/// Weights of a tessellator sample `tc = gl_TessCoord` at integer level `n` (tess driver).
/// Outer-edge samples are snapped to the level-`n` lattice (`k/n`, `(n-k)/n`, exact zero), as
/// the pattern's weights are; interior samples are used as given.
/// Mirror of `tess_weights()` in `glsl/include/bary.glsl`.
pub fn tess_weights(tc: [f32; 3], n: u32) -> [f32; 3] {
    let fnn = n as f32;
    let half_step = 0.5 / fnn;
    if tc.iter().all(|&c| c >= half_step) {
        return tc;
    }
    let mut k = tc.map(|c| {
        if c < half_step {
            0.0
        } else {
            (c * fnn).round()
        }
    });
    if k[0] == 0.0 {
        k[1] = fnn - k[2];
    } else if k[1] == 0.0 {
        k[2] = fnn - k[0];
    } else {
        k[0] = fnn - k[1];
    }
    k.map(|x| x / fnn)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rec() -> CoarseTri {
        CoarseTri::new(
            [
                Vec3::new(0.1, 0.2, 0.3),
                Vec3::new(1.7, -0.3, 0.2),
                Vec3::new(0.3, 1.9, -0.7),
            ],
            [Vec3::Z, Vec3::X, Vec3::Y],
            [7, 2, 5],
            0,
        )
    }

    #[test]
    fn tess_weights_snap_edges_only() {
        let n = 7;
        // On the edge v = 0, slightly off the lattice: snapped to (4/7, 3/7, 0).
        assert_eq!(
            tess_weights([0.571_428_5, 0.428_571_6, 0.0], n),
            [4.0 / 7.0, 3.0 / 7.0, 0.0]
        );
        // A corner.
        assert_eq!(tess_weights([0.0, 1.0, 0.0], n), [0.0, 1.0, 0.0]);
        // Interior samples are untouched.
        let inner = [0.2, 0.3, 0.5];
        assert_eq!(tess_weights(inner, n), inner);
    }

    #[test]
    fn canonical_sorts_by_index_zero_weights_last() {
        let r = rec();
        let c = canonical(&r, [0.25, 0.5, 0.25]);
        assert_eq!(c.w, [0.5, 0.25, 0.25]); // indices 2, 5, 7
        let c = canonical(&r, [0.25, 0.0, 0.75]);
        assert_eq!(c.w, [0.75, 0.25, 0.0]); // 5, 7, then the zero-weight corner (2)
        let c = canonical(&r, [0.0, 1.0, 0.0]);
        assert_eq!(c.w, [1.0, 0.0, 0.0]);
        assert_eq!(c.p[0], Vec3::new(1.7, -0.3, 0.2));
    }

    #[test]
    fn shared_edge_points_are_bit_identical() {
        // Two triangles sharing the edge (vertex 3, vertex 9), listed in opposite directions.
        let a = Vec3::new(0.31, -1.7, 2.9);
        let b = Vec3::new(-4.1, 0.77, 0.013);
        let t1 = CoarseTri::new(
            [a, b, Vec3::new(5.0, 5.0, 5.0)],
            [Vec3::X, Vec3::Y, Vec3::Z],
            [3, 9, 4],
            0,
        );
        let t2 = CoarseTri::new(
            [b, a, Vec3::new(-5.0, 2.0, 1.0)],
            [Vec3::Y, Vec3::X, Vec3::Z],
            [9, 3, 11],
            1,
        );
        let n = 37;
        for k in 0..=n {
            let wa = crate::pattern::weight(n - k, n);
            let wb = crate::pattern::weight(k, n);
            for s in Surface::ALL {
                let p1 = eval(s, &t1, [wa, wb, 0.0]);
                let p2 = eval(s, &t2, [wb, wa, 0.0]);
                assert_eq!(
                    p1.position.to_array().map(f32::to_bits),
                    p2.position.to_array().map(f32::to_bits)
                );
                assert_eq!(p1.normal, p2.normal);
            }
        }
    }
}
