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
    Capture, DrawConfig, DrawWords, GpuMesh, PushBlock, RenderError, Renderer, Scene, Submit,
    PUSH_DRAW_OFFSET, PUSH_STAGES,
};
use crate::gpu::shaders::names;
use crate::gpu::{vk, Cmd, CommandPool, Context, GraphicsPipelineDesc};
use crate::pattern::{index_count, vertex_count};
use crate::surface::{ElementRecord, RECORD_BYTES};
use std::sync::Arc;

mod bins;
pub use bins::{check_adaptive_fits, check_integer_levels, AdaptivePattern};

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
        pattern_bytes(self.stored(level, elements), elements)
    }

    /// The hierarchical patterns, or every integer level's
    /// ([`adaptive_stored`](crate::pattern::adaptive::adaptive_stored)).
    fn stored_adaptive(&self, level: u32, _elements: u64, dyadic: bool) -> (u64, u64) {
        crate::pattern::adaptive::adaptive_stored(level, dyadic)
    }

    fn adaptive_geometry_bytes(
        &self,
        level: u32,
        elements: u64,
        dyadic: bool,
        _fragment_field: bool,
    ) -> u64 {
        pattern_bytes(self.stored_adaptive(level, elements, dyadic), elements)
    }

    fn capture_per_element(&self, level: u32) -> Option<u32> {
        Some(vertex_count(level))
    }

    fn export_capture(&self) -> Option<Capture> {
        Some(Capture::Vertices)
    }

    /// Its hierarchical patterns need a power of two ([`check_adaptive_level`]).
    fn adaptive_pipeline(&self, level: u32) -> bool {
        level.is_power_of_two()
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

    /// The adaptive vertex stage: the patterns' `(w, u, v)` per vertex (the hierarchy's or the
    /// integer patterns'), the element of
    /// each instance from its bin's list (`instanced`); records read as texels (`fetch_record`).
    fn describe_adaptive_pipeline(
        &self,
        desc: &mut GraphicsPipelineDesc,
        _fragment_field: bool,
        capture: Capture,
    ) {
        let vert = match capture {
            Capture::Vertices => names::PATTERN_ADAPTIVE_VERT_CAPTURE,
            Capture::None | Capture::Triangles => names::PATTERN_ADAPTIVE_VERT,
        };
        desc.stages = vec![(vk::ShaderStageFlags::VERTEX, vert.into())];
        desc.topology = vk::PrimitiveTopology::TRIANGLE_LIST;
        desc.vertex_bindings = vec![(0, 12, false), (2, 4, true)];
        desc.vertex_attributes = vec![
            (0, 0, vk::Format::R32G32B32_SFLOAT, 0),
            (8, 2, vk::Format::R32_UINT, 0),
        ];
    }

    /// At a power of two, the adaptive draws' buffers and pass for the elements `cfg` draws
    /// (kept while the level stays), where the device can hold them ([`check_adaptive_fits`]
    /// says why not to an adaptive frame).
    fn prepare(
        &self,
        scene: &mut Scene,
        ctx: &Arc<Context>,
        pool: &CommandPool,
        cfg: &DrawConfig,
    ) -> Result<(), RenderError> {
        if !cfg.level.is_power_of_two() {
            return Ok(());
        }
        let mesh = match &mut scene.loop_ {
            Some(l) if cfg.surface.uses_loop_faces() => &mut l.gpu,
            _ => &mut scene.gpu,
        };
        let dyadic = cfg.dyadic_levels();
        if check_adaptive_fits(ctx, mesh.element_count, mesh.chunk, cfg.level, dyadic).is_err() {
            mesh.adaptive = None;
            return Ok(());
        }
        if (mesh.adaptive.as_ref()).is_none_or(|a| a.level != cfg.level || a.dyadic != dyadic) {
            mesh.adaptive = None;
            mesh.adaptive = Some(AdaptivePattern::new(ctx, pool, mesh, cfg.level, dyadic)?);
        }
        Ok(())
    }

    /// A power-of-two level ([`check_adaptive_level`]) and room for the commands and bins
    /// ([`check_adaptive_fits`]).
    fn check_adaptive(
        &self,
        ctx: &Context,
        scene: &Scene,
        cfg: &DrawConfig,
    ) -> Result<(), RenderError> {
        check_adaptive_level(cfg)?;
        let mesh = scene.elements(cfg.surface);
        let dyadic = cfg.dyadic_levels();
        check_adaptive_fits(ctx, mesh.element_count, mesh.chunk, cfg.level, dyadic)
    }

    /// An adaptive frame's bins pass.
    fn cmd_before_rendering(&self, cmd: &Cmd<'_>, _r: &Renderer, work: &FrameWork<'_>) {
        if work.adaptive {
            adaptive_of(work).cmd_bins(cmd, work.elements.clone());
        }
    }

    fn cmd_draw(&self, cmd: &Cmd<'_>, r: &Renderer, work: &FrameWork<'_>) {
        if work.adaptive {
            cmd_draw_adaptive(
                cmd,
                r,
                work.mesh,
                work.records,
                adaptive_of(work),
                work.cfg.driver.submit().unwrap_or_default(),
                work.elements.clone(),
            );
            return;
        }
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

/// Bytes of patterns storing `(vertices, indices)` (12 bytes a vertex, 4 an index) and
/// `elements` records.
fn pattern_bytes((vertices, indices): (u64, u64), elements: u64) -> u64 {
    vertices * 12 + indices * 4 + elements * RECORD_BYTES as u64
}

/// The adaptive draws `work` needs (built by `prepare`, checked by
/// [`DriverKind::check_adaptive`]).
fn adaptive_of<'a>(work: &FrameWork<'a>) -> &'a AdaptivePattern {
    work.mesh
        .adaptive
        .as_ref()
        .filter(|a| a.level == work.cfg.level && a.dyadic == work.cfg.dyadic_levels())
        .expect("an adaptive frame at a power of two, prepared")
}

/// Whether the pattern driver can draw `cfg` adaptively (`FrameWork::adaptive`): the
/// hierarchical patterns need the largest level to be a power of two (the integer patterns
/// take the same largest level). One sentence otherwise.
pub fn check_adaptive_level(cfg: &DrawConfig) -> Result<(), RenderError> {
    if cfg.driver.submit().is_none() {
        return Ok(());
    }
    check_dyadic(
        cfg.level,
        "the pattern driver needs the largest level to be a power of two (its geomorphing patterns are 1-to-4 splits)",
        "--level ",
    )
}

/// The one sentence refusing adaptive drawing at largest `level` unless it is a power of two
/// (the hierarchical patterns' 1-to-4 splits): `driver` says which driver and why, `option` is
/// written before the two powers of two around `level` it suggests.
pub(super) fn check_dyadic(level: u32, driver: &str, option: &str) -> Result<(), RenderError> {
    if level.is_power_of_two() {
        return Ok(());
    }
    let lower = 1u32 << level.max(1).ilog2();
    Err(RenderError::Incompatible(format!(
        "adaptive drawing with {driver}, not {level}: use {option}{lower} or {}",
        lower * 2
    )))
}

/// Record the adaptive draws of the elements `range` of `mesh` (the bins pass already
/// recorded): the patterns' vertices and index ranges (the hierarchy's, or the integer
/// patterns'), the commands the pass
/// wrote. The same per-element loop as [`cmd_draw`] for `push` and `ubo`; one indirect draw per
/// chunk and level for `instanced`.
fn cmd_draw_adaptive(
    cmd: &Cmd<'_>,
    r: &Renderer,
    mesh: &GpuMesh,
    records: &[ElementRecord],
    a: &AdaptivePattern,
    submit: Submit,
    range: std::ops::Range<u32>,
) {
    // The capture's slots per element: the finest level's vertices.
    let slots = vertex_count(a.level);
    let draw = |base: u32, local: u32| -> DrawWords { [a.level, base, slots, local] };
    let push_draw = |words: DrawWords| {
        cmd.push_constants(
            r.layout.raw,
            PUSH_STAGES,
            PUSH_DRAW_OFFSET,
            bytemuck::cast_slice(&words),
        )
    };
    cmd.bind_vertex_buffer(0, &a.vertices);
    // The element lists (`instanced` rebinds them per bin; the other modes ignore them).
    cmd.bind_vertex_buffer(2, &a.lists);
    cmd.bind_index_buffer_u32(&a.indices);
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
                    cmd.draw_indexed_indirect(&a.commands, a.element_command(e));
                }
            }
            Submit::Ubo => {
                let mut window = None;
                for e in elements {
                    let w = e / UBO_WINDOW;
                    if window != Some(w) {
                        let offset = (w as u64 * UBO_WINDOW as u64 * RECORD_BYTES as u64) as u32;
                        cmd.bind_descriptor_set(r.layout.raw, SET_MESH, c.set, &[offset]);
                        window = Some(w);
                    }
                    push_draw(draw(c.base, e - c.base));
                    cmd.draw_indexed_indirect(&a.commands, a.element_command(e));
                }
            }
            Submit::Instanced => {
                cmd.bind_descriptor_set(r.layout.raw, SET_MESH, c.set, &[0]);
                push_draw(draw(c.base, 0));
                // The bins were filled from the drawn range only, so a bin holds exactly the
                // elements of this chunk to draw at its level.
                for l in 0..a.levels() {
                    cmd.bind_vertex_buffer_at(2, &a.lists, a.bin_list(c.base, l));
                    cmd.draw_indexed_indirect(&a.commands, a.bin_command(c.base, l));
                }
            }
        }
    }
}
