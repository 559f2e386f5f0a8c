//! `pn` surface: curved PN triangles exactly as the 2005 paper's appendix A writes them
//! (Boubekeur & Schlick, after Vlachos et al. 2001). Mirror of `glsl/include/pn.glsl`.
//!
//! Geometry: a cubic triangular Bézier patch, `b(w,u,v) = Σ b_ijk · 3!/(i!j!k!) · w^i u^j v^k`
//! (the paper's formula (1) leaves the multinomial factors implicit). With `s_ij = (P_j − P_i)·N_i`:
//! corner points `b_300 = P_0 …`, edge points `b_ij = (2 P_i + P_j − s_ij N_i) / 3` (the one of
//! edge ij next to corner i), and the centre `b_111 = E + (E − V)/2`, E the mean of the six edge
//! points and V the mean of the corners.
//!
//! Normal field: quadratic, `n(w,u,v) = Σ n_ijk w^i u^j v^k` with unit factors, as both papers write
//! it: `n_200 = N_0 …`, `n_ij = N_i + N_j − t_ij (P_j − P_i)`, `t_ij = 4 (P_j − P_i)·(N_i + N_j) /
//! |P_j − P_i|²`, not normalized; the field is normalized after evaluation. This is the 2005
//! paper's correction of Vlachos et al., who set the control point to the *normalized* mid-edge
//! normal `h_ij/|h_ij|`, `h_ij = N_i + N_j − v_ij (P_j − P_i)`, `v_ij = 2 (P_j − P_i)·(N_i + N_j) /
//! |P_j − P_i|²`: with that control point the field's value at the edge midpoint is not the
//! reflected normal. With the paper's `n_ij` the midpoint value is `(N_i + N_j − v_ij (P_j − P_i))/2`,
//! exactly Vlachos' intended mid-edge normal direction.
//!
//! Watertight: the terms with the third corner carry its exact zero weight on an edge, and the
//! edge's control points depend on the edge's corners only (in canonical order). The geometry
//! uses the corners' geometry normals `g` (equal to `n` except at split normals with closed
//! seams, see src/surface/record.rs); the normal field uses the shading normals `n`.

use super::facts::{Elements, FragmentNormals, SurfaceFacts};
use super::{dot3, Corners, Local};
use glam::Vec3;

/// What `pn` declares about itself (docs/architecture.md, "Surfaces as plug-ins").
pub const FACTS: SurfaceFacts = SurfaceFacts {
    name: "pn",
    help: "Curved PN triangles (Vlachos et al. 2001, as in Boubekeur & Schlick 2005, appendix A): cubic Bézier geometry, quadratic normal field evaluated per fragment",
    elements: Elements::CoarseTriangles,
    options: &["pn_seams"],
    texture_coordinates: true,
    needs_every_face: false,
    tags: false,
    fragment_normals: FragmentNormals::Always,
    bindings: &[],
};

/// Control points in canonical corner order.
pub struct Control {
    /// `e[i][j]`: the edge point of edge ij next to corner i (unused on the diagonal).
    pub e: [[Vec3; 3]; 3],
    pub centre: Vec3,
}

const THIRD: f32 = 1.0 / 3.0;
const SIXTH: f32 = 1.0 / 6.0;

/// The edge point of edge (p_i, p_j) next to p_i for normal `n` at p_i:
/// `(2 P_i + P_j − ((P_j − P_i)·N) N) / 3`. Mirror of `pn_edge_point` in pn.glsl.
pub fn edge_point(pi: Vec3, pj: Vec3, n: Vec3) -> Vec3 {
    let s = dot3(pj - pi, n);
    (pi * 2.0 + pj - n * s) * THIRD
}

/// The edge point of edge ij next to corner i, with the position normal on a seam edge.
fn seam_edge_point(c: &Corners, i: usize, j: usize) -> Vec3 {
    let n = if c.seam_pn[super::edge_of(i, j)] {
        c.g[i]
    } else {
        c.n[i]
    };
    edge_point(c.p[i], c.p[j], n)
}

/// The control points with edge points from `edge(i, j)` (the one of edge ij next to corner i).
pub fn control_with(c: &Corners, edge: &dyn Fn(usize, usize) -> Vec3) -> Control {
    let mut e = [[Vec3::ZERO; 3]; 3];
    for (i, j) in [(0, 1), (1, 0), (1, 2), (2, 1), (0, 2), (2, 0)] {
        e[i][j] = edge(i, j);
    }
    let sum = e[0][1] + e[1][0] + e[1][2] + e[2][1] + e[0][2] + e[2][0];
    let mean_e = sum * SIXTH;
    let mean_v = (c.p[0] + c.p[1] + c.p[2]) * THIRD;
    Control {
        e,
        centre: mean_e + (mean_e - mean_v) * 0.5,
    }
}

/// The quadratic normal field's edge control point `n_ij`.
pub fn normal_control(c: &Corners, i: usize, j: usize) -> Vec3 {
    let d = c.p[j] - c.p[i];
    let len2 = dot3(d, d);
    let s = c.n[i] + c.n[j];
    let t = if len2 > 0.0 {
        4.0 * dot3(d, s) / len2
    } else {
        0.0
    };
    s - d * t
}

/// The normal field at the sample, normalized.
pub fn normal(c: &Corners) -> Vec3 {
    let [w0, w1, w2] = c.w;
    let n = c.n[0] * (w0 * w0)
        + c.n[1] * (w1 * w1)
        + c.n[2] * (w2 * w2)
        + normal_control(c, 0, 1) * (w0 * w1)
        + normal_control(c, 1, 2) * (w1 * w2)
        + normal_control(c, 2, 0) * (w2 * w0);
    n.normalize_or_zero()
}

pub fn control(c: &Corners) -> Control {
    control_with(c, &|i, j| seam_edge_point(c, i, j))
}

pub fn eval(c: &Corners) -> Local {
    eval_with_edges(c, &|i, j| seam_edge_point(c, i, j))
}

/// The cubic patch with edge points from `edge` (PN's own, or scalar-tagged ones), the normal
/// field on `c.n`.
pub fn eval_with_edges(c: &Corners, edge: &dyn Fn(usize, usize) -> Vec3) -> Local {
    let [w0, w1, w2] = c.w;
    let b = control_with(c, edge);
    let e = &b.e;
    let corners = c.p[0] * (w0 * w0 * w0) + c.p[1] * (w1 * w1 * w1) + c.p[2] * (w2 * w2 * w2);
    let edges = e[0][1] * (w0 * w0 * w1)
        + e[1][0] * (w0 * w1 * w1)
        + e[1][2] * (w1 * w1 * w2)
        + e[2][1] * (w1 * w2 * w2)
        + e[0][2] * (w0 * w0 * w2)
        + e[2][0] * (w0 * w2 * w2);
    let position = corners + edges * 3.0 + b.centre * (w0 * w1 * w2 * 6.0);
    let grad = [
        c.p[0] * (3.0 * w0 * w0)
            + (e[0][1] * (2.0 * w0 * w1)
                + e[1][0] * (w1 * w1)
                + e[0][2] * (2.0 * w0 * w2)
                + e[2][0] * (w2 * w2))
                * 3.0
            + b.centre * (6.0 * w1 * w2),
        c.p[1] * (3.0 * w1 * w1)
            + (e[0][1] * (w0 * w0)
                + e[1][0] * (2.0 * w0 * w1)
                + e[1][2] * (2.0 * w1 * w2)
                + e[2][1] * (w2 * w2))
                * 3.0
            + b.centre * (6.0 * w0 * w2),
        c.p[2] * (3.0 * w2 * w2)
            + (e[1][2] * (w1 * w1)
                + e[2][1] * (2.0 * w1 * w2)
                + e[0][2] * (w0 * w0)
                + e[2][0] * (2.0 * w0 * w2))
                * 3.0
            + b.centre * (6.0 * w0 * w1),
    ];
    Local {
        position,
        normal: normal(c),
        grad,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn corners(p: [Vec3; 3], n: [Vec3; 3], w: [f32; 3]) -> Corners {
        Corners {
            p,
            n,
            g: n,
            seam_pn: [false; 3],
            seam_phong: [false; 3],
            w,
            order: [0, 1, 2],
        }
    }

    /// With the face normal at every corner the patch is the flat triangle.
    #[test]
    fn planar_triangle_stays_planar() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let c = corners(p, [Vec3::Z; 3], [0.2, 0.3, 0.5]);
        let l = eval(&c);
        assert!((l.position - Vec3::new(0.3, 0.5, 0.0)).length() < 1e-6);
        assert!((l.normal - Vec3::Z).length() < 1e-6);
    }

    /// Corners are interpolated, and the edge midpoint normal is Vlachos' reflected mid-edge
    /// normal direction (what the paper's n110 is for).
    #[test]
    fn interpolates_corners_and_midpoint_normal() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let n = [
            Vec3::new(-0.3, -0.3, 1.0).normalize(),
            Vec3::new(0.5, 0.0, 1.0).normalize(),
            Vec3::new(0.0, 0.4, 1.0).normalize(),
        ];
        assert_eq!(eval(&corners(p, n, [0.0, 1.0, 0.0])).position, p[1]);
        let mid = normal(&corners(p, n, [0.5, 0.5, 0.0]));
        let d = p[1] - p[0];
        let v = 2.0 * d.dot(n[0] + n[1]) / d.dot(d);
        let h = (n[0] + n[1] - d * v).normalize();
        assert!((mid - h).length() < 1e-6, "{mid} vs {h}");
    }
}
