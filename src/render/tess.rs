//! `tess` driver: Vulkan tessellation shaders. Each coarse triangle is a 3-vertex patch; the
//! control stage sets every level to N, the evaluation stage evaluates the surface.
//!
//! lavapipe workaround (../PLATFORM.md): a tessellated draw whose evaluation stage emits more than
//! 65,536 vertices renders garbage there, so on lavapipe the patches are split into draws of at
//! most 65,535 evaluated vertices. gl_PrimitiveID restarts in every draw, so each draw pushes its
//! first triangle. A second lavapipe bug, found by the loop surface's tests (2026-12-01): past
//! 4,095 patch vertices (1,365 triangle patches) in one draw its gl_PrimitiveID in the evaluation
//! stage starts over (Mesa's draw module splits draws into chunks of 4,096 vertices), so patches
//! past that read another element's record; draws on lavapipe also hold at most 1,365 patches.
//! Other devices get one draw.

use super::bindings::SET_MESH;
use super::{GpuMesh, RenderError, Renderer, PUSH_DRAW_OFFSET, PUSH_STAGES};
use crate::gpu::{Cmd, Context};

/// Largest evaluated-vertex count of one tessellated draw that lavapipe renders correctly.
pub const LAVAPIPE_MAX_TESS_VERTICES_PER_DRAW: u32 = 65_535;

/// Most triangle patches of one tessellated draw whose gl_PrimitiveID lavapipe numbers right.
pub const LAVAPIPE_MAX_PATCHES_PER_DRAW: u32 = 4_095 / 3;

/// Check `level` against the device's maxTessellationGenerationLevel.
pub fn check_level(ctx: &Context, level: u32) -> Result<(), RenderError> {
    let max = ctx.info.limits.max_tessellation_generation_level;
    if level > max {
        return Err(RenderError::TessLevel { level, max });
    }
    Ok(())
}

/// Patches per draw on this device for `level`.
pub fn patches_per_draw(ctx: &Context, level: u32, triangles: u32) -> u32 {
    if ctx.info.is_lavapipe() {
        (LAVAPIPE_MAX_TESS_VERTICES_PER_DRAW / tess_vertex_count(level))
            .clamp(1, LAVAPIPE_MAX_PATCHES_PER_DRAW)
    } else {
        triangles.max(1)
    }
}

/// Record the tessellated draws of the elements `range` of `mesh` at `level`, chunk by chunk
/// ([`GpuMesh::chunks`]).
pub fn cmd_draw(
    cmd: &Cmd<'_>,
    r: &Renderer,
    mesh: &GpuMesh,
    level: u32,
    range: std::ops::Range<u32>,
) {
    let per_draw = patches_per_draw(cmd.context(), level, mesh.element_count);
    for c in mesh.chunks(range) {
        cmd.bind_descriptor_set(r.layout.raw, SET_MESH, c.set, &[0]);
        let mut first = c.first;
        while first < c.first + c.count {
            let count = per_draw.min(c.first + c.count - first);
            // x level, y the chunk's first element, z tessellator vertices, w this draw's first
            // element within the chunk (gl_PrimitiveID counts from there).
            let draw = [level, c.base, tess_vertex_count(level), first - c.base];
            cmd.push_constants(
                r.layout.raw,
                PUSH_STAGES,
                PUSH_DRAW_OFFSET,
                bytemuck::cast_slice(&draw),
            );
            cmd.draw(3 * count, 1, 0, 0);
            first += count;
        }
    }
}

/// Distinct vertices the tessellator makes for one triangle patch with every level `n` (integer,
/// equal spacing): concentric rings of `n, n-2, n-4, ...` segments per side, closed by a centre
/// vertex (even `n`) or a last triangle (odd `n`). Vulkan spec, "Triangle Tessellation".
pub const fn tess_vertex_count(n: u32) -> u32 {
    if n % 2 == 0 {
        let h = n / 2;
        3 * h * (h + 1) + 1
    } else {
        let h = n.div_ceil(2);
        3 * h * h
    }
}

/// Triangles the tessellator makes for one patch at level `n`: a ring of `m` segments and the
/// ring inside it (`m - 2`) are joined by `6m - 6` triangles; an innermost ring of one segment is
/// one triangle. More than a level-`n` pattern's `n²` for `n >= 2` (1.5x as `n` grows).
pub const fn tess_triangle_count(n: u32) -> u32 {
    let mut m = n;
    let mut t = 0;
    while m >= 2 {
        t += 6 * m - 6;
        m -= 2;
    }
    if m == 1 {
        t += 1;
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tessellator_counts() {
        assert_eq!((tess_vertex_count(1), tess_triangle_count(1)), (3, 1));
        assert_eq!((tess_vertex_count(2), tess_triangle_count(2)), (7, 6));
        assert_eq!((tess_vertex_count(3), tess_triangle_count(3)), (12, 13));
        assert_eq!((tess_vertex_count(4), tess_triangle_count(4)), (19, 24));
        assert_eq!(tess_triangle_count(64), 6144);
        // Euler: a triangulated disk has V - E + F = 1, E = (3F + boundary) / 2, boundary = 3n.
        for n in 1..40u32 {
            let (v, f) = (tess_vertex_count(n) as i64, tess_triangle_count(n) as i64);
            let e = (3 * f + 3 * n as i64) / 2;
            assert_eq!(v - e + f, 1, "level {n}");
        }
    }
}
