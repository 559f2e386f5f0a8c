//! `tess` driver: Vulkan tessellation shaders. Each coarse triangle is a 3-vertex patch; the
//! control stage sets every level to N, the evaluation stage evaluates the surface.
//!
//! lavapipe workaround (../PLATFORM.md): a tessellated draw whose evaluation stage emits more than
//! 65,536 vertices renders garbage there, so on lavapipe the patches are split into draws of at
//! most 65,535 evaluated vertices. gl_PrimitiveID restarts in every draw, so each draw pushes its
//! first triangle. Other devices get one draw.

use super::{GpuMesh, Renderer, PUSH_DRAW_OFFSET};
use crate::gpu::conv::PUSH_STAGES;
use crate::gpu::{Cmd, Context, GpuError};
use crate::pattern::vertex_count;

/// Largest evaluated-vertex count of one tessellated draw that lavapipe renders correctly.
pub const LAVAPIPE_MAX_TESS_VERTICES_PER_DRAW: u32 = 65_535;

/// Check `level` against the device's maxTessellationGenerationLevel.
pub fn check_level(ctx: &Context, level: u32) -> Result<(), GpuError> {
    let max = ctx.info.limits.max_tessellation_generation_level;
    if level > max {
        return Err(GpuError::Other(format!(
            "level {level} is beyond this device's maxTessellationGenerationLevel ({max}): the tess driver cannot draw it (use --driver pattern)"
        )));
    }
    Ok(())
}

/// Patches per draw on this device for `level`.
pub fn patches_per_draw(ctx: &Context, level: u32, triangles: u32) -> u32 {
    if ctx.info.is_lavapipe() {
        (LAVAPIPE_MAX_TESS_VERTICES_PER_DRAW / vertex_count(level)).max(1)
    } else {
        triangles.max(1)
    }
}

/// Record the tessellated draws of `mesh` at `level`.
pub fn cmd_draw(cmd: &Cmd<'_>, r: &Renderer, mesh: &GpuMesh, level: u32) {
    let per_draw = patches_per_draw(cmd.context(), level, mesh.triangle_count);
    let mut first = 0;
    while first < mesh.triangle_count {
        let count = per_draw.min(mesh.triangle_count - first);
        let draw = [level, first, vertex_count(level), 0];
        cmd.push_constants(
            r.layout.raw,
            PUSH_STAGES,
            PUSH_DRAW_OFFSET,
            bytemuck::cast_slice(&draw),
        );
        cmd.draw(3 * count, 1, 3 * first, 0);
        first += count;
    }
}
