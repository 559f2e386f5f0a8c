//! `pattern` driver (Boubekeur & Schlick 2005, §3.2): one refinement pattern drawn per element
//! (coarse triangle), the vertex shader maps it onto the element's surface. Three ways to hand
//! over the element's record (opaque to the driver), all measured by the benchmark:
//! - `push`: for each element, push constants (record + draw words) then a draw (the paper's loop);
//! - `ubo`: for each element, a dynamic uniform-buffer offset and the draw words, then a draw;
//! - `instanced`: one instanced draw per chunk, the records read as instance-rate vertex
//!   attributes (the records buffer as vertex buffer 1, `firstInstance` = the first element).

use super::bindings::{SET_MESH, UBO_WINDOW};
use super::driver::DriverKind;
use super::frame::FrameWork;
use super::gpu_mesh::GpuPattern;
use super::{
    Capture, DrawWords, GpuMesh, PushBlock, Renderer, Submit, PUSH_DRAW_OFFSET, PUSH_STAGES,
};
use crate::gpu::shaders::names;
use crate::gpu::{vk, Cmd, GraphicsPipelineDesc};
use crate::pattern::{index_count, vertex_count};
use crate::surface::{ElementRecord, RECORD_BYTES};

/// Record the draws of the elements `range` of `mesh` with `pattern` in submission mode
/// `submit`, chunk by chunk ([`GpuMesh::chunks`]). `records` is the CPU copy of the element
/// records (the `push` mode sends them from the command buffer).
pub fn cmd_draw(
    cmd: &Cmd<'_>,
    r: &Renderer,
    mesh: &GpuMesh,
    records: &[ElementRecord],
    pattern: &GpuPattern,
    submit: Submit,
    range: std::ops::Range<u32>,
) {
    // x level, y the chunk's first element, z pattern vertices, w the element within the chunk.
    let draw =
        |base: u32, local: u32| -> DrawWords { [pattern.level, base, pattern.vertex_count, local] };
    let push_draw = |words: DrawWords| {
        cmd.push_constants(
            r.layout.raw,
            PUSH_STAGES,
            PUSH_DRAW_OFFSET,
            bytemuck::cast_slice(&words),
        )
    };
    cmd.bind_vertex_buffer(0, &pattern.vertices);
    // The records as instance-rate attributes (`instanced` reads them; the other modes draw
    // instance 0 and ignore it).
    cmd.bind_vertex_buffer(1, &mesh.records);
    cmd.bind_index_buffer_u32(&pattern.indices);
    for c in mesh.chunks(range) {
        let elements = c.first..c.first + c.count;
        match submit {
            Submit::Push => {
                cmd.bind_descriptor_set(r.layout.raw, SET_MESH, c.set, &[0]);
                for e in elements {
                    let block = PushBlock {
                        rec: records[e as usize],
                        draw: draw(c.base, e - c.base),
                    };
                    cmd.push_constants(r.layout.raw, PUSH_STAGES, 0, bytemuck::bytes_of(&block));
                    cmd.draw_indexed(pattern.index_count, 1, 0, 0, 0);
                }
            }
            Submit::Ubo => {
                // The window of UBO_WINDOW records holding `e` is bound when `e` enters it;
                // the shader picks `e % UBO_WINDOW` in it.
                let mut window = None;
                for e in elements {
                    let w = e / UBO_WINDOW;
                    if window != Some(w) {
                        let offset = (w as u64 * UBO_WINDOW as u64 * RECORD_BYTES as u64) as u32;
                        cmd.bind_descriptor_set(r.layout.raw, SET_MESH, c.set, &[offset]);
                        window = Some(w);
                    }
                    push_draw(draw(c.base, e - c.base));
                    cmd.draw_indexed(pattern.index_count, 1, 0, 0, 0);
                }
            }
            Submit::Instanced => {
                cmd.bind_descriptor_set(r.layout.raw, SET_MESH, c.set, &[0]);
                // gl_InstanceIndex counts from first_instance = the first element: the record
                // attributes are fetched by element, whatever chunk is bound.
                push_draw(draw(c.base, 0));
                cmd.draw_indexed(pattern.index_count, c.count, 0, 0, c.first);
            }
        }
    }
}

/// The `pattern` driver's answers ([`DriverKind`]); the submission mode travels in
/// [`super::Driver::Pattern`].
pub struct PatternDriver;

impl DriverKind for PatternDriver {
    fn name(&self) -> &'static str {
        "pattern"
    }

    fn help(&self) -> &'static str {
        "The refinement pattern is drawn for every coarse triangle; the vertex shader evaluates"
    }

    /// The pattern's level².
    fn refined_per_element(&self, level: u32) -> u32 {
        crate::pattern::triangle_count(level)
    }

    /// One pattern, whatever the element count.
    fn stored(&self, level: u32, _elements: u64) -> (u64, u64) {
        (vertex_count(level) as u64, index_count(level) as u64)
    }

    /// The pattern (12 bytes a vertex, 4 an index) and the records.
    fn geometry_bytes(&self, level: u32, elements: u64, _fragment_field: bool) -> u64 {
        let (vertices, indices) = self.stored(level, elements);
        vertices * 12 + indices * 4 + elements * RECORD_BYTES as u64
    }

    fn capture_per_element(&self, level: u32) -> Option<u32> {
        Some(vertex_count(level))
    }

    fn export_capture(&self) -> Option<Capture> {
        Some(Capture::Vertices)
    }

    fn describe_pipeline(
        &self,
        desc: &mut GraphicsPipelineDesc,
        _fragment_field: bool,
        capture: Capture,
    ) {
        let vert = match capture {
            Capture::Vertices => names::PATTERN_PATTERN_VERT_CAPTURE,
            Capture::None | Capture::Triangles => names::PATTERN_PATTERN_VERT,
        };
        desc.stages = vec![(vk::ShaderStageFlags::VERTEX, vert.into())];
        desc.topology = vk::PrimitiveTopology::TRIANGLE_LIST;
        // (w, u, v) per vertex; the element's record per instance (`instanced`).
        desc.vertex_bindings = vec![(0, 12, false), (1, RECORD_BYTES as u32, true)];
        desc.vertex_attributes = vec![(0, 0, vk::Format::R32G32B32_SFLOAT, 0)];
        desc.vertex_attributes.extend(
            (0..RECORD_BYTES as u32 / 16)
                .map(|k| (1 + k, 1, vk::Format::R32G32B32A32_UINT, 16 * k)),
        );
    }

    fn cmd_draw(&self, cmd: &Cmd<'_>, r: &Renderer, work: &FrameWork<'_>) {
        let p = work
            .mesh
            .pattern(work.cfg.level)
            .expect("pattern level is in the set");
        cmd_draw(
            cmd,
            r,
            work.mesh,
            work.records,
            p,
            work.cfg.driver.submit().unwrap_or_default(),
            work.elements.clone(),
        );
    }
}
