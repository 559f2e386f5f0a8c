//! Headless rendering into an offscreen target: images, capture of evaluated vertices, timings.
//! Every call records, submits and waits, so nothing is ever in flight when it returns.

use super::frame::{cmd_render, FrameWork, TargetView};
use super::{CapturedVertex, DrawConfig, FrameUniforms, Renderer, Scene};
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
}

/// Vertices the capture variant wrote: `pattern_vertex_count` per coarse triangle, in pattern
/// order, triangle after triangle.
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
        })
    }

    /// Upload a mesh with patterns up to `max_level`.
    pub fn scene(&self, mesh: Mesh, max_level: u32) -> Result<Scene, GpuError> {
        Scene::new(&self.ctx, &self.pool, &self.renderer, mesh, max_level)
    }

    fn frame_uniforms(&self, camera: &Camera) -> FrameUniforms {
        let e = self.target.extent();
        let eye = camera.eye();
        FrameUniforms {
            view_proj: camera
                .view_proj(e.width as f32 / e.height as f32)
                .to_cols_array_2d(),
            eye: eye.extend(1.0).to_array(),
            light_dir: (eye - camera.target + glam::Vec3::new(0.3, 0.8, 0.2) * camera.distance)
                .normalize()
                .extend(0.0)
                .to_array(),
            base_color: [0.80, 0.55, 0.35, 1.0],
            options: [if self.wireframe { 1.0 } else { 0.0 }, 1.2, 0.0, 0.0],
        }
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
    ) -> Result<FrameTiming, GpuError> {
        self.draw_inner(scene, cfg, camera, false)
    }

    fn draw_inner(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        camera: &Camera,
        capture: bool,
    ) -> Result<FrameTiming, GpuError> {
        scene.prepare(&self.ctx, &self.pool, &mut self.renderer, cfg, capture)?;
        let uniforms = self.frame_uniforms(camera);
        self.renderer.set_frame(&uniforms);
        let view = self.view();
        let work = FrameWork {
            mesh: &scene.gpu,
            records: &scene.data.records,
            static_vbo: scene.static_vbo.as_ref(),
            cfg: *cfg,
            capture,
            clear: [0.08, 0.09, 0.11, 1.0],
        };
        let start = Instant::now();
        self.pool.submit_and_wait(|cmd| {
            cmd_render(cmd, &self.renderer, &view, &work, Some((&self.queries, 0)))
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
    ) -> Result<Readback, GpuError> {
        self.draw(scene, cfg, camera)?;
        self.target.read(&self.pool)
    }

    /// Draw with the capture variant of `cfg`'s pipeline and read back every evaluated vertex.
    pub fn capture(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        camera: &Camera,
    ) -> Result<CaptureResult, GpuError> {
        let pv = vertex_count(cfg.level);
        let count = scene.gpu.triangle_count as u64 * pv as u64;
        let bytes = count * std::mem::size_of::<CapturedVertex>() as u64;
        let limit = self.ctx.info.limits.max_storage_buffer_range as u64;
        if bytes > limit {
            return Err(GpuError::Other(format!(
                "capturing {count} vertices needs {bytes} bytes, over this device's maxStorageBufferRange ({limit}): use a lower level"
            )));
        }
        let buffer = Buffer::new(
            &self.ctx,
            BufferDesc::new_readback(bytes, vk::BufferUsageFlags::STORAGE_BUFFER),
            "capture output",
        )?;
        // Unwritten entries keep w = 0, so a missed vertex is detectable.
        self.pool
            .submit_and_wait(|cmd| cmd.fill_buffer(&buffer, 0))?;
        self.renderer.set_capture_target(&buffer);
        let timing = self.draw_inner(scene, cfg, camera, true)?;
        Ok(CaptureResult {
            vertices: buffer.read_pod(),
            pattern_vertex_count: pv,
            stats: timing.stats,
        })
    }
}
