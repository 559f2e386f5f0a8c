//! `pn` surface: curved PN triangles exactly as the 2005 paper's appendix A writes them
//! (Boubekeur & Schlick, after Vlachos et al. 2001). Mirror of `glsl/include/pn.glsl`.
//!
//! Geometry: a cubic triangular Bézier patch, `b(w,u,v) = Σ b_ijk · 3!/(i!j!k!) · w^i u^j v^k`
//! (the paper's formula (1) leaves the multinomial factors implicit). With `s_ij = (P_j − P_i)·N_i`:
//! corner points `b_300 = P_0 …`, edge points `b_ij = (2 P_i + P_j − s_ij N_i) / 3` (the one of
//! edge ij next to corner i), and the centre `b_111 = E + (E − V)/2`, E the mean of the six edge
//! points and V the mean of the corners.
//!
//! Normal field ([`NormalField`], `--normal-field`; docs/surfaces.md compares them):
//! - `paper`: quadratic, `n(w,u,v) = Σ n_ijk w^i u^j v^k` with unit factors, as both papers write
//!   it: `n_200 = N_0 …`, `n_ij = N_i + N_j − t_ij (P_j − P_i)`, `t_ij = 4 (P_j − P_i)·(N_i + N_j) /
//!   |P_j − P_i|²`, not normalized; the field is normalized after evaluation. This is the 2005
//!   paper's correction of Vlachos et al.: with the paper's `n_ij` the midpoint value is
//!   `(N_i + N_j − v_ij (P_j − P_i))/2`, exactly Vlachos' intended mid-edge normal direction
//!   (the normal reflected across the plane perpendicular to the edge).
//! - `vlachos`: the same quadratic with Vlachos et al.'s own control point, the *normalized*
//!   `h_ij/|h_ij|`, `h_ij = N_i + N_j − v_ij (P_j − P_i)`, `v_ij = 2 (P_j − P_i)·(N_i + N_j) /
//!   |P_j − P_i|²` (zero for a zero-length edge; a zero `h_ij` gives a zero control point). Its
//!   weight `w_i w_j` is at most 1/4, so the reflected direction only tilts the field a little
//!   between the corners' normals, where `paper` turns it fully: small differences between
//!   neighbouring normals on dense meshes are amplified far less.
//! - `linear`: the normalized linear interpolation of the corner normals (Phong shading).
//!
//! Watertight: the terms with the third corner carry its exact zero weight on an edge, and the
//! edge's control points depend on the edge's corners only (in canonical order). The geometry
//! uses the corners' geometry normals `g` (equal to `n` except at split normals with closed
//! seams, see src/surface/record.rs); the normal field uses the shading normals `n`.

use super::bounds::{Patch, SurfaceBound};
use super::facts::{Elements, FragmentNormals, SurfaceFacts};
use super::stpn::VertexTag;
use super::{dot3, Corners, Local, SurfaceParams};
use crate::lod::Net;
use glam::Vec3;

/// What `pn` declares about itself (docs/architecture.md, "Surfaces as plug-ins").
pub const FACTS: SurfaceFacts = SurfaceFacts {
    name: "pn",
    help: "Curved PN triangles (Vlachos et al. 2001, as in Boubekeur & Schlick 2005, appendix A): cubic Bézier geometry, quadratic normal field evaluated per fragment",
    elements: Elements::CoarseTriangles,
    pre_pass: None,
    options: &["pn_seams", "normal_field"],
    texture_coordinates: true,
    needs_every_face: false,
    tags: false,
    fragment_normals: FragmentNormals::Always,
    bindings: &[],
    bound: SurfaceBound::Nets {
        geometry: net,
        direction,
    },
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

/// The normal field of `pn` and `stpn` (module notes). The discriminant is the
/// `NORMAL_FIELD` specialization constant (glsl/include/pn.glsl).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[repr(u32)]
pub enum NormalField {
    /// The 2005 paper's quadratic field (the fully reflected normal at edge midpoints).
    Paper = 0,
    /// Vlachos et al. 2001's quadratic field (normalized mid-edge control normals): the
    /// default, smooth on dense meshes with computed normals (docs/surfaces.md).
    #[default]
    Vlachos = 1,
    /// The linearly interpolated corner normals.
    Linear = 2,
}

impl NormalField {
    pub const ALL: [NormalField; 3] = [
        NormalField::Paper,
        NormalField::Vlachos,
        NormalField::Linear,
    ];

    /// The name on the command line and in the panel.
    pub fn name(self) -> &'static str {
        match self {
            NormalField::Paper => "paper",
            NormalField::Vlachos => "vlachos",
            NormalField::Linear => "linear",
        }
    }
}

/// The paper's quadratic normal field's edge control point `n_ij`.
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

/// Vlachos et al.'s edge control point `h_ij / |h_ij|`. Mirror of `pn_vlachos_control`.
pub fn vlachos_control(c: &Corners, i: usize, j: usize) -> Vec3 {
    let d = c.p[j] - c.p[i];
    let len2 = dot3(d, d);
    let s = c.n[i] + c.n[j];
    let v = if len2 > 0.0 {
        2.0 * dot3(d, s) / len2
    } else {
        0.0
    };
    let h = s - d * v;
    let l2 = dot3(h, h);
    if l2 > 0.0 {
        h / l2.sqrt()
    } else {
        Vec3::ZERO
    }
}

/// The edge control point of quadratic field `field` (`Paper` or `Vlachos`).
pub fn field_control(c: &Corners, i: usize, j: usize, field: NormalField) -> Vec3 {
    match field {
        NormalField::Vlachos => vlachos_control(c, i, j),
        _ => normal_control(c, i, j),
    }
}

/// The normal field `field` at the sample, normalized.
pub fn normal(c: &Corners, field: NormalField) -> Vec3 {
    if field == NormalField::Linear {
        return super::flat::normal(c);
    }
    let [w0, w1, w2] = c.w;
    let n = c.n[0] * (w0 * w0)
        + c.n[1] * (w1 * w1)
        + c.n[2] * (w2 * w2)
        + field_control(c, 0, 1, field) * (w0 * w1)
        + field_control(c, 1, 2, field) * (w1 * w2)
        + field_control(c, 2, 0, field) * (w2 * w0);
    super::unit_field(n, c)
}

pub fn control(c: &Corners) -> Control {
    control_with(c, &|i, j| seam_edge_point(c, i, j))
}

pub fn eval(c: &Corners, field: NormalField) -> Local {
    eval_with_edges(c, &|i, j| seam_edge_point(c, i, j), field)
}

/// The cubic patch with edge points from `edge` (PN's own, or scalar-tagged ones), the normal
/// field `field` on `c.n`.
pub fn eval_with_edges(
    c: &Corners,
    edge: &dyn Fn(usize, usize) -> Vec3,
    field: NormalField,
) -> Local {
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
        normal: normal(c, field),
        grad,
    }
}

/// The cubic Bézier net of control points `b` on corners `c`.
pub fn bezier_net(c: &Corners, b: &Control) -> Net {
    let corner = |w: [usize; 3]| (0..3).find(|&i| w[i] == w.iter().sum::<usize>());
    Net::from_fn(3, |w| match corner(w) {
        Some(i) => c.p[i],
        None => match (0..3).find(|&i| w[i] == 2) {
            Some(i) => b.e[i][(0..3).find(|&j| w[j] == 1).unwrap()],
            None => b.centre,
        },
    })
}

/// Chord-error bound: a cubic Bézier triangle. Along direction `k` the second derivative is
/// `6 Σ_γ B¹_γ Δ²_k b_γ`, a convex combination, so `M_k = 6 max |Δ²_k b|` over the three second
/// differences of the ten-point net in that direction; an edge's curve (its four control points
/// `b0..b3`) has `M_e = 6 max(|b0 − 2b1 + b2|, |b1 − 2b2 + b3|)`, i.e. the edge error is
/// `3/4 · max(...) / N²` (the 2006 paper's bound, sign-free). `stpn` uses the same net
/// ([`super::stpn::net`]).
pub fn net(_: &SurfaceParams, c: &Corners, _: &[VertexTag; 3], _: bool) -> Patch {
    Patch::Exact(bezier_net(c, &control(c)))
}

/// The normal field `field` (unnormalized) with corner normals `n` on corners `c`, as a net:
/// quadratic for `paper` and `vlachos` (control normals `n_ij / 2`), linear for `linear`.
pub fn field_net(field: NormalField, c: &Corners, n: [Vec3; 3]) -> Net {
    if field == NormalField::Linear {
        return super::flat::linear_net(n);
    }
    let cn = Corners { n, ..*c };
    Net::from_fn(2, |w| match (0..3).find(|&i| w[i] == 2) {
        Some(i) => n[i],
        None => {
            let i = (0..3).find(|&i| w[i] == 1).unwrap();
            let j = (i + 1..3).find(|&j| w[j] == 1).unwrap();
            // normal()'s terms: n01 w0w1, n12 w1w2, n20 w2w0.
            let (a, b) = if (i, j) == (0, 2) { (2, 0) } else { (i, j) };
            field_control(&cn, a, b, field) * 0.5
        }
    })
}

/// The direction field displacement moves along: the normal field `--normal-field` of the
/// geometry normals.
pub fn direction(
    _: &SurfaceParams,
    field: NormalField,
    c: &Corners,
    _: &[VertexTag; 3],
    _: bool,
) -> Vec<Net> {
    let cg = Corners { n: c.g, ..*c };
    vec![field_net(field, &cg, cg.n)]
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
        for field in NormalField::ALL {
            let l = eval(&c, field);
            assert!((l.position - Vec3::new(0.3, 0.5, 0.0)).length() < 1e-6);
            assert!((l.normal - Vec3::Z).length() < 1e-6, "{field:?}");
        }
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
        assert_eq!(
            eval(&corners(p, n, [0.0, 1.0, 0.0]), NormalField::Paper).position,
            p[1]
        );
        let mid = normal(&corners(p, n, [0.5, 0.5, 0.0]), NormalField::Paper);
        let d = p[1] - p[0];
        let v = 2.0 * d.dot(n[0] + n[1]) / d.dot(d);
        let h = (n[0] + n[1] - d * v).normalize();
        assert!((mid - h).length() < 1e-6, "{mid} vs {h}");
    }

    /// Every field interpolates the corner normals; at an edge midpoint `linear` is the mean of
    /// the edge's normals, `paper` that mean reflected across the plane perpendicular to the
    /// edge, and `vlachos` (Vlachos et al.'s field, `(N_i + N_j + h_ij/|h_ij|)/4` there) lies
    /// between the two, never turned further from the mean than `paper`.
    #[test]
    fn fields_at_corners_and_edge_midpoints() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::new(0.2, 0.9, 0.1)];
        let n = [
            Vec3::new(-0.3, -0.3, 1.0).normalize(),
            Vec3::new(0.5, 0.1, 1.0).normalize(),
            Vec3::new(0.0, 0.4, 1.0).normalize(),
        ];
        for field in NormalField::ALL {
            for i in 0..3 {
                let mut w = [0.0; 3];
                w[i] = 1.0;
                let at = normal(&corners(p, n, w), field);
                assert!((at - n[i]).length() < 1e-6, "{field:?} corner {i}");
            }
        }
        for (i, j) in [(0, 1), (1, 2), (2, 0)] {
            let mut w = [0.0; 3];
            w[i] = 0.5;
            w[j] = 0.5;
            let c = corners(p, n, w);
            let (d, s) = (p[j] - p[i], n[i] + n[j]);
            let h = s - d * (2.0 * d.dot(s) / d.dot(d));
            let linear = normal(&c, NormalField::Linear);
            assert!((linear - s.normalize()).length() < 1e-6);
            let paper = normal(&c, NormalField::Paper);
            assert!((paper - h.normalize()).length() < 1e-6);
            let vlachos = normal(&c, NormalField::Vlachos);
            let want = (s + h.normalize()).normalize();
            assert!((vlachos - want).length() < 1e-6, "{vlachos} vs {want}");
            let angle = |a: Vec3| a.angle_between(linear);
            assert!(angle(vlachos) <= angle(paper) + 1e-6, "edge {i}{j}");
            assert!(
                angle(paper) > 1e-3,
                "the edge's normals must not be symmetric"
            );
        }
    }

    /// Degenerate input gives finite control points: a zero-length edge, opposite normals.
    #[test]
    fn vlachos_control_is_finite_on_degenerate_edges() {
        let c = corners(
            [Vec3::ZERO, Vec3::ZERO, Vec3::Y],
            [Vec3::Z, -Vec3::Z, Vec3::Z],
            [0.5, 0.5, 0.0],
        );
        assert_eq!(vlachos_control(&c, 0, 1), Vec3::ZERO);
        assert!(vlachos_control(&c, 1, 2).is_finite());
        assert!(normal(&c, NormalField::Vlachos).is_finite());
    }
}
