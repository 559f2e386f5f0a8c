//! `phong` surface: Phong tessellation (Boubekeur & Alexa 2008). The flat point `p = Σ w_i P_i`
//! is projected onto each corner's tangent plane, `π_i(q) = q − ((q − P_i)·N_i) N_i`, and the
//! projections are interpolated again: `P = (1 − α) p + α Σ w_i π_i(p)`. α = 3/4 by default.
//! The normal is the normalized linear interpolation of the corner normals (as in the paper).
//! Mirror of `glsl/include/phong.glsl` (same operation order, `precise` there).
//!
//! On a coarse edge the third corner's weight is an exact zero, so its projection drops out and
//! the point depends on the edge's two corners only: Phong tessellation is watertight wherever
//! the corners share geometry normals (everywhere with closed seams, src/surface/record.rs).

use super::bounds::{Patch, SurfaceBound};
use super::facts::{Elements, FragmentNormals, SurfaceFacts};
use super::stpn::VertexTag;
use super::{dot3, edge_of, flat, Corners, Local, SurfaceParams};
use crate::lod::Net;
use glam::Vec3;

/// What `phong` declares about itself (docs/architecture.md, "Surfaces as plug-ins").
pub const FACTS: SurfaceFacts = SurfaceFacts {
    name: "phong",
    help: "Phong tessellation (Boubekeur & Alexa 2008): the flat point pulled towards the corners' tangent planes by the shape factor --alpha",
    elements: Elements::CoarseTriangles,
    pre_pass: None,
    options: &["alpha", "pn_seams"],
    texture_coordinates: true,
    needs_every_face: false,
    tags: false,
    fragment_normals: FragmentNormals::Never,
    bindings: &[],
    bound: SurfaceBound::Nets {
        geometry: net,
        direction: flat::direction,
    },
};

/// Projection of `q` onto the plane through `p` with unit normal `n`.
pub fn project(q: Vec3, p: Vec3, n: Vec3) -> Vec3 {
    q - n * dot3(q - p, n)
}

/// The normal corner `i`'s tangent plane uses: its own normal, or the position normal on an edge
/// flagged as a seam (src/surface/record.rs). Inside the triangle the choices of the corner's two
/// edges are blended by the weights of their other corners, so the surface stays continuous and
/// each edge uses exactly its own choice (the other weight is an exact zero there).
/// Mirror of `phong_corner_normal` in phong.glsl.
pub fn corner_normal(c: &Corners, i: usize) -> glam::Vec3 {
    let (j, k) = ((i + 1) % 3, (i + 2) % 3);
    let pick = |e: usize| if c.seam_phong[e] { c.g[i] } else { c.n[i] };
    let (a_ij, a_ik) = (pick(edge_of(i, j)), pick(edge_of(i, k)));
    if a_ij == a_ik || c.w[k] == 0.0 {
        a_ij
    } else if c.w[j] == 0.0 {
        a_ik
    } else {
        // Opposite choices (a seam's two normals) blend to nothing halfway: the edge's first.
        let s = a_ij * c.w[j] + a_ik * c.w[k];
        if super::dot3(s, s) > super::FIELD_MIN2 {
            s.normalize()
        } else {
            a_ij
        }
    }
}

pub fn eval(c: &Corners, alpha: f32) -> Local {
    let [w0, w1, w2] = c.w;
    let p = flat::point(c);
    let g = [0, 1, 2].map(|i| corner_normal(c, i));
    let pi = [0, 1, 2].map(|i| project(p, c.p[i], g[i]));
    let curved = pi[0] * w0 + pi[1] * w1 + pi[2] * w2;
    let position = p * (1.0 - alpha) + curved * alpha;
    // ∂/∂b_j: p moves by P_j, each projection by P_j minus its normal component.
    let grad = [0, 1, 2].map(|j| {
        let pj = c.p[j];
        let moved: Vec3 = (0..3).map(|i| (pj - g[i] * dot3(pj, g[i])) * c.w[i]).sum();
        pj * (1.0 - alpha) + (pi[j] + moved) * alpha
    });
    Local {
        position,
        normal: flat::normal(c),
        grad,
    }
}

/// The normal Phong tessellation's corner `i` projects onto for the curve of edge `e`.
fn edge_normal(c: &Corners, i: usize, e: usize) -> Vec3 {
    if c.seam_phong[e] {
        c.g[i]
    } else {
        c.n[i]
    }
}

/// Chord-error bound: Phong tessellation is a quadratic, the Bézier net of degree 2
/// `P = Σ w_i P_i − α Σ_{i<j} w_i w_j K_ij`, `K_ij = ((P_j − P_i)·a_i) a_i + ((P_i − P_j)·a_j) a_j`
/// (`a_i` the corner's tangent-plane normal), so `D²P[d_ij, d_ij] = 2α K_ij` exactly and the edge
/// error at `N` segments is exactly `α |K_ij| / (4 N²)`. A corner whose two edges pick different
/// normals (a flagged seam, src/surface/record.rs) blends them inside the triangle, which is not
/// a polynomial: such an element has no finite interior bound (the flat triangle's net, with
/// `|Phong − flat| <= α · max |p − P_i| <= α ·` the longest edge), unless only the edges' curves
/// are wanted (`edges_only`: each edge's curve is the quadratic of its own normals) or `α = 0`
/// (the flat triangle exactly: [`eval`] draws `p · 1 + curved · 0`, the net's midpoints).
pub fn net(params: &SurfaceParams, c: &Corners, _: &[VertexTag; 3], edges_only: bool) -> Patch {
    let alpha = params.alpha;
    let corner = |w: [usize; 3]| (0..3).find(|&i| w[i] == w.iter().sum::<usize>());
    let mixed = alpha != 0.0
        && (0..3).any(|i| {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            edge_normal(c, i, edge_of(i, j)) != edge_normal(c, i, edge_of(i, k))
        });
    if mixed && !edges_only {
        let longest = (0..3)
            .map(|i| (c.p[(i + 1) % 3] - c.p[i]).length())
            .fold(0.0, f32::max);
        return Patch::Near(flat::linear_net(c.p), alpha * longest);
    }
    Patch::Exact(Net::from_fn(2, |w| match corner(w) {
        Some(i) => c.p[i],
        None => {
            let i = (0..3).find(|&i| w[i] == 1).unwrap();
            let j = (i + 1..3).find(|&j| w[j] == 1).unwrap();
            let e = edge_of(i, j);
            let (ai, aj) = (edge_normal(c, i, e), edge_normal(c, j, e));
            let k = ai * dot3(c.p[j] - c.p[i], ai) + aj * dot3(c.p[i] - c.p[j], aj);
            (c.p[i] + c.p[j]) * 0.5 - k * (0.5 * alpha)
        }
    }))
}
