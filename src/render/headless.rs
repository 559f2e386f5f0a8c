//! Headless rendering into an offscreen target: images, capture of evaluated vertices, timings.
//! Every call records, submits and waits, so nothing is ever in flight when it returns.

use super::frame::{cmd_render, Background, FrameWork, TargetView};
use super::xfb_capture::CapturePass;
use super::{
    Capture, CapturedVertex, DrawConfig, Driver, FrameUniforms, RenderError, Renderer, Scene, View,
};
use crate::gpu::{
    vk, Buffer, CommandPool, Context, ContextDesc, GpuError, OffscreenTarget, PipelineStats,
    QueryPools, Readback, DEPTH_FORMAT, OFFSCREEN_FORMAT,
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
    /// Draw the cage overlay (the coarse mesh's edges) over the surface.
    pub cage: bool,
    /// What the image is drawn on.
    pub background: Background,
    /// Draw each element at its own levels from its mesh's levels buffer
    /// ([`super::GpuMesh::upload_levels`]), the configuration's level being the largest
    /// (`FrameWork::adaptive`; the pattern driver at a power of two).
    pub adaptive: bool,
    /// What the fragment stage shows.
    pub view: View,
    /// Largest capture buffer of one pass, in bytes (None: the device's limit; tests set a small
    /// one to exercise captures made in several passes).
    pub max_capture_bytes: Option<u64>,
    /// Hears each capture pass as it ends (a progress report for long captures).
    pub capture_progress: Option<Box<dyn FnMut(CapturePass) + Send>>,
    /// Within a capture after its first pass: the pre-pass (Loop's step) and the level pass
    /// have written what they write for the whole mesh, so the passes after it draw from that
    /// (each would otherwise run both over every element: time growing with the square of
    /// the mesh where the passes are many).
    pub(super) passes_reuse: bool,
}

/// Vertices the capture variant of a driver's pipeline wrote.
/// - `pattern`: exactly `pattern_vertex_count` per coarse triangle, in pattern order, triangle
///   after triangle (`id = (triangle, pattern vertex)`).
/// - `pattern` drawing adaptively: packed, each element's vertices at its drawn inner level
///   `inner_levels[t]` only (`vertex_count` of it, none when culled), in that level's own pattern
///   order, element after element ([`CaptureResult::adaptive_elements`]); `id = (element, the
///   pattern's vertex: the hierarchy's, in its order, or the integer patterns', inner level, 1)`.
/// - `tess`: every evaluation-stage invocation, in no particular order (`id.y = u32::MAX`,
///   `coord` = gl_TessCoord); an implementation may evaluate a vertex more than once.
pub struct CaptureResult {
    pub vertices: Vec<CapturedVertex>,
    /// The (finest) pattern's vertex count.
    pub pattern_vertex_count: u32,
    /// The adaptive pattern driver's: each element's drawn inner level, 0 where culled.
    pub inner_levels: Option<Vec<u32>>,
    pub stats: Option<PipelineStats>,
}

impl CaptureResult {
    /// An adaptive pattern capture's elements in order: each one's drawn inner level (0:
    /// culled) and its vertices, that level's pattern (empty when culled); nothing for another
    /// capture.
    pub fn adaptive_elements(&self) -> impl Iterator<Item = (u32, &[CapturedVertex])> + '_ {
        let levels = self.inner_levels.as_deref().unwrap_or_default();
        let mut first = 0;
        levels.iter().map(move |&l| {
            let count = if l == 0 { 0 } else { vertex_count(l) as usize };
            let end = (first + count).min(self.vertices.len());
            let vertices = &self.vertices[first.min(end)..end];
            first = end;
            (l, vertices)
        })
    }
}

/// One pass of a capture: the elements it draws, the packed slot its buffer starts at (the
/// adaptive pattern driver's; 0 otherwise), and how many slots it fills (None: the driver
/// appends, the counter says).
pub(super) struct CapturePlan {
    pub elements: std::ops::Range<u32>,
    pub base: u32,
    pub slots: Option<u64>,
}

/// Bytes of one captured vertex.
pub(super) const VERTEX_BYTES: u64 = std::mem::size_of::<CapturedVertex>() as u64;

/// Timings and counters of one frame.
#[derive(Clone, Copy, Debug)]
pub struct FrameTiming {
    pub gpu_ms: f64,
    pub wall_ms: f64,
    pub stats: Option<PipelineStats>,
}

/// The largest buffer one capture pass may use, and the name of the limit that sets it: the
/// binding's own range limit, maxMemoryAllocationSize (one buffer is one allocation), and a
/// smaller cap where given ([`Headless::max_capture_bytes`], lavapipe's pass size), with its
/// name.
pub(super) fn pass_limit(
    range: (u64, &'static str),
    allocation: u64,
    cap: Option<(u64, &'static str)>,
) -> (u64, &'static str) {
    let mut limit = range;
    if allocation < limit.0 {
        limit = (allocation, "this device's maxMemoryAllocationSize");
    }
    match cap {
        Some(c) if c.0 < limit.0 => c,
        _ => limit,
    }
}

/// The name of [`Headless::max_capture_bytes`] in over-limit sentences (`export` sets it from
/// this variable).
pub const CAPTURE_CAP_NAME: &str = "the capture cap MESHREFINE_MAX_CAPTURE_BYTES";

/// The clear colour as the sRGB offscreen target stores it (8 bits per channel).
pub fn clear_color_srgb8() -> [u8; 4] {
    background_srgb8(Background::Dark)
}

/// `background`'s colour as the sRGB target stores it.
pub fn background_srgb8(background: Background) -> [u8; 4] {
    let encode = |c: f32| {
        let s = if c <= 0.003_130_8 {
            12.92 * c
        } else {
            1.055 * c.powf(1.0 / 2.4) - 0.055
        };
        (s.clamp(0.0, 1.0) * 255.0).round() as u8
    };
    let [r, g, b, a] = background.color();
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
    covered_pixels_on(image, Background::Dark)
}

/// Pixels of `image` that differ from `background` by more than 1/255 in some channel.
pub fn covered_pixels_on(image: &Readback, background: Background) -> usize {
    let clear = background_srgb8(background);
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
        Self::multisampled(ctx, width, height, vk::SampleCountFlags::TYPE_1)
    }

    /// Rendering with `samples` per pixel (`gpu::sample_count` checks a request), resolved into
    /// the image that is read back.
    pub fn multisampled(
        ctx: Arc<Context>,
        width: u32,
        height: u32,
        samples: vk::SampleCountFlags,
    ) -> Result<Self, GpuError> {
        let pool = CommandPool::new(&ctx, "headless commands")?;
        let renderer = Renderer::multisampled(&ctx, OFFSCREEN_FORMAT, DEPTH_FORMAT, samples)?;
        let target = OffscreenTarget::multisampled(&ctx, width, height, samples)?;
        let queries = QueryPools::new(&ctx, 1)?;
        Ok(Self {
            ctx,
            pool,
            renderer,
            target,
            queries,
            wireframe: false,
            cage: false,
            background: Background::Dark,
            adaptive: false,
            view: View::Shaded,
            max_capture_bytes: None,
            capture_progress: None,
            passes_reuse: false,
        })
    }

    /// Upload a mesh with patterns up to `max_level`.
    pub fn scene(&self, mesh: Mesh, max_level: u32) -> Result<Scene, RenderError> {
        Scene::new(&self.ctx, &self.pool, &self.renderer, mesh, max_level)
    }

    /// Give `scene` the height map `map`.
    pub fn set_heightmap(
        &self,
        scene: &mut Scene,
        map: crate::surface::Heightmap,
    ) -> Result<(), RenderError> {
        scene.set_heightmap(&self.ctx, &self.pool, &self.renderer, map)
    }

    fn frame_uniforms(&self, camera: &Camera, cfg: &DrawConfig, scene: &Scene) -> FrameUniforms {
        let e = self.target.extent();
        let u = FrameUniforms::new(camera, e.width as f32 / e.height as f32, cfg, scene);
        // Adaptive frames: each element's own level (the levels view reads it).
        if self.adaptive {
            u.adaptive()
        } else {
            u
        }
    }

    fn view(&self) -> TargetView {
        let t = &self.target;
        let (color, resolve) = match &t.msaa {
            Some(msaa) => (msaa, Some((t.color.raw, t.color.view))),
            None => (&t.color, None),
        };
        TargetView {
            color: color.raw,
            color_view: color.view,
            resolve,
            depth: self.target.depth.raw,
            depth_view: self.target.depth.view,
            extent: self.target.extent(),
            final_layout: vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
        }
    }

    /// Prepare `scene` for `cfg` and say how many elements it draws.
    pub fn prepared_elements(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        capture: Capture,
    ) -> Result<u32, RenderError> {
        scene.adaptive_frames = self.adaptive;
        self.renderer.set_view(self.view);
        scene.prepare(
            &self.ctx,
            &self.pool,
            &mut self.renderer,
            cfg,
            capture,
            self.wireframe,
        )?;
        Ok(scene.elements(cfg.surface).element_count)
    }

    /// Draw the elements in `elements` only (none: the frame's other work alone, e.g. the loop
    /// surface's passes), wait, and return its timing and statistics.
    pub fn draw_elements(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        camera: &Camera,
        elements: std::ops::Range<u32>,
    ) -> Result<FrameTiming, RenderError> {
        self.draw_inner(scene, cfg, camera, Capture::None, None, elements)
    }

    /// GPU milliseconds of the passes `cfg`'s surface runs before drawing (the loop surface's
    /// M0 -> M1 and normals), alone in a submission; None for a surface without any.
    pub fn time_pre_pass(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
    ) -> Result<Option<f64>, RenderError> {
        self.prepared_elements(scene, cfg, Capture::None)?;
        let gpu = DrawConfig {
            driver: Driver::default(),
            ..*cfg
        };
        let Some(pass) = scene.pre_pass(&gpu) else {
            return Ok(None);
        };
        let queries = &self.queries;
        self.pool.submit_and_wait(|cmd| {
            queries.cmd_begin(cmd, 0);
            pass.cmd_apply(cmd);
            queries.cmd_end(cmd, 0);
        })?;
        Ok(Some(self.queries.gpu_ms(0)?))
    }

    /// GPU milliseconds of the level pass alone (its submission, timestamps around it) as the
    /// last [`Scene::set_levels`] for `cfg` set it up; None when no pass is set up for `cfg`
    /// (the levels were uploaded from the CPU instead).
    pub fn time_level_pass(
        &mut self,
        scene: &Scene,
        cfg: &DrawConfig,
    ) -> Result<Option<f64>, RenderError> {
        let Some((pass, view)) = scene.level_pass(cfg) else {
            return Ok(None);
        };
        let mesh = scene.elements(cfg.surface);
        let queries = &self.queries;
        self.pool.submit_and_wait(|cmd| {
            queries.cmd_begin(cmd, 0);
            pass.cmd_record(cmd, mesh, &view);
            queries.cmd_end(cmd, 0);
        })?;
        Ok(Some(self.queries.gpu_ms(0)?))
    }

    /// Draw one frame, wait, and return its timing and statistics.
    pub fn draw(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        camera: &Camera,
    ) -> Result<FrameTiming, RenderError> {
        self.draw_inner(scene, cfg, camera, Capture::None, None, 0..u32::MAX)
    }

    pub(super) fn draw_inner(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        camera: &Camera,
        capture: Capture,
        xfb: Option<(&Buffer, &Buffer)>,
        elements: std::ops::Range<u32>,
    ) -> Result<FrameTiming, RenderError> {
        // The element count is the surface's (M1 faces for loop, known once prepared).
        let count = self.prepared_elements(scene, cfg, capture)?;
        let cage = self.cage && capture == Capture::None;
        if cage {
            scene.prepare_cage(&self.ctx, &mut self.renderer)?;
        }
        if self.adaptive {
            cfg.driver.kind().check_adaptive(&self.ctx, scene, cfg)?;
        }
        let elements = elements.start..elements.end.min(count);
        let uniforms = self.frame_uniforms(camera, cfg, scene);
        self.renderer.set_frame(&uniforms);
        let view = self.view();
        let wire_front_only = self.wireframe && scene.front_only(cfg, camera.eye())?;
        let work = FrameWork {
            capture,
            wire_front_only,
            xfb: xfb.map(|x| x.0),
            xfb_counter: xfb.map(|x| x.1),
            wireframe: self.wireframe,
            adaptive: self.adaptive,
            element_draws: self.view == View::Levels,
            cage: scene.cage.as_ref().filter(|_| cage),
            clear: self.background.color(),
            level_pass: (scene.level_pass(cfg)).filter(|_| self.adaptive && !self.passes_reuse),
            elements,
            ..FrameWork::new(scene, *cfg)
        };
        let work = FrameWork {
            pre_pass: work.pre_pass.filter(|_| !self.passes_reuse),
            ..work
        };
        // Said for tests of the capture passes (RUST_LOG): each runs once, in the first pass.
        if work.level_pass.is_some() {
            log::debug!("this frame records the level pass");
        }
        if work.pre_pass.is_some() {
            log::debug!("this frame records Loop's pre-pass");
        }
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

    /// The refined mesh `cfg`'s driver draws, read back from its real drawing pipeline and
    /// welded on exact bits (what `meshrefine export` writes): the evaluated vertices joined by
    /// the pattern's triangles (drawing adaptively, each element's at its inner level), or the
    /// tessellator's triangles by transform feedback.
    pub fn refined_mesh(
        &mut self,
        scene: &mut Scene,
        cfg: &DrawConfig,
        camera: &Camera,
    ) -> Result<crate::export::RefinedMesh, RenderError> {
        match cfg.driver.kind().export_capture() {
            Some(Capture::Triangles) => {
                let mut welder = crate::export::TriangleWelder::default();
                self.capture_triangles_each(scene, cfg, camera, |t| welder.add(t))?;
                Ok(welder.finish())
            }
            Some(_) => {
                let cap = self.capture(scene, cfg, camera)?;
                if cap.inner_levels.is_some() {
                    return crate::export::weld_adaptive(&cap, cfg.level)
                        .map_err(RenderError::Capture);
                }
                let pattern = scene
                    .patterns
                    .find(cfg.level)
                    .map(|i| &scene.patterns.patterns[i])
                    .ok_or(RenderError::Unsupported("no pattern of this level was made"))?;
                crate::export::weld(&cap, pattern).map_err(RenderError::Capture)
            }
            None => Err(RenderError::Unsupported(
                "the static driver evaluates on the CPU: there is nothing to capture (use pattern or tess)",
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A capture pass fits the binding's range and one allocation, whichever is smaller, and
    /// names it.
    #[test]
    fn capture_passes_fit_the_smaller_limit() {
        let range = (4u64 << 30, "maxTransformFeedbackBufferSize");
        assert_eq!(
            pass_limit(range, 2 << 30, None),
            (2 << 30, "this device's maxMemoryAllocationSize")
        );
        assert_eq!(pass_limit(range, 8 << 30, None), range);
        let cap = (1000, CAPTURE_CAP_NAME);
        assert_eq!(pass_limit(range, 2 << 30, Some(cap)), cap);
        assert_eq!(
            pass_limit(range, 2 << 30, Some((3 << 30, "a cap"))).1,
            "this device's maxMemoryAllocationSize"
        );
    }
}
