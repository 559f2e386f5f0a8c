//! `pattern` driver (Boubekeur & Schlick 2005, §3.2): one refinement pattern drawn per coarse
//! triangle, the vertex shader maps it onto the triangle's surface. Three ways to hand over the
//! triangle's record, all measured by the benchmark:
//! - `push`: for each coarse triangle, push constants then a draw (the paper's loop);
//! - `ubo`: for each coarse triangle, a dynamic uniform-buffer offset then a draw;
//! - `instanced`: one instanced draw, records in a storage buffer indexed by gl_InstanceIndex.

use super::bindings::SET_MESH;
use super::scene::GpuPattern;
use super::{GpuMesh, PushBlock, Renderer, Submit, PUSH_DRAW_OFFSET};
use crate::gpu::conv::PUSH_STAGES;
use crate::gpu::Cmd;
use crate::surface::CoarseTri;

/// Record the draws of `mesh` with `pattern` in submission mode `submit`. `records` is the CPU
/// copy of the coarse records (the `push` mode sends them from the command buffer).
pub fn cmd_draw(
    cmd: &Cmd<'_>,
    r: &Renderer,
    mesh: &GpuMesh,
    records: &[CoarseTri],
    pattern: &GpuPattern,
    submit: Submit,
) {
    let draw = [pattern.level, 0, pattern.vertex_count, 0];
    cmd.bind_vertex_buffer(0, &pattern.vertices);
    cmd.bind_index_buffer_u32(&pattern.indices);
    match submit {
        Submit::Push => {
            for rec in records {
                let block = PushBlock { tri: *rec, draw };
                cmd.push_constants(r.layout.raw, PUSH_STAGES, 0, bytemuck::bytes_of(&block));
                cmd.draw_indexed(pattern.index_count, 1, 0, 0, 0);
            }
        }
        Submit::Ubo => {
            cmd.push_constants(
                r.layout.raw,
                PUSH_STAGES,
                PUSH_DRAW_OFFSET,
                bytemuck::cast_slice(&draw),
            );
            for t in 0..mesh.triangle_count as u64 {
                let offset = (t * mesh.ubo_stride) as u32;
                cmd.bind_descriptor_set(r.layout.raw, SET_MESH, mesh.set, &[offset]);
                cmd.draw_indexed(pattern.index_count, 1, 0, 0, 0);
            }
        }
        Submit::Instanced => {
            cmd.push_constants(
                r.layout.raw,
                PUSH_STAGES,
                PUSH_DRAW_OFFSET,
                bytemuck::cast_slice(&draw),
            );
            cmd.draw_indexed(pattern.index_count, mesh.triangle_count, 0, 0, 0);
        }
    }
}
