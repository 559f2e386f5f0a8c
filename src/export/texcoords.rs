//! Texture coordinates of exported vertices. The GPU's capture holds each vertex's element and
//! sample but not its texture coordinates, so they are computed here, on the CPU, as the
//! surfaces compute the coordinates the height map reads: the element's corner coordinates
//! interpolated linearly by the sample's barycentric weights, in the surface's corner order, so
//! that both sides of a shared edge with the same coordinates at its ends give the same bits
//! (docs/architecture.md, "The seam").

use crate::surface::{eval_local, ElementRecord, NormalField, Surface, SurfaceParams};
use glam::Vec2;

/// Texture coordinates at barycentric `bary` of element `rec` of a local surface whose corners
/// have coordinates `corners`: exactly the `uv` the surface's CPU mirror evaluates there.
pub fn element_texcoord(
    surface: Surface,
    params: &SurfaceParams,
    rec: &ElementRecord,
    bary: [f32; 3],
    corners: &[[f32; 2]; 3],
) -> Vec2 {
    // The coordinates depend on the corner order alone, not on the normal field or tags.
    let field = NormalField::default();
    eval_local(surface, params, field, None, rec, bary, Some(corners)).uv
}
