//! The window demo's overlay panel on the GPU: egui's triangles recorded by `egui-ash-renderer`
//! (0.8, dynamic rendering) into the frame's own rendering instance, after the mesh, the way
//! Sascha Willems' samples draw their UI overlay inside the scene's render pass.
//!
//! The renderer's API is safe Rust but hands our handles to the driver, so it lives here, behind
//! these invariants:
//! - its pipeline is built for the frame's attachments: the swapchain's colour format and
//!   [`DEPTH_FORMAT`](super::DEPTH_FORMAT) (depth test off; the panel is drawn last, on top);
//! - its buffers and textures come from the context's gpu-allocator, so the context's leak check
//!   covers them; it holds an `Arc<Context>`, so it is dropped before the device;
//! - one frame in flight: [`Overlay::update_textures`] and [`Overlay::cmd_draw`] rewrite what
//!   the last frame read (textures, the one vertex/index buffer pair), so both are called only
//!   after that frame's fence; uploads are submitted on the context's queue from the
//!   overlay's own command pool and waited for (queue idle) before recording;
//! - textures egui releases are freed one `update_textures` later, i.e. after the fence of the
//!   frame that last drew with them.

use super::{track_drop, track_new, vk, Cmd, CommandPool, Context, GpuError};
use egui::{ClippedPrimitive, TextureId, TexturesDelta};
use egui_ash_renderer::{DynamicRendering, Options, Renderer};
use std::sync::Arc;

/// Field order is drop order: the renderer (its objects and allocations) first.
pub struct Overlay {
    renderer: Renderer,
    /// Textures the last egui output released; the frame that drew it may still read them.
    released: Vec<TextureId>,
    uploads: CommandPool,
    ctx: Arc<Context>,
}

impl Overlay {
    /// An overlay drawing into `color_format` with a `depth_format` attachment bound (`None`:
    /// drawn in a rendering instance of its own, without depth, over a resolved image).
    pub fn new(
        ctx: &Arc<Context>,
        color_format: vk::Format,
        depth_format: Option<vk::Format>,
    ) -> Result<Self, GpuError> {
        let srgb = matches!(
            color_format,
            vk::Format::B8G8R8A8_SRGB | vk::Format::R8G8B8A8_SRGB
        );
        let renderer = Renderer::with_gpu_allocator(
            ctx.shared_allocator(),
            ctx.device.clone(),
            DynamicRendering {
                color_attachment_format: color_format,
                depth_attachment_format: depth_format,
            },
            Options {
                in_flight_frames: 1,
                enable_depth_test: false,
                enable_depth_write: false,
                srgb_framebuffer: srgb,
            },
        )?;
        let uploads = CommandPool::new(ctx, "overlay texture uploads")?;
        track_new();
        Ok(Self {
            renderer,
            released: Vec::new(),
            uploads,
            ctx: ctx.clone(),
        })
    }

    /// Free the textures the previous output released, then upload this output's new and
    /// changed textures (submitted and waited for). Only after the last frame's fence.
    pub fn update_textures(&mut self, delta: &TexturesDelta) -> Result<(), GpuError> {
        self.renderer.free_textures(&self.released)?;
        self.released.clone_from(&delta.free);
        self.renderer
            .set_textures(self.ctx.queue, self.uploads.raw, &delta.set)?;
        Ok(())
    }

    /// Record egui's triangles. Inside the frame's rendering instance, last: it leaves its own
    /// pipeline, viewport and scissor bound. Only after the last frame's fence.
    pub fn cmd_draw(
        &mut self,
        cmd: &Cmd<'_>,
        extent: vk::Extent2D,
        pixels_per_point: f32,
        primitives: &[ClippedPrimitive],
    ) -> Result<(), GpuError> {
        self.renderer
            .cmd_draw(cmd.raw, extent, pixels_per_point, primitives)?;
        Ok(())
    }
}

impl Drop for Overlay {
    fn drop(&mut self) {
        track_drop();
    }
}
