//! `flat` surface: linear interpolation of the coarse triangle (Boubekeur & Schlick 2005, §3.2:
//! `V = w·P0 + u·P1 + v·P2`), normals interpolated the same way and normalized.
//! Mirror of `glsl/include/flat.glsl`. Evaluated in the same operation order as the GLSL, which
//! marks it `precise` (no fused multiply-add), so CPU and GPU positions agree to the bit.

use super::bounds::{Patch, SurfaceBound};
use super::facts::{Elements, FragmentNormals, SurfaceFacts};
use super::stpn::VertexTag;
use super::{Corners, Local, SurfaceParams};
use crate::lod::Net;
use glam::Vec3;

/// What `flat` declares about itself (docs/architecture.md, "Surfaces as plug-ins").
pub const FACTS: SurfaceFacts = SurfaceFacts {
    name: "flat",
    help: "Linear interpolation of the coarse triangle's positions and normals",
    elements: Elements::CoarseTriangles,
    pre_pass: None,
    options: &[],
    texture_coordinates: true,
    needs_every_face: false,
    tags: false,
    fragment_normals: FragmentNormals::Never,
    bindings: &[],
    bound: SurfaceBound::Nets {
        geometry: net,
        direction,
    },
};

/// The flat point `Σ w_i P_i`.
pub fn point(c: &Corners) -> Vec3 {
    let [w0, w1, w2] = c.w;
    c.p[0] * w0 + c.p[1] * w1 + c.p[2] * w2
}

/// The normalized linear interpolation of the corner normals.
pub fn normal(c: &Corners) -> Vec3 {
    let [w0, w1, w2] = c.w;
    super::unit_field(c.n[0] * w0 + c.n[1] * w1 + c.n[2] * w2, c)
}

pub fn eval(c: &Corners) -> Local {
    Local {
        position: point(c),
        normal: normal(c),
        grad: c.p,
    }
}

/// The linear net with corners `p` (canonical order).
pub fn linear_net(p: [Vec3; 3]) -> Net {
    Net::from_fn(1, |w| p[(0..3).find(|&i| w[i] == 1).unwrap()])
}

/// Chord-error bound: `flat` is its own linear net, whose second derivatives are zero.
pub fn net(_: &SurfaceParams, c: &Corners, _: &[VertexTag; 3], _: bool) -> Patch {
    Patch::Exact(linear_net(c.p))
}

/// The direction field displacement moves along: the linear interpolation of the geometry
/// normals.
pub fn direction(
    _: &SurfaceParams,
    _: super::NormalField,
    c: &Corners,
    _: &[VertexTag; 3],
    _: bool,
) -> Vec<Net> {
    vec![linear_net(c.g)]
}
