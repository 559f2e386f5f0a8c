//! The overlay panel (egui), after the UI overlay of Sascha Willems' Vulkan samples: the last
//! frame's statistics and the demo's switches in a small collapsible window anchored top-left,
//! drawn over the mesh by [`crate::gpu::Overlay`]. `H` shows and hides it; the keyboard
//! shortcuts change the same [`Controls`]. While the pointer is over the panel, or dragging in
//! it, egui takes pointer events and the camera ignores them.

use crate::render::{Background, DrawConfig, Driver, Submit, View};
use crate::surface::{Displace, NormalField, Surface, SurfaceParams};
use egui::{Align2, ClippedPrimitive, RichText, TexturesDelta};
use winit::event::WindowEvent;
use winit::window::Window;

/// The demo's switches, changed by keys and by the panel.
#[derive(Clone, Copy, Debug)]
pub struct Controls {
    pub cfg: DrawConfig,
    pub wireframe: bool,
    /// The cage overlay: the coarse mesh's edges.
    pub cage: bool,
    pub animate: bool,
    /// Level of detail by camera distance (sets `cfg.level` every frame).
    pub lod: bool,
    /// The largest level LOD chooses: the uniform level of the moment it was turned on (at
    /// the start, `--level`).
    pub lod_max: u32,
    /// The surface last asked for that the mesh refused (its fallback is shown): `S` goes on
    /// from it, not from the fallback.
    pub refused: Option<Surface>,
    /// The displacement switched off for a surface that cannot take it, shown again with the
    /// next surface that takes it (none chosen meanwhile).
    pub dropped: Option<Displace>,
    /// What the fragment stage shows.
    pub view: View,
    /// The parameters the demo started with: the sliders' ranges are scaled to them.
    pub initial: SurfaceParams,
    /// The pattern driver's submission mode, remembered while another driver is drawn.
    pub submit: Submit,
    /// Adaptive mode: each element at the levels its bound needs (pattern and tess); `cfg.level`
    /// is then the uniform mode's level only.
    pub adaptive: bool,
    /// The largest error allowed on screen in adaptive mode, in pixels.
    pub pixel_error: f32,
    /// The largest level in adaptive mode.
    pub max_level: u32,
    /// Adaptive mode culls elements outside the view or facing away.
    pub cull: bool,
    /// Adaptive levels stay those chosen for the camera of the moment this was set.
    pub freeze: bool,
    /// What the mesh is drawn on.
    pub background: Background,
    /// Borderless fullscreen.
    pub fullscreen: bool,
    /// What a key or a button asked for once, done at the next frame.
    pub asked: Asked,
}

/// One-shot requests of the keys and the panel's buttons, taken by the next frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Asked {
    /// Save the next frame as `meshrefine-<n>.png`.
    pub screenshot: bool,
    /// Back to the camera the demo started with.
    pub reset_camera: bool,
    /// Frame the mesh from the current direction.
    pub fit_view: bool,
}

/// Why adaptive frames of `driver` up to the largest level asked for, `largest` (the panel's,
/// at most what the driver draws on this device), cannot glide whatever `--geomorph` says
/// (`DrawConfig::glides`); `None` where they can.
pub fn glide_refusal(driver: Driver, largest: u32) -> Option<String> {
    let kind = driver.kind();
    let cfg = DrawConfig {
        geomorph: true,
        ..DrawConfig::new(driver, largest)
    };
    if cfg.glides() {
        None
    } else if kind.refines_on_cpu() {
        Some(format!("the {} driver never glides", kind.name()))
    } else {
        Some(format!(
            "the {} driver glides only under a largest level that is a power of two, not {largest}",
            kind.name()
        ))
    }
}

/// The pixel error's range in the window (the slider and the `[` `]` keys).
pub const PIXEL_ERRORS: std::ops::RangeInclusive<f32> = 0.25..=16.0;

/// The pixel error after `[` (`finer`: halved) or `]` (doubled), held within [`PIXEL_ERRORS`]:
/// a step past an end stops at it.
pub fn step_pixel_error(px: f32, finer: bool) -> f32 {
    let stepped = if finer { px * 0.5 } else { px * 2.0 };
    stepped.clamp(*PIXEL_ERRORS.start(), *PIXEL_ERRORS.end())
}

/// A pixel error from the command line as the window's slider holds it: within
/// [`PIXEL_ERRORS`], with a warning where it had to move.
pub fn slider_pixel_error(px: f32) -> f32 {
    let held = px.clamp(*PIXEL_ERRORS.start(), *PIXEL_ERRORS.end());
    if held != px {
        log::warn!(
            "the window's pixel error spans {} to {} px (its slider): --pixel-error {} is drawn at {held} px",
            PIXEL_ERRORS.start(),
            PIXEL_ERRORS.end(),
            crate::lod::px(px)
        );
    }
    held
}

impl Controls {
    /// The pattern driver with submission `s`.
    pub fn set_submit(&mut self, s: Submit) {
        self.submit = s;
        self.cfg.driver = Driver::Pattern(s);
    }

    /// The level `+` and `-` step: the largest level in adaptive mode, else the level.
    pub fn level(&self) -> u32 {
        if self.adaptive {
            self.max_level
        } else {
            self.cfg.level
        }
    }

    /// Set [`Controls::level`].
    pub fn set_level(&mut self, l: u32) {
        if self.adaptive {
            self.max_level = l;
        } else {
            self.cfg.level = l;
        }
    }

    /// Switch to the kind of driver `d` (the pattern driver with the remembered submission).
    pub fn set_driver(&mut self, d: Driver) {
        self.cfg.driver = match d {
            Driver::Pattern(_) => Driver::Pattern(self.submit),
            other => other,
        };
    }
}

/// What the panel reports and offers.
pub struct PanelInfo<'a> {
    pub device: &'a str,
    /// The pattern set's levels, ascending.
    pub levels: &'a [u32],
    pub wireframe_supported: bool,
    /// No frame is drawn yet (the first one's panel): nothing to show of the last frame.
    pub first: bool,
    pub fps: f64,
    /// GPU time of the last frame (timestamp queries).
    pub gpu_ms: f64,
    /// What the last frame drew (LOD and the tessellator's limit applied).
    pub drawn: DrawConfig,
    pub coarse: u64,
    pub refined: u64,
    pub geometry_bytes: u64,
    /// Bytes an animated frame uploads (level-independent but for static).
    pub upload_bytes: u64,
    /// Whether the mesh is animated (the upload figure is shown only then).
    pub animating: bool,
    /// The loop surface's basis function tables.
    pub table_bytes: Option<u64>,
    /// Whether the mesh has texture coordinates (the height map needs them).
    pub has_texcoords: bool,
    /// Why the frame draws less than asked (a level lowered to keep frames interactive).
    pub note: Option<&'a str>,
    /// Why adaptive mode drew the last frame uniformly (a configuration the driver cannot
    /// draw adaptively).
    pub mode_note: Option<&'a str>,
    /// What the last adaptive frame chose, as name and value rows.
    pub adaptive_rows: Vec<(&'static str, String)>,
    /// The camera as `render` takes it (`--eye X,Y,Z --look-at X,Y,Z`, the file's coordinates).
    pub camera: &'a str,
    /// Where the last screenshot key's frame went (or why it could not).
    pub screenshot_note: Option<&'a str>,
}

/// One frame of egui output, ready for [`crate::gpu::Overlay`].
pub struct UiFrame {
    pub textures: TexturesDelta,
    pub primitives: Vec<ClippedPrimitive>,
    pub pixels_per_point: f32,
}

/// egui's context and its winit input state.
pub struct Ui {
    egui: egui::Context,
    input: egui_winit::State,
    pub visible: bool,
}

impl Ui {
    pub fn new(window: &Window, max_texture_side: usize) -> Self {
        let egui = egui::Context::default();
        // Room for the passes a new or resized panel takes to lay out (an invisible sizing
        // pass, the grid's columns, the height measured), so that the first frame, which a
        // `--frames 1 --screenshot` run saves, shows it laid out.
        egui.options_mut(|o| o.max_passes = std::num::NonZeroUsize::new(4).unwrap());
        let input = egui_winit::State::new(
            egui.clone(),
            egui::ViewportId::ROOT,
            window,
            Some(window.scale_factor() as f32),
            None,
            Some(max_texture_side),
        );
        Self {
            egui,
            input,
            visible: true,
        }
    }

    /// Feed a window event to egui. True when egui takes it and the demo should ignore it: a
    /// button or wheel event while the pointer (at `cursor`, physical pixels) is over the panel or
    /// egui is dragging, or a key egui wants. The panel is hit-tested where it was last drawn,
    /// not by egui's hover state of the last frame, so a slow frame cannot pass a click or a
    /// wheel turn over the panel through to the camera.
    pub fn on_window_event(
        &mut self,
        window: &Window,
        event: &WindowEvent,
        cursor: (f64, f64),
    ) -> bool {
        let response = self.input.on_window_event(window, event);
        match event {
            WindowEvent::MouseInput { .. } | WindowEvent::MouseWheel { .. } => {
                self.egui.is_using_pointer() || self.over_panel(window, cursor)
            }
            _ => response.consumed,
        }
    }

    fn over_panel(&self, window: &Window, (x, y): (f64, f64)) -> bool {
        let ppp = egui_winit::pixels_per_point(&self.egui, window) as f64;
        let pos = egui::pos2((x / ppp) as f32, (y / ppp) as f32);
        // egui keeps a full-window background layer; the panel is a window above it.
        self.visible
            && self
                .egui
                .layer_id_at(pos)
                .is_some_and(|layer| layer.order != egui::Order::Background)
    }

    /// Lay out one frame: the panel when visible (applying its switches to `controls`),
    /// nothing otherwise (egui still consumes its input and keeps its textures).
    pub fn run(&mut self, window: &Window, controls: &mut Controls, info: &PanelInfo) -> UiFrame {
        let input = self.input.take_egui_input(window);
        let visible = self.visible;
        let output = self.egui.run(input, |ctx| {
            if visible {
                panel(ctx, controls, info);
            }
        });
        self.input
            .handle_platform_output(window, output.platform_output);
        UiFrame {
            textures: output.textures_delta,
            primitives: self.egui.tessellate(output.shapes, output.pixels_per_point),
            pixels_per_point: output.pixels_per_point,
        }
    }
}

/// The panel: the device, the last frame's statistics, then the switches by section.
fn panel(ctx: &egui::Context, c: &mut Controls, info: &PanelInfo) {
    // A window that grows after the panel was cut to its height: egui keeps the panel's
    // shrunk (scrolled) height, so the panel is measured afresh, as a new one (expanded), when
    // the window grows while the panel reaches its bottom; otherwise (F11 over a panel that
    // fits, a collapsed panel) it stays as it is.
    let height = ctx.screen_rect().height();
    let key = egui::Id::new("meshrefine panel: (screen height, cut, generation, content)");
    let (before, cut, generation, content): (f32, bool, u32, f32) =
        ctx.data_mut(|d| d.get_temp(key).unwrap_or((height, false, 0, f32::INFINITY)));
    let generation = generation + u32::from(height > before && cut);
    // A scrolled window is as tall as it is told, whatever its contents (egui 0.31): its rows'
    // height as the last frame measured it (all of the window's height less the title bar at
    // first), at most the window's.
    let tall = content.min(height - 60.0).max(60.0);
    let shown = egui::Window::new("meshrefine")
        .id(egui::Id::new(("meshrefine panel", generation)))
        .anchor(Align2::LEFT_TOP, [10.0, 10.0])
        .default_width(360.0)
        // At most 480 points wide (or the window's width): long rows wrap.
        .max_width((ctx.screen_rect().width() - 20.0).clamp(60.0, 480.0))
        .resizable(false)
        .collapsible(true)
        // Shown at once, not faded in over the first frames (a screenshot of the first frame).
        .fade_in(false)
        // Taller than the window (a small window, the default size in adaptive mode): the
        // panel scrolls instead of losing its last rows.
        .vscroll(true)
        .min_height(tall)
        .max_height(tall)
        .show(ctx, |ui| {
            ui.add(egui::Label::new(info.device).wrap());
            ui.separator();
            statistics(ui, info);
            ui.separator();
            drawing(ui, c, info);
            surface_choice(ui, c, info);
            parameters(ui, c);
            display(ui, c, info);
            ui.min_rect().height()
        });
    // Anchored 10 px down and at most 20 px shorter than the window: cut where it reaches
    // within a few pixels of the bottom.
    let cut = (shown.as_ref()).is_some_and(|r| r.response.rect.bottom() >= height - 15.0);
    let measured = shown.and_then(|r| r.inner).unwrap_or(content);
    if measured != content {
        // Lay out again at the measured height before this frame is drawn.
        ctx.request_discard("the panel's rows changed height");
    }
    ctx.data_mut(|d| d.insert_temp(key, (height, cut, generation, measured)));
}

/// The last frame's statistics, a name and a value a row.
fn statistics(ui: &mut egui::Ui, info: &PanelInfo) {
    egui::Grid::new("stats").num_columns(2).show(ui, |ui| {
        let d = &info.drawn;
        if info.first {
            // Rather than figures of a frame never drawn (the starting configuration's).
            ui.label("statistics");
            ui.label("from the next frame (this is the first)");
            ui.end_row();
            return;
        }
        let mut rows = vec![
            // Measuring until a frame's GPU time is read back (as the title's `-`).
            ("fps", measured(info.gpu_ms, || format!("{:.0}", info.fps))),
            (
                "GPU frame",
                measured(info.gpu_ms, || format!("{:.2} ms", info.gpu_ms)),
            ),
            (
                "drawn",
                match info.adaptive_rows.is_empty() {
                    true => format!("{} level {}", d.label(), d.level),
                    false => format!("{} adaptive, max level {}", d.label(), d.level),
                },
            ),
            (
                "surface",
                format!("{} + {}", d.surface.name(), d.displace.name()),
            ),
            (d.surface.facts().elements.label(), info.coarse.to_string()),
            ("refined triangles", info.refined.to_string()),
            (
                "GPU geometry",
                format!("{:.2} MB", info.geometry_bytes as f64 / 1e6),
            ),
        ];
        // What an animated frame uploads, while it animates.
        if info.animating {
            rows.push((
                "animated upload",
                format!("{:.1} KB / frame", info.upload_bytes as f64 / 1e3),
            ));
        }
        if let Some(t) = info.table_bytes {
            rows.push(("BF tables", format!("{:.1} KB", t as f64 / 1e3)));
        }
        rows.extend(info.adaptive_rows.iter().cloned());
        for (name, value) in rows {
            ui.label(name);
            // Long values (the uniform comparison, a wide histogram) wrap within the panel.
            ui.add(egui::Label::new(RichText::new(value).monospace()).wrap());
            ui.end_row();
        }
    });
    for note in [info.mode_note, info.note].into_iter().flatten() {
        ui.label(RichText::new(note).color(egui::Color32::from_rgb(240, 190, 90)));
    }
}

/// How it is drawn: the driver, the pattern driver's submission, the level (unless LOD sets it).
fn drawing(ui: &mut egui::Ui, c: &mut Controls, info: &PanelInfo) {
    ui.horizontal(|ui| {
        ui.label("driver [1 2 3]");
        for d in Driver::ALL {
            if ui
                .selectable_label(c.cfg.driver.same_kind(d), d.name())
                .clicked()
            {
                c.set_driver(d);
            }
        }
    });
    ui.add_enabled_ui(c.cfg.driver.submit().is_some(), |ui| {
        ui.horizontal(|ui| {
            ui.label("submit [P U I]");
            for s in Submit::ALL {
                if ui.selectable_label(c.submit == s, s.name()).clicked() {
                    c.set_submit(s);
                }
            }
        });
    });
    ui.horizontal(|ui| {
        ui.label("mode [M]");
        ui.selectable_value(&mut c.adaptive, true, "adaptive");
        ui.selectable_value(&mut c.adaptive, false, "uniform");
    });
    if c.adaptive {
        adaptive(ui, c, info);
        return;
    }
    ui.add_enabled_ui(!c.lod, |ui| {
        let drawn = info.adaptive_rows.is_empty().then_some(info.drawn.level);
        level_row(ui, "level [+ -]", &mut c.cfg.level, info.levels, drawn)
    });
}

/// A row of the levels the driver draws, the one the last frame drew selected (else
/// `current`, or the largest listed where `current` lies beyond the driver's limit: the
/// tessellator draws up to it); a click sets `current`.
fn level_row(
    ui: &mut egui::Ui,
    label: &str,
    current: &mut u32,
    levels: &[u32],
    drawn: Option<u32>,
) {
    ui.horizontal_wrapped(|ui| {
        ui.label(label);
        let selected = selected_level(*current, levels, drawn);
        for &l in levels {
            if ui.selectable_label(selected == l, l.to_string()).clicked() {
                *current = l;
            }
        }
    });
}

/// The level a row shows selected: the level the last frame drew in the row's mode (`drawn`: a
/// largest level rounded down to a power of two, lowered by the frame budget or chosen by LOD)
/// where the row has it, else `current`, at most the last of `levels` (ascending).
fn selected_level(current: u32, levels: &[u32], drawn: Option<u32>) -> u32 {
    match drawn {
        Some(l) if levels.contains(&l) => l,
        _ => levels.last().map_or(current, |&last| current.min(last)),
    }
}

/// Adaptive mode's controls: the pixel error (log scale), the largest level, culling, frozen
/// levels.
fn adaptive(ui: &mut egui::Ui, c: &mut Controls, info: &PanelInfo) {
    ui.add(
        egui::Slider::new(&mut c.pixel_error, PIXEL_ERRORS)
            .logarithmic(true)
            .suffix(" px")
            .text("pixel error [ ]"),
    );
    let drawn = (!info.adaptive_rows.is_empty()).then_some(info.drawn.level);
    level_row(ui, "max level [+ -]", &mut c.max_level, info.levels, drawn);
    ui.horizontal(|ui| {
        ui.checkbox(&mut c.cull, "cull [C]");
        // Where the driver drawn cannot glide the box is off and disabled, saying why.
        let largest = info
            .levels
            .last()
            .map_or(c.max_level, |&l| c.max_level.min(l));
        match glide_refusal(c.cfg.driver, largest) {
            None => ui.checkbox(&mut c.cfg.geomorph, "geomorph [G]"),
            Some(why) => ui
                .add_enabled(false, egui::Checkbox::new(&mut false, "geomorph [G]"))
                .on_disabled_hover_text(why),
        };
        ui.checkbox(&mut c.freeze, "freeze levels [F]");
    });
}

/// What is drawn: the surface and its displacement (the height map only where usable).
fn surface_choice(ui: &mut egui::Ui, c: &mut Controls, info: &PanelInfo) {
    ui.horizontal(|ui| {
        ui.label("surface [S]");
        for s in Surface::ALL {
            ui.selectable_value(&mut c.cfg.surface, s, s.name());
        }
    });
    ui.horizontal(|ui| {
        ui.label("displace [D]");
        for d in Displace::ALL {
            let why_not = c.cfg.surface.incompatibility(d, info.has_texcoords);
            ui.add_enabled_ui(why_not.is_none(), |ui| {
                let chose = ui.selectable_value(&mut c.cfg.displace, d, d.name());
                // Chosen: a displacement switched off for another surface stays off.
                if chose.clicked() {
                    c.dropped = None;
                }
                chose.on_disabled_hover_text(why_not.unwrap_or_default());
            });
        }
    });
}

/// The surface's and the displacement's parameters, each enabled where it applies, the
/// displacement's ranges scaled to the starting values.
fn parameters(ui: &mut egui::Ui, c: &mut Controls) {
    let p = &mut c.cfg.params;
    let reads = |option: &str| {
        c.cfg.surface.facts().options.contains(&option)
            || c.cfg.displace.facts().options.contains(&option)
    };
    ui.add_enabled(
        reads("alpha"),
        egui::Slider::new(&mut p.alpha, 0.0..=1.0).text("alpha"),
    );
    ui.add_enabled_ui(reads("normal_field"), |ui| {
        ui.horizontal(|ui| {
            ui.label("normal field");
            for f in NormalField::ALL {
                ui.selectable_value(&mut c.cfg.build.normal_field, f, f.name());
            }
        });
    });
    ui.add_enabled_ui(reads("amplitude"), |ui| {
        let a = c.initial.amplitude.abs().max(1e-6) * 4.0;
        ui.add(egui::Slider::new(&mut p.amplitude, -a..=a).text("amplitude"));
        let f = c.initial.frequency.max(1e-6) * 4.0;
        ui.add(egui::Slider::new(&mut p.frequency, 0.0..=f).text("frequency"));
        ui.add_enabled(
            reads("bias"),
            egui::Slider::new(&mut p.bias, 0.0..=1.0).text("bias"),
        );
        ui.add_enabled(
            reads("octaves"),
            egui::Slider::new(&mut p.octaves, 1..=SurfaceParams::MAX_OCTAVES).text("octaves"),
        );
    });
}

/// How it is shown: normals view, LOD, wireframe (where supported), cage, animation, the
/// background, the window and the camera, the hint.
fn display(ui: &mut egui::Ui, c: &mut Controls, info: &PanelInfo) {
    ui.horizontal(|ui| {
        ui.label("view [N]");
        for v in View::ALL {
            let name = match v {
                View::Levels => "colour by level",
                v => v.name(),
            };
            if ui.selectable_label(c.view == v, name).clicked() {
                c.view = v;
            }
        }
    });
    // LOD by distance picks the uniform mode's level.
    ui.add_enabled(
        !c.adaptive,
        egui::Checkbox::new(&mut c.lod, "LOD by distance [L]"),
    );
    ui.add_enabled(
        info.wireframe_supported,
        egui::Checkbox::new(&mut c.wireframe, "wireframe [W]"),
    );
    ui.checkbox(&mut c.cage, "cage [K]");
    ui.checkbox(&mut c.animate, "animate [A]");
    ui.horizontal(|ui| {
        ui.label("background [B]");
        for b in Background::ALL {
            ui.selectable_value(&mut c.background, b, b.name());
        }
    });
    ui.checkbox(&mut c.fullscreen, "fullscreen [F11]");
    ui.horizontal_wrapped(|ui| {
        c.asked.reset_camera |= ui.button("reset camera [R]").clicked();
        c.asked.fit_view |= ui.button("fit view [Z]").clicked();
        c.asked.screenshot |= ui.button("screenshot [F12]").clicked();
    });
    ui.add(egui::Label::new(RichText::new(info.camera).monospace()).wrap());
    if let Some(note) = info.screenshot_note {
        ui.add(egui::Label::new(note).wrap());
    }
    ui.weak("drag: orbit, right or middle drag: pan, wheel: zoom; H hides this panel");
}

/// `figure()` once a frame's GPU time (`gpu_ms`) has been read back, `measuring` before.
fn measured(gpu_ms: f64, figure: impl FnOnce() -> String) -> String {
    if gpu_ms > 0.0 {
        figure()
    } else {
        "measuring".to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pixel error from the command line is held within the slider's range, at its nearest
    /// end (docs/window.md).
    #[test]
    fn the_slider_holds_the_pixel_error_at_its_nearest_end() {
        assert_eq!(slider_pixel_error(64.0), 16.0);
        assert_eq!(slider_pixel_error(0.1), 0.25);
        assert_eq!(slider_pixel_error(1.5), 1.5);
        assert_eq!(slider_pixel_error(16.0), 16.0);
    }

    /// `[` halves and `]` doubles the pixel error, stopping at the range's ends (docs/window.md:
    /// 0.25 to 16 px), whatever the slider left between powers of two.
    #[test]
    fn the_keys_halve_and_double_the_pixel_error_within_its_range() {
        assert_eq!(step_pixel_error(1.0, true), 0.5);
        assert_eq!(step_pixel_error(1.0, false), 2.0);
        assert_eq!(step_pixel_error(0.25, true), 0.25);
        assert_eq!(step_pixel_error(0.3, true), 0.25);
        assert_eq!(step_pixel_error(16.0, false), 16.0);
        assert_eq!(step_pixel_error(12.0, false), 16.0);
        assert_eq!(step_pixel_error(12.0, true), 6.0);
        // Down from the top and back up again lands where it started.
        let mut px = 16.0;
        for _ in 0..10 {
            px = step_pixel_error(px, true);
        }
        assert_eq!(px, 0.25);
        for _ in 0..6 {
            px = step_pixel_error(px, false);
        }
        assert_eq!(px, 16.0);
    }

    /// A row selects the level the last frame of its mode drew (a largest level of 48 drawn at
    /// 32 by the pattern driver), else the level asked for, and a level beyond what the driver
    /// draws (128 after switching to a tessellator limited to 64) the largest listed, not none.
    #[test]
    fn the_level_row_selects_the_level_drawn() {
        let levels = [1, 2, 4, 8, 16, 32, 48, 64];
        assert_eq!(selected_level(48, &levels, Some(32)), 32);
        assert_eq!(selected_level(48, &levels, None), 48);
        // A level drawn that the row does not list (the frame budget's 12): the one asked for.
        assert_eq!(selected_level(16, &levels, Some(12)), 16);
        assert_eq!(selected_level(128, &levels, None), 64);
        assert_eq!(selected_level(40, &[1, 2, 4, 8, 16, 32, 40, 64], None), 40);
    }

    /// Geomorphing is refused where the driver cannot glide at the largest level asked for:
    /// never on static, on tess only under a power of two; the pattern driver always glides
    /// (its largest level is rounded down to one).
    #[test]
    fn geomorphing_is_refused_where_the_driver_cannot_glide() {
        let pattern = Driver::Pattern(Submit::Instanced);
        assert_eq!(glide_refusal(pattern, 64), None);
        assert_eq!(glide_refusal(Driver::Tess, 64), None);
        let tess = glide_refusal(Driver::Tess, 48).unwrap();
        assert!(tess.contains("power of two, not 48"), "{tess}");
        let stat = glide_refusal(Driver::Static, 64).unwrap();
        assert_eq!(stat, "the static driver never glides");
    }

    /// The panel is as tall as its rows where the window has room for them, and scrolls within
    /// the window where it has not (egui sizes a scrolled window by its default height, not its
    /// contents: the panel showed its first rows only, half the window's height).
    #[test]
    fn the_panel_shows_every_row_where_the_window_has_room() {
        let mut c = Controls {
            cfg: DrawConfig::new(Driver::Pattern(Submit::Instanced), 8),
            wireframe: false,
            cage: false,
            animate: false,
            lod: false,
            lod_max: 8,
            refused: None,
            dropped: None,
            view: View::Shaded,
            initial: SurfaceParams::default(),
            submit: Submit::Instanced,
            adaptive: true,
            pixel_error: 1.0,
            max_level: 64,
            cull: true,
            freeze: false,
            background: Background::Dark,
            fullscreen: false,
            asked: Asked::default(),
        };
        let info = PanelInfo {
            device: "a device",
            levels: &[1, 2, 4, 8, 16, 32, 64],
            wireframe_supported: true,
            first: false,
            fps: 60.0,
            gpu_ms: 1.0,
            drawn: c.cfg,
            coarse: 372,
            refined: 40000,
            geometry_bytes: 1000,
            upload_bytes: 0,
            animating: false,
            table_bytes: None,
            has_texcoords: false,
            note: None,
            mode_note: None,
            adaptive_rows: vec![("uniform level", "16".into()), ("culled", "30".into())],
            camera: "--eye 1,2,3 --look-at 0,0,0",
            screenshot_note: None,
        };
        // The panel's height after a few frames on a screen `height` points high.
        let panel_height = |c: &mut Controls, height: f32, info: &PanelInfo| {
            let ctx = egui::Context::default();
            let input = || egui::RawInput {
                screen_rect: Some(egui::Rect::from_min_size(
                    egui::Pos2::ZERO,
                    egui::vec2(1000.0, height),
                )),
                ..Default::default()
            };
            for _ in 0..4 {
                let _ = ctx.run(input(), |ctx| panel(ctx, c, info));
            }
            let id = egui::Id::new(("meshrefine panel", 0u32));
            ctx.memory(|m| m.area_rect(id))
                .expect("the panel is shown")
                .height()
        };
        let tall = panel_height(&mut c, 2000.0, &info);
        assert!(
            tall > 700.0,
            "the panel is {tall} points tall on a tall screen"
        );
        assert!(
            tall < 1500.0,
            "the panel is {tall} points tall, more than its rows"
        );
        let short = panel_height(&mut c, 500.0, &info);
        assert!(
            short <= 490.0,
            "the panel is {short} points tall on a 500-point screen"
        );
        // The first frame's panel has no last frame to show: one row where the statistics'
        // nine (with the adaptive rows) would be.
        let first = PanelInfo {
            first: true,
            ..info
        };
        let rows = 8.0 * 14.0;
        let without = panel_height(&mut c, 2000.0, &first);
        assert!(
            without < tall - rows,
            "the first frame's panel is {without} points tall, against {tall}"
        );
    }
}
