//! What the keys and the panel's buttons ask for, done at the start of a frame (after the
//! previous one is complete): the camera's reset and fit, and the window's fullscreen state.
#![forbid(unsafe_code)]

use super::ui::Asked;
use super::State;
use winit::window::Fullscreen;

impl State {
    /// Reset or fit the camera as asked (the screenshot is the frame's business).
    pub(super) fn apply_asked(&mut self, asked: &Asked) {
        if asked.reset_camera {
            self.camera = self.start_camera;
        }
        if asked.fit_view {
            let e = self.swapchain.extent;
            let aspect = e.width as f32 / e.height.max(1) as f32;
            let framing = self.scene.framing_points(&self.controls.cfg);
            self.camera = (self.camera).fit_clear_of(&framing.points, &framing.reach, aspect);
        }
        self.apply_window_mode();
    }

    /// Make the window fullscreen or windowed as `controls.fullscreen` asks, when it changed:
    /// borderless on the window's monitor, asking for the monitor's size too (a window
    /// manager gives a fullscreen window that size; without one, as on a bare X server,
    /// nothing else would), and back to the windowed size. The swapchain follows the resize
    /// events.
    pub(super) fn apply_window_mode(&mut self) {
        let on = self.controls.fullscreen;
        if on == self.fullscreen {
            return;
        }
        if on {
            let monitor = (self.window.current_monitor())
                .or_else(|| self.window.primary_monitor())
                .or_else(|| self.window.available_monitors().next());
            let Some(monitor) = monitor else {
                log::warn!("no monitor found to fill: the window stays as it is");
                self.controls.fullscreen = false;
                return;
            };
            let size = monitor.size();
            self.windowed_size = self.window.inner_size().into();
            self.window
                .set_fullscreen(Some(Fullscreen::Borderless(Some(monitor))));
            let _ = self.window.request_inner_size(size);
        } else {
            self.window.set_fullscreen(None);
            let _ = self.window.request_inner_size(self.windowed_size);
        }
        self.fullscreen = on;
    }
}
