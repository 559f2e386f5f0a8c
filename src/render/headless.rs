//! Headless rendering into an offscreen target: images, capture of evaluated vertices, timings.
//! Every call records, submits and waits, so nothing is ever in flight when it returns.

use super::frame::{cmd_render, FrameWork, TargetView, CLEAR_COLOR};
use super::tess::tess_triangle_count;
use super::{
    Capture, CapturedVertex, DrawConfig, Driver, FrameUniforms, RenderError, Renderer, Scene,
    XfbVertex,
};
use crate::gpu::{
    vk, Buffer, BufferDesc, CommandPool, Context, ContextDesc, GpuError, OffscreenTarget,
    PipelineStats, QueryPools, Readback, DEPTH_FORMAT, OFFSCREEN_FORMAT,
};
use crate::mesh::Mesh;
use crate::pattern::vertex_count;
use crate::render::Camera;
use std::sync::Arc;
use std::time::Instant;

pub struct Headless {
    pub ctx: Arc<Context>,
    pub pool: CommandPool,
    pub renderer: Renderer,
    pub target: OffscreenTarget,
    pub queries: QueryPools,
    pub wireframe: bool,
    /// Show normals as colours instead of shading.
    pub view_normals: bool,
}

/// Vertices the capture variant of a driver's pipeline wrote.
/// - `pattern`: exactly `pattern_vertex_count` per coarse triangle, in pattern order, triangle
///   after triangle (`id = (triangle, pattern vertex)`).
/// - `tess`: every evaluation-stage invocation, in no particular order (`id.y = u32::MAX`,
///   `coord` = gl_TessCoord); an implementation may evaluate a vertex more than once.
pub struct CaptureResult {
    pub vertices: Vec<CapturedVertex>,
    pub pattern_vertex_count: u32,
    pub stats: Option<PipelineStats>,
}

/// Timings and counters of one frame.
#[derive(Clone, Copy, Debug)]
pub struct FrameTiming {
    pub gpu_ms: f64,
    pub wall_ms: f64,
    pub stats: Option<PipelineStats>,
}

/// The clear colour as the sRGB offscreen target stores it (8 bits per channel).
pub fn clear_color_srgb8() -> [u8; 4] {
    let encode = |c: f32| {
        let s = if c <= 0.003_130_8 {
            12.92 * c
        } else {
            1.055 * c.powf(1.0 / 2.4) - 0.055
        };
        (s.clamp(0.0, 1.0) * 255.0).round() as u8
    };
    let [r, g, b, a] = CLEAR_COLOR;
    [
        encode(r),
        encode(g),
        encode(b),
        (a.clamp(0.0, 1.0) * 255.0).round() as u8,
    ]
}

/// Pixels of a headless image that differ from the clear colour (by more than the rounding of
/// the sRGB conversion): 0 means nothing was drawn.
pub fn covered_pixels(image: &Readback) -> usize {
    let clear = clear_color_srgb8();
    image
        .rgba
        .chunks_exact(4)
        .filter(|px| px.iter().zip(clear).any(|(&p, c)| p.abs_diff(c) > 1))
        .count()
}

impl Headless {
    pub fn new(desc: &ContextDesc, width: u32, height: u32) -> Result<Self, GpuError> {
        let ctx = Context::new(desc)?;
        Self::with_context(ctx, width, height)
    }

    pub fn with_context(ctx: Arc<Context>, width: u32, height: u32) -> Result<Self, GpuError> {
        let pool = CommandPool::new(&ctx, "headless commands")?;
        let renderer = Renderer::new(&ctx, OFFSCREEN_FORMAT, DEPTH_FORMAT)?;
        let target = OffscreenTarget::new(&ctx, width, height)?;
        let queries = QueryPools::new(&ctx, 1)?;
        Ok(Self {
            ctx,
            pool,
            renderer,
            target,
            queries,
            wireframe: false,
            view_normals: false,
        })
    }

    /// Upload a mesh with patterns up to `max_level`.
    pub fn scene(&self, mesh: Mesh, max_level: u32) -> Result<Scene, RenderError> {
        Scene::new(&self.ctx, &self.pool, &self.renderer, mesh, max_level)
    }

    fn frame_uniforms(&self, camera: &Camera, cfg: &DrawConfig) -> FrameUniforms {
        let e = self.target.extent();
        let mut f = FrameUniforms::new(camera, e.width as f32 / e.height as f32, &cfg.params);
        f.options[0] = self.view_normals as u32 as f32;
        f
    }

    fn view(&self) -> TargetView {
        TargetView {
            color: self.target.color.raw,
            color_view: self.target.color.view,
            depth: self.target.depth.raw,
            depth_view: self.target.depth.view,
            extent: self.target.extent(),
            final_layout: vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
        }
    }

    /// Draw one frame, wait, and return its timing and statistics.
    pub fn draw(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        camera: &Camera,
    ) -> Result<FrameTiming, RenderError> {
        self.draw_inner(scene, cfg, camera, Capture::None, None)
    }

    fn draw_inner(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        camera: &Camera,
        capture: Capture,
        xfb: Option<&Buffer>,
    ) -> Result<FrameTiming, RenderError> {
        scene.prepare(
            &self.ctx,
            &self.pool,
            &mut self.renderer,
            cfg,
            capture,
            self.wireframe,
        )?;
        let uniforms = self.frame_uniforms(camera, cfg);
        self.renderer.set_frame(&uniforms);
        let view = self.view();
        let work = FrameWork {
            mesh: &scene.gpu,
            records: &scene.data.records,
            static_vbo: scene.static_vbo.as_ref(),
            cfg: *cfg,
            capture,
            xfb,
            wireframe: self.wireframe,
            clear: CLEAR_COLOR,
        };
        let start = Instant::now();
        self.pool.submit_and_wait(|cmd| {
            cmd_render(
                cmd,
                &self.renderer,
                &view,
                &work,
                Some((&self.queries, 0)),
                None,
            )
        })?;
        let wall_ms = start.elapsed().as_secs_f64() * 1e3;
        Ok(FrameTiming {
            gpu_ms: self.queries.gpu_ms(0)?,
            wall_ms,
            stats: self.queries.statistics(0)?,
        })
    }

    /// Render to an image.
    pub fn render(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        camera: &Camera,
    ) -> Result<Readback, RenderError> {
        self.draw(scene, cfg, camera)?;
        Ok(self.target.read(&self.pool)?)
    }

    /// Draw with the capture variant of `cfg`'s pipeline and read back every evaluated vertex.
    pub fn capture(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        camera: &Camera,
    ) -> Result<CaptureResult, RenderError> {
        let pv = vertex_count(cfg.level);
        if cfg.driver.capture_per_element(cfg.level).is_none() {
            return Err(RenderError::Unsupported(
                "the static driver evaluates on the CPU: there is nothing to capture (use pattern or tess)",
            ));
        }
        // Vertices and bytes to capture at a level.
        let size = |level: u32| {
            let per = cfg.driver.capture_per_element(level).unwrap_or(0);
            let capacity = scene.gpu.element_count as u64 * per as u64;
            (
                capacity,
                capacity * std::mem::size_of::<CapturedVertex>() as u64,
            )
        };
        let limit = self.ctx.info.limits.max_storage_buffer_range as u64;
        let fits = |level: u32| {
            let (capacity, bytes) = size(level);
            bytes <= limit && capacity <= u32::MAX as u64
        };
        let (capacity, bytes) = size(cfg.level);
        if !fits(cfg.level) {
            let remedy = match (1..cfg.level).rev().find(|&l| fits(l)) {
                Some(l) => format!("use --level {l} or lower, or a mesh with fewer triangles"),
                None => "use a mesh with fewer triangles".to_string(),
            };
            return Err(RenderError::OverLimit {
                what: format!("capturing {capacity} evaluated vertices"),
                needed: bytes,
                limit: "maxStorageBufferRange",
                max: limit,
                remedy,
            });
        }
        let vertices = Buffer::new(
            &self.ctx,
            BufferDesc::new_readback(bytes, vk::BufferUsageFlags::STORAGE_BUFFER),
            "capture output",
        )?;
        let mut counter = Buffer::new(
            &self.ctx,
            BufferDesc::new_upload(8, vk::BufferUsageFlags::STORAGE_BUFFER),
            "capture counter",
        )?;
        counter.write_pod(0, &[0u32, capacity as u32]);
        // Unwritten entries keep w = 0, so a missed vertex is detectable.
        self.pool
            .submit_and_wait(|cmd| cmd.fill_buffer(&vertices, 0))?;
        self.renderer.set_capture_target(&vertices, &counter);
        let wire = std::mem::replace(&mut self.wireframe, false);
        let timing = self.draw_inner(scene, cfg, camera, Capture::Vertices, None);
        self.wireframe = wire;
        let timing = timing?;
        let mut out: Vec<CapturedVertex> = vertices.read_pod();
        if cfg.driver == Driver::Tess {
            let written = counter.read_pod::<u32>()[0] as u64;
            if written > capacity {
                return Err(RenderError::CaptureOverflow { written, capacity });
            }
            out.truncate(written as usize);
        }
        Ok(CaptureResult {
            vertices: out,
            pattern_vertex_count: pv,
            stats: timing.stats,
        })
    }

    /// Draw `cfg` (tess) with its transform-feedback variant and read back the triangles the
    /// tessellator made, as evaluated: `(position, normal)` per corner, in primitive order.
    pub fn capture_triangles(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        camera: &Camera,
    ) -> Result<Vec<[XfbVertex; 3]>, RenderError> {
        let triangles = scene.gpu.element_count as u64 * tess_triangle_count(cfg.level) as u64;
        let bytes = triangles * 3 * std::mem::size_of::<XfbVertex>() as u64;
        let limit = self.ctx.info.max_transform_feedback_buffer_size;
        if self.ctx.info.transform_feedback && bytes > limit {
            return Err(RenderError::OverLimit {
                what: format!("reading back {triangles} tessellated triangles"),
                needed: bytes,
                limit: "maxTransformFeedbackBufferSize",
                max: limit,
                remedy: "use a lower level".into(),
            });
        }
        let buffer = Buffer::new(
            &self.ctx,
            BufferDesc::new_readback(bytes, vk::BufferUsageFlags::TRANSFORM_FEEDBACK_BUFFER_EXT),
            "transform feedback output",
        )?;
        let wire = std::mem::replace(&mut self.wireframe, false);
        let timing = self.draw_inner(scene, cfg, camera, Capture::Triangles, Some(&buffer));
        self.wireframe = wire;
        timing?;
        let flat: Vec<XfbVertex> = buffer.read_pod();
        Ok(flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
    }
}
