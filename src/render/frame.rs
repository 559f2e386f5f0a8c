//! Recording one frame: layout transitions, queries, dynamic rendering, the chosen driver.
//! Shared by headless rendering, capture, benchmarks and the window; the window adds its overlay
//! panel through a hook recorded last in the same rendering instance.

use super::bindings::{SET_CAPTURE, SET_FRAME};
use super::static_vbo::StaticVbo;
use super::{Capture, DrawConfig, GpuMesh, Renderer, Scene};
use crate::gpu::{vk, Buffer, Cmd, QueryPools};
use crate::surface::ElementRecord;

/// Background colour (linear; the targets are sRGB).
pub const CLEAR_COLOR: [f32; 4] = [0.012, 0.014, 0.02, 1.0];

/// The light background (linear): a pale grey on which dark cracks and silhouettes show.
pub const LIGHT_CLEAR_COLOR: [f32; 4] = [0.62, 0.65, 0.70, 1.0];

/// The background an image is drawn on (`--background dark|light`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Background {
    /// Near black, the default.
    #[default]
    Dark,
    /// Pale grey: cracks (background showing through the surface) are dark spots on it.
    Light,
}

impl Background {
    pub const ALL: [Background; 2] = [Background::Dark, Background::Light];

    pub fn name(self) -> &'static str {
        match self {
            Background::Dark => "dark",
            Background::Light => "light",
        }
    }

    /// Its linear colour, the targets' clear value.
    pub fn color(self) -> [f32; 4] {
        match self {
            Background::Dark => CLEAR_COLOR,
            Background::Light => LIGHT_CLEAR_COLOR,
        }
    }
}

/// Where a frame is drawn. With multisampling, `color` is the multisampled attachment and
/// `resolve` the single-sampled image it is averaged into (what is read back or presented).
#[derive(Clone, Copy, Debug)]
pub struct TargetView {
    pub color: vk::Image,
    pub color_view: vk::ImageView,
    pub resolve: Option<(vk::Image, vk::ImageView)>,
    pub depth: vk::Image,
    pub depth_view: vk::ImageView,
    pub extent: vk::Extent2D,
    /// Layout the colour image (the resolve image, with multisampling) is left in
    /// (TRANSFER_SRC_OPTIMAL or PRESENT_SRC_KHR).
    pub final_layout: vk::ImageLayout,
}

/// What one frame draws.
pub struct FrameWork<'a> {
    pub mesh: &'a GpuMesh,
    pub records: &'a [ElementRecord],
    pub static_vbo: Option<&'a StaticVbo>,
    /// Passes to run before drawing (the `loop` surface's M0 -> M1), inside the timed range.
    pub pre_pass: Option<&'a super::loop_gpu::LoopPass>,
    /// The level pass and its camera, run after `pre_pass` to write the mesh's levels for an
    /// adaptive frame (src/render/level_pass.rs); `None` keeps the levels as they are.
    pub level_pass: Option<(&'a super::LevelPass, crate::lod::frame::LodView)>,
    /// Time the level pass alone in this slot ([`QueryPools::cmd_begin_time`]: the window's
    /// panel shows it), inside the frame's own span.
    pub level_pass_timer: Option<(&'a QueryPools, u32)>,
    pub cfg: DrawConfig,
    pub capture: Capture,
    /// Transform-feedback output (with `Capture::Triangles`).
    pub xfb: Option<&'a Buffer>,
    /// Receives the bytes transform feedback wrote (a `u32`), with `xfb`.
    pub xfb_counter: Option<&'a Buffer>,
    /// Draw the refined triangles' edges in a second pass (if the device supports it).
    pub wireframe: bool,
    /// Cull the wireframe's lines of faces turned away from the eye: set where only front
    /// faces can be seen ([`Scene::front_only`](super::Scene::front_only)).
    pub wire_front_only: bool,
    /// Draw each element at its own levels from the mesh's levels buffer
    /// ([`GpuMesh::levels`], src/lod/levels.rs), `cfg.level` being the largest; otherwise every
    /// element at `cfg.level`.
    pub adaptive: bool,
    /// Draw the static driver's adaptive mesh element by element, each draw naming its element,
    /// where its vertices carry none (they do where the normal field is evaluated per
    /// fragment): the `levels` view colours each element by its level. Other drivers name their
    /// elements anyway.
    pub element_draws: bool,
    /// Draw the coarse mesh's edges over the surface (the cage overlay, src/render/cage.rs).
    pub cage: Option<&'a super::cage::Cage>,
    /// The elements to draw (all of them for an image; capture passes draw a part).
    pub elements: std::ops::Range<u32>,
    pub clear: [f32; 4],
}

impl<'a> FrameWork<'a> {
    /// Every element of `scene` drawn as `cfg` says, with the passes it needs first, no capture,
    /// no wireframe, on the default background: the one way every frame (headless, window,
    /// benchmark) is described; callers change the fields that differ.
    pub fn new(scene: &'a Scene, cfg: DrawConfig) -> Self {
        let mesh = scene.elements(cfg.surface);
        Self {
            mesh,
            records: scene.records(cfg.surface),
            static_vbo: scene.static_vbo.as_ref(),
            pre_pass: scene.pre_pass(&cfg),
            level_pass: None,
            level_pass_timer: None,
            cfg,
            capture: Capture::None,
            xfb: None,
            xfb_counter: None,
            wireframe: false,
            wire_front_only: false,
            adaptive: false,
            element_draws: false,
            cage: None,
            elements: 0..mesh.element_count,
            clear: CLEAR_COLOR,
        }
    }
}

/// Record the frame. Pipelines must be prepared and levels checked (`Scene::prepare`).
/// `overlay` records on top of the mesh, right before the rendering instance ends (inside the
/// timed range), or with multisampling in a second, single-sampled instance on the resolved
/// image without depth; it may leave its own pipeline and dynamic state bound.
pub fn cmd_render(
    cmd: &Cmd<'_>,
    r: &Renderer,
    target: &TargetView,
    work: &FrameWork<'_>,
    queries: Option<(&QueryPools, u32)>,
    overlay: Option<&mut dyn FnMut(&Cmd<'_>)>,
) {
    use vk::ImageLayout as L;
    cmd.transition(
        target.color,
        vk::ImageAspectFlags::COLOR,
        L::UNDEFINED,
        L::COLOR_ATTACHMENT_OPTIMAL,
    );
    cmd.transition(
        target.depth,
        vk::ImageAspectFlags::DEPTH,
        L::UNDEFINED,
        L::DEPTH_ATTACHMENT_OPTIMAL,
    );
    if let Some((resolve, _)) = target.resolve {
        cmd.transition(
            resolve,
            vk::ImageAspectFlags::COLOR,
            L::UNDEFINED,
            L::COLOR_ATTACHMENT_OPTIMAL,
        );
    }
    if let Some((q, slot)) = queries {
        q.cmd_begin(cmd, slot);
    }
    if let Some(pass) = work.pre_pass {
        pass.cmd_apply(cmd);
    }
    // The levels first (the level pass), then what the driver builds from them (the pattern
    // driver's bins).
    if let Some((pass, view)) = &work.level_pass {
        if let Some((q, slot)) = work.level_pass_timer {
            q.cmd_begin_time(cmd, slot);
        }
        pass.cmd_record(cmd, work.mesh, view);
        if let Some((q, slot)) = work.level_pass_timer {
            q.cmd_end_time(cmd, slot);
        }
    }
    work.cfg.driver.kind().cmd_before_rendering(cmd, r, work);
    cmd.begin_rendering_resolved(
        target.color_view,
        target.resolve.map(|(_, view)| view),
        target.depth_view,
        target.extent,
        work.clear,
    );
    cmd.bind_descriptor_set(r.layout.raw, SET_FRAME, r.frame_set, &[]);
    if work.capture == Capture::Vertices {
        cmd.bind_descriptor_set(r.layout.raw, SET_CAPTURE, r.capture_set, &[]);
    }
    cmd.bind_graphics_pipeline(r.pipeline(&work.cfg, work.capture, false, work.adaptive));
    if let Some(xfb) = work.xfb.filter(|_| work.capture == Capture::Triangles) {
        cmd.begin_transform_feedback(xfb);
        cmd_draw_driver(cmd, r, work);
        cmd.end_transform_feedback(work.xfb_counter);
    } else {
        cmd_draw_driver(cmd, r, work);
    }
    if work.wireframe && r.wireframe_supported() {
        cmd.bind_graphics_pipeline(r.pipeline(&work.cfg, Capture::None, true, work.adaptive));
        cmd.set_cull_mode(if work.wire_front_only {
            vk::CullModeFlags::BACK
        } else {
            vk::CullModeFlags::NONE
        });
        cmd_draw_driver(cmd, r, work);
    }
    if let Some(cage) = work.cage {
        cage.cmd_draw(cmd, r);
    }
    match (overlay, target.resolve) {
        (Some(overlay), None) => {
            overlay(cmd);
            cmd.end_rendering();
        }
        (Some(overlay), Some((_, view))) => {
            cmd.end_rendering();
            cmd.begin_rendering_over(view, target.extent);
            overlay(cmd);
            cmd.end_rendering();
        }
        (None, _) => cmd.end_rendering(),
    }
    if let Some((q, slot)) = queries {
        q.cmd_end(cmd, slot);
    }
    if work.capture != Capture::None {
        cmd.barrier_to_host();
    }
    cmd.transition(
        target.resolve.map_or(target.color, |(image, _)| image),
        vk::ImageAspectFlags::COLOR,
        L::COLOR_ATTACHMENT_OPTIMAL,
        target.final_layout,
    );
}

/// The chosen driver's draws (pipeline and descriptor sets already bound).
fn cmd_draw_driver(cmd: &Cmd<'_>, r: &Renderer, work: &FrameWork<'_>) {
    work.cfg.driver.kind().cmd_draw(cmd, r, work);
}
