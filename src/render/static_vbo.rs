//! `static` driver: the CPU refines every coarse triangle with the surface's Rust mirror and
//! uploads one vertex and index buffer: the "static VBO" baseline of Boubekeur & Schlick 2005 (§5,
//! Fig. 7). Its GPU footprint grows with (coarse triangles x pattern size); an animated mesh must
//! be refined and uploaded again every frame.

use super::bindings::SET_MESH;
use super::driver::DriverKind;
use super::frame::FrameWork;
use super::{
    Capture, DrawConfig, GpuMesh, RenderError, Renderer, Scene, PUSH_DRAW_OFFSET, PUSH_STAGES,
};
use crate::gpu::shaders::names;
use crate::gpu::{vk, Buffer, Cmd, CommandPool, Context, DeviceInfo, GraphicsPipelineDesc};
use crate::pattern::{index_count, vertex_count, Pattern};
use crate::surface::{ElementRecord, Mirror};
use std::sync::Arc;

/// Refined vertex: position, normal.
pub type StaticVertex = [f32; 6];

/// The static buffer's vertex for an evaluated point: position, then normal.
pub fn static_vertex(sp: &crate::surface::SurfacePoint) -> StaticVertex {
    let (p, n) = (sp.position, sp.normal);
    [p.x, p.y, p.z, n.x, n.y, n.z]
}

/// A refined vertex's sample, for the per-fragment normal field: `(w, u, v)` bits and element.
pub type ElementVertex = [u32; 4];

/// The whole mesh refined on the CPU: vertices (pattern order, one block per coarse triangle)
/// and the pattern's triangle list offset per triangle (the same vertex-cache order as the
/// pattern driver's, so the baseline shades as few vertices as the pattern does).
/// `mirror` is `cfg`'s surface and displacement with their inputs (`Scene::mirror`), `cfg` gives
/// the parameters (its driver and level are not used).
pub fn refine_on_cpu(
    cfg: &DrawConfig,
    records: &[ElementRecord],
    pattern: &Pattern,
    mirror: &Mirror,
) -> (Vec<StaticVertex>, Vec<u32>) {
    let pv = pattern.bary.len() as u32;
    let mut vertices = Vec::with_capacity(records.len() * pv as usize);
    let mut indices = Vec::with_capacity(records.len() * pattern.indices.len());
    for (t, rec) in records.iter().enumerate() {
        for &b in &pattern.bary {
            vertices.push(static_vertex(&mirror.eval(&cfg.params, t, rec, b)));
        }
        let base = t as u32 * pv;
        indices.extend(pattern.indices.iter().map(|&i| base + i));
    }
    (vertices, indices)
}

pub struct StaticVbo {
    /// What was refined (surface, displacement, parameters, level).
    pub cfg: DrawConfig,
    pub level: u32,
    /// Refined adaptively (src/render/static_adaptive.rs): each element's index range and
    /// levels, and what refining cost; `None`: every element at `level`.
    pub adaptive: Option<super::static_adaptive::AdaptiveIndex>,
    pub vertices: Buffer,
    /// Each vertex's element and sample ([`ElementVertex`]), when the normal field is evaluated
    /// per fragment.
    pub elements: Option<Buffer>,
    pub indices: Buffer,
    pub index_count: u32,
    pub vertex_count: u32,
    pub(super) pattern_vertex_count: u32,
    pub(super) pattern_index_count: u32,
}

/// Refuse a static buffer of `bytes` beyond maxMemoryAllocationSize (one buffer is one
/// allocation), before the CPU refines it: `what` names it, `remedy` says what to do instead.
pub(super) fn check_allocation(
    ctx: &Context,
    bytes: u64,
    what: impl FnOnce() -> String,
    remedy: &str,
) -> Result<(), RenderError> {
    check_allocation_on(&ctx.info, bytes, what, remedy)
}

/// [`check_allocation`] on `device`'s limits (read without opening it).
fn check_allocation_on(
    device: &DeviceInfo,
    bytes: u64,
    what: impl FnOnce() -> String,
    remedy: &str,
) -> Result<(), RenderError> {
    let max = device.max_memory_allocation_size;
    if bytes > max {
        return Err(RenderError::OverLimit {
            what: what(),
            needed: bytes,
            unit: "bytes",
            limit: "this device's maxMemoryAllocationSize",
            max,
            remedy: remedy.into(),
        });
    }
    Ok(())
}

/// Whether the refined mesh of `elements` elements at `pattern`'s level fits one allocation
/// on this device (one sentence where not).
fn check_uniform_size(
    ctx: &Context,
    elements: usize,
    pattern: &Pattern,
) -> Result<(), RenderError> {
    check_uniform_size_on(&ctx.info, elements as u64, pattern.level)
}

/// Whether the static driver's vertex buffer for `elements` elements at uniform `level` fits
/// one allocation on `device` (its limits read, nothing opened: `info --level` says so as
/// `render` would), one sentence where not.
pub fn check_uniform_size_on(
    device: &DeviceInfo,
    elements: u64,
    level: u32,
) -> Result<(), RenderError> {
    let bytes = elements * vertex_count(level) as u64 * std::mem::size_of::<StaticVertex>() as u64;
    check_allocation_on(
        device,
        bytes,
        || format!("the static driver's refined mesh at level {level}"),
        if level > 1 {
            "use a lower level or the pattern driver"
        } else {
            "use the pattern driver"
        },
    )
}

impl StaticVbo {
    pub fn new(
        ctx: &Arc<Context>,
        pool: &CommandPool,
        cfg: &DrawConfig,
        records: &[ElementRecord],
        pattern: &Pattern,
        mirror: &Mirror,
    ) -> Result<Self, RenderError> {
        // Check the size before refining: the CPU would hold the same bytes.
        check_uniform_size(ctx, records.len(), pattern)?;
        let (v, i) = refine_on_cpu(cfg, records, pattern, mirror);
        let vertices = Buffer::new_with_data(
            ctx,
            pool,
            vk::BufferUsageFlags::VERTEX_BUFFER,
            &v,
            "static vertices",
        )?;
        let indices = Buffer::new_with_data(
            ctx,
            pool,
            vk::BufferUsageFlags::INDEX_BUFFER,
            &i,
            "static triangles",
        )?;
        let elements = if cfg.fragment_normal_field() {
            let e: Vec<ElementVertex> = (0..records.len() as u32)
                .flat_map(|t| {
                    pattern
                        .bary
                        .iter()
                        .map(move |b| [b[0].to_bits(), b[1].to_bits(), b[2].to_bits(), t])
                })
                .collect();
            Some(Buffer::new_with_data(
                ctx,
                pool,
                vk::BufferUsageFlags::VERTEX_BUFFER,
                &e,
                "static vertex samples",
            )?)
        } else {
            None
        };
        Ok(Self {
            cfg: *cfg,
            level: pattern.level,
            adaptive: None,
            vertices,
            elements,
            pattern_index_count: pattern.indices.len() as u32,
            indices,
            index_count: i.len() as u32,
            vertex_count: v.len() as u32,
            pattern_vertex_count: pattern.bary.len() as u32,
        })
    }
}

/// Record the static driver's draws of the elements `range`: one indexed draw per chunk of
/// records ([`GpuMesh::chunks`]; the fragment stage reads records of the bound chunk), a single
/// draw for every mesh that fits one; an adaptive mesh with `per_element`, one draw per element
/// ([`FrameWork::element_draws`](super::frame::FrameWork::element_draws)).
pub fn cmd_draw(
    cmd: &Cmd<'_>,
    r: &Renderer,
    mesh: &GpuMesh,
    vbo: &StaticVbo,
    range: std::ops::Range<u32>,
    per_element: bool,
) {
    cmd.bind_vertex_buffer(0, &vbo.vertices);
    if let Some(e) = &vbo.elements {
        cmd.bind_vertex_buffer(1, e);
    }
    cmd.bind_index_buffer_u32(&vbo.indices);
    if let Some(a) = &vbo.adaptive {
        // Vertices that carry their element need no draw of their own per element.
        let per_element = per_element && vbo.elements.is_none();
        super::static_adaptive::cmd_draw(cmd, r, mesh, vbo.level, a, range, per_element);
        return;
    }
    for c in mesh.chunks(range) {
        cmd.bind_descriptor_set(r.layout.raw, SET_MESH, c.set, &[0]);
        let draw = [vbo.level, c.base, vbo.pattern_vertex_count, 0];
        cmd.push_constants(
            r.layout.raw,
            PUSH_STAGES,
            PUSH_DRAW_OFFSET,
            bytemuck::cast_slice(&draw),
        );
        let per = vbo.pattern_index_count;
        cmd.draw_indexed(c.count * per, 1, c.first * per, 0, 0);
    }
}

/// The `static` driver's answers ([`DriverKind`]).
pub struct StaticDriver;

impl DriverKind for StaticDriver {
    fn name(&self) -> &'static str {
        "static"
    }

    fn help(&self) -> &'static str {
        "The CPU refines the whole mesh into one vertex buffer (the 2005 paper's baseline)"
    }

    fn refines_on_cpu(&self) -> bool {
        true
    }

    /// The pattern's level² (what the static buffer stores).
    fn refined_per_element(&self, level: u32) -> u32 {
        crate::pattern::triangle_count(level)
    }

    fn stored(&self, level: u32, elements: u64) -> (u64, u64) {
        (
            elements * vertex_count(level) as u64,
            elements * index_count(level) as u64,
        )
    }

    fn geometry_bytes(&self, level: u32, elements: u64, fragment_field: bool) -> u64 {
        let (vertices, indices) = self.stored(level, elements);
        let mut per_vertex = std::mem::size_of::<StaticVertex>() as u64;
        if fragment_field {
            per_vertex += std::mem::size_of::<ElementVertex>() as u64;
        }
        vertices * per_vertex + indices * 4
    }

    fn capture_per_element(&self, _level: u32) -> Option<u32> {
        None
    }

    fn export_capture(&self) -> Option<Capture> {
        None
    }

    fn describe_pipeline(
        &self,
        desc: &mut GraphicsPipelineDesc,
        fragment_field: bool,
        _capture: Capture,
    ) {
        let vert = if fragment_field {
            names::STATIC_STATIC_VERT_ELEMENTS
        } else {
            names::STATIC_STATIC_VERT
        };
        desc.stages = vec![(vk::ShaderStageFlags::VERTEX, vert.into())];
        desc.topology = vk::PrimitiveTopology::TRIANGLE_LIST;
        // position + normal, 24 bytes per vertex
        desc.vertex_bindings = vec![(0, 24, false)];
        desc.vertex_attributes = vec![
            (0, 0, vk::Format::R32G32B32_SFLOAT, 0),
            (1, 0, vk::Format::R32G32B32_SFLOAT, 12),
        ];
        if fragment_field {
            // (w, u, v) + element, 16 bytes per vertex (ElementVertex)
            desc.vertex_bindings.push((1, 16, false));
            desc.vertex_attributes.extend([
                (2, 1, vk::Format::R32G32B32_SFLOAT, 0),
                (3, 1, vk::Format::R32_UINT, 12),
            ]);
        }
    }

    /// The uniform refined mesh's size, before the slow-frame warning and the refinement
    /// (adaptive frames check theirs when their levels are chosen).
    fn check_fits(
        &self,
        scene: &Scene,
        ctx: &Context,
        cfg: &DrawConfig,
    ) -> Result<(), RenderError> {
        if scene.adaptive_frames {
            return Ok(());
        }
        let idx = scene.patterns.find(cfg.level).unwrap();
        let elements = scene.records(cfg.surface).len();
        check_uniform_size(ctx, elements, &scene.patterns.patterns[idx])
    }

    /// Refine the mesh on the CPU unless the buffer already holds `cfg`'s surface at its level;
    /// for adaptive frames, at the levels of the last `Scene::set_levels`, again when they
    /// change (src/render/static_adaptive.rs).
    fn prepare(
        &self,
        scene: &mut Scene,
        ctx: &Arc<Context>,
        pool: &CommandPool,
        cfg: &DrawConfig,
    ) -> Result<(), RenderError> {
        if scene.adaptive_frames {
            return super::static_adaptive::prepare(scene, ctx, pool, cfg);
        }
        let stale = scene.static_vbo.as_ref().is_none_or(|v| {
            v.adaptive.is_some()
                || v.level != cfg.level
                || v.cfg.surface != cfg.surface
                || v.cfg.displace != cfg.displace
                || v.cfg.params != cfg.params
                || v.cfg.build != cfg.build
        });
        if stale {
            scene.static_vbo = None;
            let idx = scene.patterns.find(cfg.level).unwrap();
            scene.static_vbo = Some(StaticVbo::new(
                ctx,
                pool,
                cfg,
                scene.records(cfg.surface),
                &scene.patterns.patterns[idx],
                &scene.mirror(cfg, cfg.level)?,
            )?);
        }
        Ok(())
    }

    /// A power of two the largest level (the pattern driver's construction).
    fn check_adaptive(
        &self,
        _ctx: &Context,
        _scene: &Scene,
        cfg: &DrawConfig,
    ) -> Result<(), RenderError> {
        super::static_adaptive::check(cfg)
    }

    fn cmd_draw(&self, cmd: &Cmd<'_>, r: &Renderer, work: &FrameWork<'_>) {
        let Some(vbo) = work.static_vbo else {
            // An adaptive frame before any levels were chosen draws nothing, as the pattern
            // driver's with an empty levels buffer.
            assert!(work.adaptive, "static driver needs its vertex buffer");
            return;
        };
        cmd_draw(
            cmd,
            r,
            work.mesh,
            vbo,
            work.elements.clone(),
            work.element_draws,
        );
    }
}
