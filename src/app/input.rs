//! The window's events: winit's callbacks, the mouse's orbit and zoom, and the keys.

use super::ui::step_pixel_error;
use super::{camera, next, App, State, ViewOptions};
use crate::render::{Background, DrawConfig, Driver, Submit, View};
use crate::surface::{Displace, Surface};
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::ActiveEventLoop;
use winit::keyboard::{Key, NamedKey};
use winit::window::WindowId;

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.state.is_some() {
            return;
        }
        match self.create(event_loop) {
            Ok(s) => {
                self.messages = Some(s.ctx.messages_handle());
                self.state = Some(s);
            }
            Err(e) => {
                self.error = Some(e);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(s) = self.state.as_mut() else { return };
        // Pointer events egui takes (over or dragging the panel) leave the camera alone.
        let egui_took = s.ui.on_window_event(&s.window, &event, s.cursor);
        match event {
            WindowEvent::CloseRequested => s.request_quit(&self.opts, event_loop),
            // Another client destroyed the window: nothing more can be shown.
            WindowEvent::Destroyed => {
                self.error = Some(anyhow::anyhow!("the window was closed by another program"));
                event_loop.exit();
            }
            WindowEvent::Resized(_) => s.resize = true,
            WindowEvent::Occluded(hidden) => s.occluded = hidden,
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Left,
                ..
            } => {
                s.drag = (state == ElementState::Pressed && !egui_took).then_some(s.cursor);
            }
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Right | MouseButton::Middle,
                ..
            } => {
                s.pan_drag = (state == ElementState::Pressed && !egui_took).then_some(s.cursor);
            }
            WindowEvent::CursorMoved { position, .. } => {
                s.cursor = (position.x, position.y);
                if let Some((x, y)) = s.drag {
                    s.camera.orbit(
                        ((position.x - x) * 0.01) as f32,
                        ((position.y - y) * 0.01) as f32,
                    );
                    s.drag = Some(s.cursor);
                }
                if let Some((x, y)) = s.pan_drag {
                    let height = s.window.inner_size().height as f32;
                    let bounds = camera::view_bounds(&s.scene);
                    let d = ((position.x - x) as f32, (position.y - y) as f32);
                    camera::pan(&mut s.camera, d, height, bounds);
                    s.pan_drag = Some(s.cursor);
                }
            }
            WindowEvent::MouseWheel { delta, .. } if !egui_took => {
                let d = match delta {
                    MouseScrollDelta::LineDelta(_, y) => y,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                s.camera.zoom(0.9f32.powf(d));
            }
            WindowEvent::KeyboardInput { event, .. } if !egui_took => {
                let quit = event.state == ElementState::Pressed && !s.key(&event.logical_key);
                if quit {
                    s.request_quit(&self.opts, event_loop);
                }
            }
            WindowEvent::RedrawRequested => match s.frame(&self.opts) {
                Ok(true) => {}
                Ok(false) => event_loop.exit(),
                Err(e) => {
                    self.error = Some(if surface_lost(&e) {
                        anyhow::anyhow!(super::WINDOW_GONE)
                    } else {
                        e
                    });
                    event_loop.exit();
                }
            },
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _event_loop: &ActiveEventLoop) {
        if let Some(s) = &self.state {
            // Minimised (X11 reports no zero size for it) or wholly covered: no frames until
            // it shows again, whose events (map, expose) wake the loop with a redraw; except
            // the last one asked for on quitting, to save the screenshot.
            if s.quit || !(s.occluded || s.window.is_minimized() == Some(true)) {
                s.window.request_redraw();
            }
        }
    }
}

impl State {
    /// Close or Esc: with `--screenshot`, draw one last frame to save it, then exit.
    pub(super) fn request_quit(&mut self, opts: &ViewOptions, event_loop: &ActiveEventLoop) {
        if opts.screenshot.is_some() {
            self.quit = true;
        } else {
            event_loop.exit();
        }
    }

    /// Why the mesh cannot take displacement `d` with `cfg`'s parameters: the limits the command
    /// line checks (docs/errors.md, "Displacement limits"), in the drawn frame: a mesh far
    /// from its own origin cannot take `sine` or `noise`, and the panel's sliders can ask for
    /// more than any mesh takes.
    pub(super) fn displacement_refusal(&self, cfg: &DrawConfig, d: Displace) -> Option<String> {
        let (centre, radius) = self.scene.bounding_sphere();
        let extent = (centre - cfg.params.origin).as_dvec3().length() + radius as f64;
        cfg.params.check_displacement(d, radius, extent).err()
    }

    /// A displacement the surface cannot take (`S` or a panel click onto `loop` with the height
    /// map) is switched off and remembered, said once; it comes back with the next surface that
    /// takes it, unless another displacement was chosen meanwhile.
    fn settle_displacement(&mut self, opts: &ViewOptions) {
        let source = &opts.source;
        let uvs = self.scene.data.uvs.is_some();
        let c = &mut self.controls;
        // A surface the mesh refuses (Loop on a mesh it cannot subdivide) shows the fallback.
        let refused = opts.loop_refusal.is_some() && c.cfg.surface.facts().needs_every_face;
        let surface = if refused {
            Surface::FALLBACK
        } else {
            c.cfg.surface
        };
        let displace = c.cfg.displace;
        if let Some(why) = surface.incompatibility(displace, uvs) {
            // On a mesh without texture coordinates no surface takes it back.
            let back = match uvs {
                true => format!(
                    "; the {} displacement comes back with a surface that takes it",
                    displace.name()
                ),
                false => String::new(),
            };
            log::warn!("'{source}': {why}: showing no displacement{back}");
            c.dropped = uvs.then_some(displace);
            c.cfg.displace = Displace::None;
        } else if let Some(d) = c.dropped {
            if displace != Displace::None {
                c.dropped = None;
            } else if surface.incompatibility(d, uvs).is_none() {
                log::warn!(
                    "'{source}': the {} surface takes the {} displacement: showing it again",
                    surface.name(),
                    d.name()
                );
                c.cfg.displace = d;
                c.dropped = None;
            }
        }
    }

    /// `cfg` without a displacement the mesh cannot take (the panel's buttons and sliders can
    /// choose one), said once per refusal; one its surface cannot take is settled first.
    pub(super) fn limit_displacement(&mut self, cfg: &mut DrawConfig, opts: &ViewOptions) {
        let source = &opts.source;
        self.settle_displacement(opts);
        cfg.displace = self.controls.cfg.displace;
        let Some(why) = self.displacement_refusal(cfg, cfg.displace) else {
            return;
        };
        log::warn!("'{source}': {why}: showing no displacement");
        cfg.displace = Displace::None;
        self.controls.cfg.displace = Displace::None;
    }

    /// Handle a key; false quits.
    pub(super) fn key(&mut self, key: &Key) -> bool {
        let levels: Vec<u32> = self.scene.patterns.levels().collect();
        let limit = (self.controls.cfg.driver.kind())
            .level_limit(&self.ctx.info)
            .map(|(max, _)| max);
        let uvs = self.scene.data.uvs.is_some();
        let refused: Vec<Displace> = (Displace::ALL.into_iter())
            .filter(|&d| self.displacement_refusal(&self.controls.cfg, d).is_some())
            .collect();
        let beyond = |d| refused.contains(&d);
        let largest = limit.map_or(self.controls.max_level, |l| self.controls.max_level.min(l));
        let glide_refusal = super::ui::glide_refusal(self.controls.cfg.driver, largest);
        let lines = self.ctx.info.fill_mode_non_solid;
        let c = &mut self.controls;
        match key {
            Key::Named(NamedKey::Escape) => return false,
            Key::Named(NamedKey::Home) => c.asked.fit_view = true,
            Key::Named(NamedKey::F11) => c.fullscreen = !c.fullscreen,
            Key::Named(NamedKey::F12) => c.asked.screenshot = true,
            Key::Character(ch) => match ch.as_str() {
                "1" | "2" | "3" => c.set_driver(Driver::ALL[(ch.as_bytes()[0] - b'1') as usize]),
                "s" | "S" => {
                    let from = c.refused.take().unwrap_or(c.cfg.surface);
                    // A displacement the new surface cannot take (Loop's M1 has no texture
                    // coordinates for the height map) is switched off until one that takes it
                    // (`settle_displacement`).
                    c.cfg.surface = next(&Surface::ALL, from);
                }
                "d" | "D" => {
                    // Skip the displacements this surface and mesh cannot take (no displacement
                    // always can).
                    let surface = c.cfg.surface;
                    let takes = |d| surface.incompatibility(d, uvs).is_none() && !beyond(d);
                    c.cfg.displace = next_displacement(c.cfg.displace, takes);
                }
                "n" | "N" => {
                    c.view = next(&View::ALL, c.view);
                }
                "p" | "P" => c.set_submit(Submit::Push),
                "u" | "U" => c.set_submit(Submit::Ubo),
                "i" | "I" => c.set_submit(Submit::Instanced),
                "+" | "=" | "-" | "_" => {
                    let up = matches!(ch.as_str(), "+" | "=");
                    let to = step_level(&levels, limit, c.level(), up);
                    if to == c.level() {
                        // The driver's limit on this device, or the end of the window's list.
                        let end = match (up, limit.is_some_and(|m| to >= m)) {
                            (false, _) => "the smallest level",
                            (true, true) => "the largest level the driver draws here",
                            (true, false) => "the largest level the window offers",
                        };
                        log::warn!("'{ch}' changes nothing: {to} is {end}");
                    }
                    c.set_level(to);
                }
                "m" | "M" => c.adaptive = !c.adaptive,
                "c" | "C" if c.adaptive => c.cull = !c.cull,
                "g" | "G" if c.adaptive && glide_refusal.is_some() => {
                    let why = glide_refusal.as_deref().unwrap_or_default();
                    log::warn!("'{ch}' changes nothing here: {why}")
                }
                "g" | "G" if c.adaptive => c.cfg.geomorph = !c.cfg.geomorph,
                "f" | "F" if c.adaptive => c.freeze = !c.freeze,
                "[" | "]" if c.adaptive => {
                    let finer = ch.as_str() == "[";
                    let px = step_pixel_error(c.pixel_error, finer);
                    if px == c.pixel_error {
                        let end = if finer { "smallest" } else { "largest" };
                        log::warn!(
                            "'{ch}' changes nothing: the pixel error is at its {end}, {px} px"
                        );
                    }
                    c.pixel_error = px;
                }
                // Each mode's own keys change nothing in the other (it would show up unasked
                // on switching back), and say so.
                "c" | "C" | "g" | "G" | "f" | "F" | "[" | "]" => {
                    log::warn!("'{ch}' acts in adaptive mode only (M switches to it)")
                }
                "l" | "L" if c.adaptive => {
                    log::warn!(
                        "'{ch}' (LOD by distance) acts in uniform mode only (M switches to it)"
                    )
                }
                "w" | "W" if !lines => log::warn!(
                    "'{ch}' changes nothing here: the device has no fillModeNonSolid, which the wireframe's lines need"
                ),
                "w" | "W" => c.wireframe = !c.wireframe,
                "k" | "K" => c.cage = !c.cage,
                "a" | "A" => c.animate = !c.animate,
                "l" | "L" => c.lod = !c.lod,
                "h" | "H" => self.ui.visible = !self.ui.visible,
                "r" | "R" => c.asked.reset_camera = true,
                "z" | "Z" => c.asked.fit_view = true,
                "b" | "B" => c.background = next(&Background::ALL, c.background),
                _ => {}
            },
            _ => {}
        }
        true
    }
}

/// The displacement after `from` (in [`Displace::ALL`]'s order, round) that the surface and mesh
/// `take`; none, which every surface takes, where no other is.
fn next_displacement(from: Displace, take: impl Fn(Displace) -> bool) -> Displace {
    let mut d = next(&Displace::ALL, from);
    while d != Displace::None && !take(d) {
        d = next(&Displace::ALL, d);
    }
    d
}

/// The window's levels the driver draws on this device (`limit`: its largest, if it has one):
/// what `+` and `-` step through and the panel offers.
pub(super) fn usable_levels(levels: &[u32], limit: Option<u32>) -> Vec<u32> {
    (levels.iter().copied())
        .filter(|&l| limit.is_none_or(|max| l <= max))
        .collect()
}

/// The window's level after `current` (`up`) or before it among `levels` (ascending), up to
/// the driver's `limit`: `+` stops at the finest level the driver draws (rather than counting
/// on past it with nothing changing on screen), and a level beyond it steps down from there.
fn step_level(levels: &[u32], limit: Option<u32>, current: u32, up: bool) -> u32 {
    let usable = usable_levels(levels, limit);
    let Some(&last) = usable.last() else {
        return current;
    };
    let current = current.min(last);
    // The position of the largest usable level at or below the current one.
    let pos = usable.iter().rposition(|&l| l <= current).unwrap_or(0);
    if up {
        usable[(pos + 1).min(usable.len() - 1)]
    } else if usable[pos] < current {
        usable[pos]
    } else {
        usable[pos.saturating_sub(1)]
    }
}

/// Whether `e` says the window's surface is gone (the window was destroyed under the demo).
fn surface_lost(e: &anyhow::Error) -> bool {
    matches!(
        e.downcast_ref::<crate::gpu::GpuError>(),
        Some(crate::gpu::GpuError::Vk {
            result: crate::gpu::vk::Result::ERROR_SURFACE_LOST_KHR,
            ..
        })
    )
}

#[cfg(test)]
mod tests {
    use super::step_level;

    /// `D` skips the displacements the mesh cannot take: the height map without texture
    /// coordinates, `sine` and `noise` beyond the displacement limits (a mesh far from its
    /// origin), as the command line refuses them.
    #[test]
    fn d_skips_what_the_mesh_cannot_take() {
        use crate::surface::{Displace, Surface, SurfaceParams};
        let far = |d| {
            SurfaceParams::default()
                .check_displacement(d, 1.0, 1.7e7)
                .is_err()
        };
        let takes = |uvs: bool| move |d| Surface::Pn.incompatibility(d, uvs).is_none() && !far(d);
        assert_eq!(
            super::next_displacement(Displace::None, takes(false)),
            Displace::None
        );
        assert_eq!(
            super::next_displacement(Displace::None, takes(true)),
            Displace::Heightmap
        );
        let near = |d| Surface::Pn.incompatibility(d, false).is_none();
        assert_eq!(
            super::next_displacement(Displace::None, near),
            Displace::Sine
        );
        assert_eq!(
            super::next_displacement(Displace::Sine, near),
            Displace::Noise
        );
        assert_eq!(
            super::next_displacement(Displace::Noise, near),
            Displace::None
        );
    }

    #[test]
    fn levels_step_within_what_the_driver_draws() {
        let levels = [1, 2, 3, 4, 8, 16, 32, 64, 128, 256];
        assert_eq!(step_level(&levels, None, 4, true), 8);
        assert_eq!(step_level(&levels, None, 4, false), 3);
        assert_eq!(step_level(&levels, None, 256, true), 256);
        assert_eq!(step_level(&levels, None, 1, false), 1);
        // The tessellator up to 64 on this device: `+` stops there, `-` from past it goes
        // below what is shown.
        assert_eq!(step_level(&levels, Some(64), 64, true), 64);
        assert_eq!(step_level(&levels, Some(64), 256, false), 32);
        assert_eq!(step_level(&levels, Some(64), 128, true), 64);
        // A level between the listed ones steps to its neighbours.
        assert_eq!(step_level(&levels, None, 5, true), 8);
        assert_eq!(step_level(&levels, None, 5, false), 4);
    }
}
