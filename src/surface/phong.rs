//! `phong` surface: Phong tessellation (Boubekeur & Alexa 2008). The flat point `p = Σ w_i P_i`
//! is projected onto each corner's tangent plane, `π_i(q) = q − ((q − P_i)·N_i) N_i`, and the
//! projections are interpolated again: `P = (1 − α) p + α Σ w_i π_i(p)`. α = 3/4 by default.
//! The normal is the normalized linear interpolation of the corner normals (as in the paper).
//! Mirror of `glsl/include/phong.glsl` (same operation order, `precise` there).
//!
//! On a coarse edge the third corner's weight is an exact zero, so its projection drops out and
//! the point depends on the edge's two corners only: Phong tessellation is watertight wherever
//! the corners share normals.

use super::{dot3, flat, Corners, Local};
use glam::Vec3;

/// Projection of `q` onto the plane through `p` with unit normal `n`.
pub fn project(q: Vec3, p: Vec3, n: Vec3) -> Vec3 {
    q - n * dot3(q - p, n)
}

pub fn eval(c: &Corners, alpha: f32) -> Local {
    let [w0, w1, w2] = c.w;
    let p = flat::point(c);
    let pi = [0, 1, 2].map(|i| project(p, c.p[i], c.n[i]));
    let curved = pi[0] * w0 + pi[1] * w1 + pi[2] * w2;
    let position = p * (1.0 - alpha) + curved * alpha;
    // ∂/∂b_j: p moves by P_j, each projection by P_j minus its normal component.
    let grad = [0, 1, 2].map(|j| {
        let pj = c.p[j];
        let moved: Vec3 = (0..3)
            .map(|i| (pj - c.n[i] * dot3(pj, c.n[i])) * c.w[i])
            .sum();
        pj * (1.0 - alpha) + (pi[j] + moved) * alpha
    });
    Local {
        position,
        normal: flat::normal(c),
        grad,
    }
}
