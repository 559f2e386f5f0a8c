//! Recording a frame for the swapchain image (the scene, the panel over it, the screenshot
//! copy) and saving screenshots: `--screenshot`'s last frame and the screenshot key's
//! `meshrefine-<n>.png`.
#![forbid(unsafe_code)]

use super::{ui, State};
use crate::gpu::{vk, Buffer, BufferDesc, Cmd, SwapchainFrame};
use crate::render::frame::{cmd_render, FrameWork, TargetView};
use crate::render::{DrawConfig, FrameUniforms, View};
use anyhow::{Context as _, Result};
use std::io::Write as _;

impl State {
    /// Record the frame into `self.cmd`: the scene (adaptively when `adaptive`), the panel on
    /// top, and the screenshot copy.
    pub(super) fn record(
        &mut self,
        cfg: &DrawConfig,
        image: &SwapchainFrame,
        ui_frame: &ui::UiFrame,
        screenshot: bool,
        adaptive: bool,
    ) -> Result<()> {
        let extent = self.swapchain.extent;
        if screenshot {
            self.screenshot_buffer = Some(Buffer::new(
                &self.ctx,
                BufferDesc::new_readback(
                    extent.width as u64 * extent.height as u64 * 4,
                    vk::BufferUsageFlags::empty(),
                ),
                "screenshot",
            )?);
        }
        let aspect = extent.width as f32 / extent.height as f32;
        let uniforms = FrameUniforms::new(&self.camera, aspect, cfg, &self.scene);
        // The levels view shows each element's own level when it has one.
        let uniforms = if adaptive {
            uniforms.adaptive()
        } else {
            uniforms
        };
        self.renderer.set_frame(&uniforms);
        let depth = self.swapchain.depth.as_ref().expect("depth image exists");
        let (color, color_view, resolve) = match &self.swapchain.msaa {
            Some(msaa) => (msaa.raw, msaa.view, Some((image.image, image.view))),
            None => (image.image, image.view, None),
        };
        let target = TargetView {
            color,
            color_view,
            resolve,
            depth: depth.raw,
            depth_view: depth.view,
            extent,
            final_layout: if screenshot {
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL
            } else {
                vk::ImageLayout::PRESENT_SRC_KHR
            },
        };
        let wire_front_only =
            self.controls.wireframe && self.scene.front_only(cfg, self.camera.eye())?;
        let level_pass = self.scene.level_pass(cfg).filter(|_| adaptive);
        self.level_cost.timed = level_pass.is_some();
        let work = FrameWork {
            wireframe: self.controls.wireframe,
            wire_front_only,
            adaptive,
            element_draws: self.controls.view == View::Levels,
            cage: self.scene.cage.as_ref().filter(|_| self.controls.cage),
            level_pass,
            level_pass_timer: Some((&self.queries, 1)),
            clear: self.controls.background.color(),
            ..FrameWork::new(&self.scene, *cfg)
        };
        let screenshot_buffer = self.screenshot_buffer.as_ref().filter(|_| screenshot);
        let overlay = &mut self.overlay;
        let mut overlay_recorded = Ok(());
        let mut cmd_overlay = |cmd: &Cmd<'_>| {
            overlay_recorded =
                overlay.cmd_draw(cmd, extent, ui_frame.pixels_per_point, &ui_frame.primitives);
        };
        self.pool.record(self.cmd, |cmd| {
            cmd_render(
                cmd,
                &self.renderer,
                &target,
                &work,
                Some((&self.queries, 0)),
                Some(&mut cmd_overlay),
            );
            if let Some(buf) = screenshot_buffer {
                cmd.copy_image_to_buffer(image.image, extent, buf);
                cmd.barrier_to_host();
                cmd.transition(
                    image.image,
                    vk::ImageAspectFlags::COLOR,
                    vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                    vk::ImageLayout::PRESENT_SRC_KHR,
                );
            }
        })?;
        overlay_recorded?;
        Ok(())
    }

    pub(super) fn save_screenshot(&mut self, path: &std::path::Path) -> Result<()> {
        let buf = self.screenshot_buffer.take().expect("screenshot buffer");
        let e = self.swapchain.extent;
        let mut rgba = buf.mapped()[..(e.width * e.height * 4) as usize].to_vec();
        if matches!(
            self.swapchain.format,
            vk::Format::B8G8R8A8_SRGB | vk::Format::B8G8R8A8_UNORM
        ) {
            for px in rgba.chunks_exact_mut(4) {
                px.swap(0, 2);
            }
        }
        for px in rgba.chunks_exact_mut(4) {
            px[3] = 255;
        }
        crate::gpu::Readback {
            width: e.width,
            height: e.height,
            rgba,
        }
        .save_png(path)
        .with_context(|| format!("cannot write '{}'", path.display()))
    }
}

impl State {
    /// Save the frame just drawn (its copy is complete) to `path` and say where on stdout. A
    /// frame of the screenshot key (`key`) is also said in the panel, and a file it cannot
    /// write only there and in the log: the demo goes on. `--screenshot`'s ends it.
    pub(super) fn saved_screenshot(&mut self, path: &std::path::Path, key: bool) -> Result<()> {
        match self.save_screenshot(path) {
            Ok(()) if key => {
                let shown = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
                let note = format!("saved {}", shown.display());
                let _ = writeln!(std::io::stdout().lock(), "{note}");
                self.screenshot_note = Some(note);
            }
            Ok(()) => {
                let _ = writeln!(std::io::stdout().lock(), "saved {}", path.display());
            }
            Err(e) if key => {
                log::warn!("{e:#}");
                self.screenshot_note = Some(format!("{e:#}"));
            }
            Err(e) => return Err(e),
        }
        Ok(())
    }
}

/// The screenshot key's file: `meshrefine-<n>.png` in `dir` (None: the current directory) with
/// the smallest n from 1 that names no file yet, so that no earlier screenshot is overwritten.
pub(super) fn next_screenshot(dir: Option<&std::path::Path>) -> std::path::PathBuf {
    let dir = dir.unwrap_or(std::path::Path::new("."));
    (1u64..)
        .map(|n| dir.join(format!("meshrefine-{n}.png")))
        .find(|p| !p.exists())
        .expect("some number names no file")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn screenshots_are_numbered_without_overwriting() {
        let dir = std::env::temp_dir().join(format!("meshrefine-shots-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        assert_eq!(next_screenshot(Some(&dir)), dir.join("meshrefine-1.png"));
        std::fs::write(dir.join("meshrefine-1.png"), b"").unwrap();
        std::fs::write(dir.join("meshrefine-3.png"), b"").unwrap();
        assert_eq!(next_screenshot(Some(&dir)), dir.join("meshrefine-2.png"));
        std::fs::write(dir.join("meshrefine-2.png"), b"").unwrap();
        assert_eq!(next_screenshot(Some(&dir)), dir.join("meshrefine-4.png"));
        std::fs::remove_dir_all(&dir).unwrap();
        let here = next_screenshot(None);
        assert_eq!(here.parent(), Some(std::path::Path::new(".")));
        assert!(
            here.to_str().unwrap().starts_with("./meshrefine-"),
            "{here:?}"
        );
    }
}
