//! The window demo (winit 0.30 + ash-window): orbit camera, adaptive mode (each element at the
//! level its bound needs; pixel error, largest level, culling, frozen levels) or uniform mode,
//! live switching of driver, submission mode, level, LOD, wireframe and a CPU animation of the
//! coarse mesh (docs/window.md). Two HUDs: the window title
//! (fps, GPU frame time from timestamp queries, coarse and refined triangle counts, GPU geometry
//! bytes) and an egui overlay panel (`ui`, key `H`) that shows the same and has the switches;
//! the terminal gets the key help.
//!
//! One frame in flight: each frame waits for the previous frame's fence before it writes uniforms
//! or records, uploads overlay textures, or rebuilds anything, so nothing in flight is ever
//! changed or destroyed.
#![forbid(unsafe_code)]

mod actions;
mod adaptive;
mod budget;
mod camera;
mod draw;
mod hud;
mod input;
mod options;
mod ui;

pub use adaptive::{AdaptiveView, DEFAULT_MAX_LEVEL, DEFAULT_PIXEL_ERROR};
pub use options::ViewOptions;

use crate::gpu::sample_count;
use crate::gpu::{
    surface_extensions, vk, Buffer, CommandPool, Context, ContextDesc, Fence, Messages, Overlay,
    QueryPools, Semaphore, Swapchain, DEPTH_FORMAT,
};
use crate::mesh::Mesh;
use crate::render::{Camera, DrawConfig, Renderer, Scene};
use crate::surface::Surface;
use anyhow::{anyhow, Context as _, Result};
use raw_window_handle::{HasDisplayHandle, HasWindowHandle};
use std::io::Write as _;
use std::sync::Arc;
use std::time::Instant;
use ui::{Asked, Controls, Ui};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::window::Window;

/// How the demo ends when its window goes away under it (another program destroyed it, its
/// Vulkan surface was lost, or the display went away): one sentence whichever noticed first.
pub(super) const WINDOW_GONE: &str =
    "the window system failed: the window was closed by another program, or its display went away";

/// The window system could not be opened (no reachable X server, say): callers may fall back
/// to a headless render.
#[derive(Debug, thiserror::Error)]
#[error("cannot connect to the display '{0}'")]
pub struct NoWindowSystem(pub String);

/// The window offers every power-of-two level up to this one (and the level it starts at):
/// `+` reaches it whatever the start level. A pattern of level 256 is 33,153 vertices.
pub const WINDOW_LEVELS: u32 = 256;

pub const KEY_HELP: &str = "keys: left drag = orbit, right or middle drag = pan, wheel = zoom, \
R = reset camera, Z or Home = fit view, 1/2/3 = static/pattern/tess, \
P/U/I = push/ubo/instanced, S = next surface, D = next displacement, N = next view, \
+/- = level (max level when adaptive), M = adaptive/uniform, [/] = pixel error halve/double, \
C = culling, G = geomorph, F = freeze levels, L = LOD by distance, W = wireframe, K = cage, A = animate, \
B = background, F11 = fullscreen, F12 = screenshot, H = panel, Esc = quit";

/// The value after `v` in `all`, wrapping around.
fn next<T: Copy + PartialEq>(all: &[T], v: T) -> T {
    let i = all.iter().position(|&x| x == v).unwrap_or(0);
    all[(i + 1) % all.len()]
}

/// Make `items` hold exactly one item per swapchain image (`count`), creating the missing ones
/// with `make(index)` and dropping the extra ones: a recreated swapchain may have more or fewer
/// images than the first.
fn per_image<T, E>(
    items: &mut Vec<T>,
    count: usize,
    mut make: impl FnMut(usize) -> Result<T, E>,
) -> Result<(), E> {
    items.truncate(count);
    while items.len() < count {
        let i = items.len();
        items.push(make(i)?);
    }
    Ok(())
}

/// The window system, reached: what [`run`] opens the window on. Where it cannot be reached
/// (no X server at `DISPLAY`, say) the caller may fall back to a headless render, before
/// checking what only a window reads.
pub fn connect() -> Result<EventLoop<()>, NoWindowSystem> {
    EventLoop::new().map_err(|e| {
        log::debug!("winit: {e}");
        // An empty variable names no display (the command line treats it as unset).
        let named = |v: &str| std::env::var(v).ok().filter(|d| !d.is_empty());
        let display = named("WAYLAND_DISPLAY")
            .or_else(|| named("DISPLAY"))
            .unwrap_or_default();
        NoWindowSystem(display)
    })
}

/// Run the demo on `event_loop` ([`connect`]) until the window closes (or `frames` frames).
/// Returns the context's message list so the caller can check validation and leaks after
/// everything is dropped.
pub fn run(
    event_loop: EventLoop<()>,
    desc: ContextDesc,
    mesh: Mesh,
    opts: ViewOptions,
) -> Result<Arc<Messages>> {
    let mut app = App {
        desc,
        mesh: Some(mesh),
        opts,
        state: None,
        error: None,
        messages: None,
    };
    // The window system may fail under winit's feet (another client destroys the window: X
    // answers BadDrawable where winit expects a reply and panics). That ends the demo with one
    // sentence, not a backtrace: the panic message is kept instead of printed.
    let panicked = Arc::new(std::sync::Mutex::new(None::<String>));
    let previous = std::panic::take_hook();
    let record = panicked.clone();
    std::panic::set_hook(Box::new(move |info| {
        *record.lock().unwrap_or_else(|p| p.into_inner()) = Some(info.to_string());
    }));
    let ran = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        event_loop.run_app(&mut app)
    }));
    std::panic::set_hook(previous);
    app.state = None; // drop every Vulkan object before reporting
    match ran {
        Ok(result) => result.context("window event loop failed")?,
        Err(_) => {
            let why = panicked.lock().unwrap_or_else(|p| p.into_inner()).take();
            log::debug!("window system panic: {why:?}");
            return Err(anyhow!(WINDOW_GONE));
        }
    }
    if let Some(e) = app.error {
        return Err(e);
    }
    app.messages
        .ok_or_else(|| anyhow!("the window was never shown"))
}

struct App {
    desc: ContextDesc,
    mesh: Option<Mesh>,
    opts: ViewOptions,
    state: Option<State>,
    error: Option<anyhow::Error>,
    messages: Option<Arc<Messages>>,
}

/// Field order is drop order: GPU objects first, the window last.
struct State {
    scene: Scene,
    base_mesh: Mesh,
    renderer: Renderer,
    overlay: Overlay,
    queries: QueryPools,
    screenshot_buffer: Option<Buffer>,
    cmd: vk::CommandBuffer,
    pool: CommandPool,
    fence: Fence,
    acquired: Semaphore,
    rendered: Vec<Semaphore>,
    swapchain: Swapchain,
    ctx: Arc<Context>,
    window: Arc<Window>,
    ui: Ui,
    camera: Camera,
    /// The camera the demo started with (`R` returns to it).
    start_camera: Camera,
    /// [`ViewOptions::viewing`]: the camera is reported in the file's coordinates.
    viewing: (glam::DVec3, f64),
    controls: Controls,
    /// Whether the window was last made fullscreen (`controls.fullscreen` asks), and the
    /// windowed size to return to.
    fullscreen: bool,
    windowed_size: winit::dpi::Size,
    /// Where the last screenshot key's frame went, or why it could not be saved.
    screenshot_note: Option<String>,
    /// What the last frame drew (LOD and the tessellator's limit applied).
    drawn: DrawConfig,
    /// The level last lowered to what the driver can draw (said once).
    level_note: Option<u32>,
    /// Set while the frame draws a lower level than asked, to keep frames under a second on a
    /// software device: what the panel says about it.
    budget_note: Option<String>,
    /// Whether the frame budget applies ([`ViewOptions::frame_budget`]).
    frame_budget: bool,
    /// Why adaptive mode draws this frame uniformly (a configuration the driver cannot draw
    /// adaptively): what the panel says about it.
    mode_note: Option<String>,
    /// The levels the last frame drew with, when it drew adaptively.
    levels: Option<crate::render::ChosenLevels>,
    /// What choosing the last adaptive frame's levels cost.
    level_cost: hud::LevelCost,
    /// The kinds of unmet pixel error last said on standard error (`hud.rs`), to say them
    /// again only when they change.
    unmet_said: Option<hud::UnmetKinds>,
    /// The largest level the last adaptive frame drew (the frame budget may lower it).
    adaptive_level: Option<u32>,
    /// The camera and window size frozen levels are chosen for.
    frozen: Option<(Camera, vk::Extent2D)>,
    /// The slowest GPU time per refined triangle measured on a slow adaptive frame (over a
    /// quarter second) of this driver, surface and displacement, in nanoseconds.
    measured_rates: adaptive::MeasuredRates,
    /// What the last frame drew (configuration, wireframe, adaptively), and whether the frame
    /// before drew the same: only then were its pipelines compiled before it (lavapipe compiles
    /// at the first draw, inside the frame's GPU time).
    last_drawn: Option<(DrawConfig, bool, bool)>,
    warm: bool,
    start: Instant,
    frames: u64,
    recorded_once: bool,
    resize: bool,
    /// The window is wholly covered (`WindowEvent::Occluded`): frames pause.
    occluded: bool,
    /// Quit was asked for: the next frame is the last (and saves the screenshot).
    quit: bool,
    drag: Option<(f64, f64)>,
    /// A right or middle drag pans from this position.
    pan_drag: Option<(f64, f64)>,
    cursor: (f64, f64),
    fps_window: (Instant, u64),
    fps: f64,
    gpu_ms: f64,
}

impl App {
    fn create(&mut self, event_loop: &ActiveEventLoop) -> Result<State> {
        let (w, h) = self.opts.size;
        let windowed_size = winit::dpi::LogicalSize::new(w as f64, h as f64).into();
        let attrs = Window::default_attributes()
            .with_title("meshrefine")
            .with_inner_size(windowed_size);
        let window = Arc::new(
            event_loop
                .create_window(attrs)
                .context("cannot create a window")?,
        );
        let display = window
            .display_handle()
            .map_err(|e| anyhow!("no display handle: {e}"))?
            .as_raw();
        let handle = window
            .window_handle()
            .map_err(|e| anyhow!("no window handle: {e}"))?
            .as_raw();
        let mut desc = self.desc.clone();
        desc.surface_extensions = surface_extensions(display)?;
        let ctx = Context::new(&desc)?;
        let size = window.inner_size();
        let samples = sample_count(&ctx, self.opts.msaa)?;
        let swapchain = Swapchain::new(&ctx, display, handle, (size.width, size.height), samples)?;
        let mut renderer = Renderer::multisampled(&ctx, swapchain.format, DEPTH_FORMAT, samples)?;
        // With multisampling the panel is drawn over the resolved image, without depth.
        let overlay_depth = (samples == vk::SampleCountFlags::TYPE_1).then_some(DEPTH_FORMAT);
        let overlay = Overlay::new(&ctx, swapchain.format, overlay_depth)?;
        let mut ui = Ui::new(&window, ctx.info.limits.max_image_dimension2_d as usize);
        ui.visible = self.opts.panel;
        let pool = CommandPool::new(&ctx, "window commands")?;
        // A device without line fill draws no wireframe (said when its capabilities are read).
        let wireframe = self.opts.wireframe && ctx.info.fill_mode_non_solid;
        let cmd = pool.allocate(1)?[0];
        let mesh = self.mesh.take().expect("created once");
        let cfg = self.opts.cfg;
        let a = self.opts.adaptive;
        let adaptive_max = a.max_level.unwrap_or_else(|| {
            let limit = crate::render::driver::shared_level_limit(&ctx);
            let max = limit.map_or(DEFAULT_MAX_LEVEL, |max| max.min(DEFAULT_MAX_LEVEL));
            1 << max.max(1).ilog2()
        });
        let mut scene = self.scene(&ctx, &pool, &renderer, &mesh, [cfg.level, adaptive_max])?;
        let extent = swapchain.extent;
        let aspect = extent.width as f32 / extent.height as f32;
        let gpu = (&ctx, &pool, &mut renderer);
        let start_camera = camera::start_camera(gpu, &mut scene, &cfg, &a.viewpoint, aspect)?;
        let mut rendered = Vec::new();
        per_image(&mut rendered, swapchain.images.len(), |i| {
            Semaphore::new(&ctx, &format!("rendered {i}"))
        })?;
        // Informational only: a closed or full stdout must not stop (or panic) the demo.
        let _ = writeln!(std::io::stdout().lock(), "{KEY_HELP}");
        let mut state = State {
            base_mesh: mesh,
            scene,
            queries: QueryPools::new(&ctx, 2)?,
            screenshot_buffer: None,
            cmd,
            fence: Fence::new(&ctx, true, "frame fence")?,
            acquired: Semaphore::new(&ctx, "acquired")?,
            rendered,
            renderer,
            overlay,
            pool,
            swapchain,
            ctx,
            window,
            ui,
            camera: start_camera,
            start_camera,
            viewing: self.opts.viewing,
            fullscreen: false,
            windowed_size,
            screenshot_note: None,
            mode_note: None,
            levels: None,
            level_cost: Default::default(),
            unmet_said: None,
            adaptive_level: None,
            frozen: None,
            measured_rates: Default::default(),
            last_drawn: None,
            warm: false,
            controls: Controls {
                cfg,
                wireframe,
                cage: self.opts.cage,
                animate: self.opts.animate,
                lod: self.opts.lod,
                lod_max: cfg.level,
                refused: None,
                dropped: None,
                view: self.opts.view,
                initial: cfg.params,
                submit: cfg.driver.submit().unwrap_or(self.opts.submit),
                adaptive: a.on,
                pixel_error: ui::slider_pixel_error(a.pixel_error),
                max_level: adaptive_max,
                cull: a.cull,
                freeze: false,
                background: self.opts.background,
                fullscreen: self.opts.fullscreen,
                asked: Asked::default(),
            },
            drawn: cfg,
            level_note: None,
            budget_note: None,
            frame_budget: self.opts.frame_budget,
            start: Instant::now(),
            frames: 0,
            recorded_once: false,
            resize: false,
            occluded: false,
            quit: false,
            drag: None,
            pan_drag: None,
            cursor: (0.0, 0.0),
            fps_window: (Instant::now(), 0),
            fps: 0.0,
            gpu_ms: 0.0,
        };
        state.apply_window_mode();
        Ok(state)
    }

    /// The window's scene: every power of two up to [`WINDOW_LEVELS`] and the `asked` levels
    /// as patterns, with the mesh's height map and tags.
    fn scene(
        &self,
        ctx: &Arc<Context>,
        pool: &CommandPool,
        renderer: &Renderer,
        mesh: &Mesh,
        asked: [u32; 2],
    ) -> Result<Scene> {
        let mut levels: Vec<u32> = (0..=WINDOW_LEVELS.trailing_zeros())
            .map(|s| 1 << s)
            .collect();
        levels.extend(asked);
        let patterns = crate::pattern::PatternSet::from_levels(&levels);
        let mut scene = Scene::with_patterns(ctx, pool, renderer, mesh.clone(), patterns)?;
        if let Some(map) = self.opts.heightmap.clone() {
            scene.set_heightmap(ctx, pool, renderer, map)?;
        }
        if let Some(tags) = self.opts.tags.clone() {
            scene.set_tags(ctx, pool, renderer, tags)?;
        }
        // The window keeps frames under a second itself (`fit_frame_budget`, `choose_levels`)
        // and says so in the panel.
        scene.skip_slow_warning();
        Ok(scene)
    }
}

impl State {
    /// One frame in named phases; false once the last frame asked for is shown.
    fn frame(&mut self, opts: &ViewOptions) -> Result<bool> {
        let size = self.window.inner_size();
        if size.width == 0 || size.height == 0 {
            return Ok(true); // minimised: pause rendering
        }
        self.finish_previous_frame((size.width, size.height))?;
        // The panel shows the last frame and may change the switches for this one; its textures
        // are uploaded now that the last frame is done with them.
        let ui_frame = self.run_ui();
        self.overlay.update_textures(&ui_frame.textures)?;
        let asked = std::mem::take(&mut self.controls.asked);
        self.apply_asked(&asked);
        self.advance_scene();
        let pipelines = self.renderer.pipeline_count();
        let (cfg, adaptive) = self.prepare_frame(opts)?;
        let compiled = self.renderer.pipeline_count() != pipelines;
        self.say_compiling(pipelines);
        let drawn = Some((cfg, self.controls.wireframe, adaptive));
        // A frame that made pipelines (a configuration, or a view, drawn for the first time)
        // compiles them at its draw: not warm, whatever it draws.
        self.warm = self.last_drawn == drawn && !compiled;
        self.last_drawn = drawn;
        let Some(image) = self.swapchain.acquire(self.acquired.raw)? else {
            self.resize = true;
            // The screenshot key's frame is the next one drawn.
            self.controls.asked.screenshot |= asked.screenshot;
            return Ok(true);
        };
        let last = self.quit || opts.frames.is_some_and(|n| self.frames + 1 >= u64::from(n));
        // `--screenshot` saves the last frame, the screenshot key this one (on the last frame
        // with `--screenshot` too, it is saved once, to `--screenshot`).
        let shot = match (last, &opts.screenshot) {
            (true, Some(path)) => Some((path.clone(), false)),
            _ => asked
                .screenshot
                .then(|| (draw::next_screenshot(opts.screenshot_dir.as_deref()), true)),
        };
        let screenshot = shot.is_some();
        self.record(&cfg, &image, &ui_frame, screenshot, adaptive)?;
        self.fence.reset()?;
        let rendered = &self.rendered[image.index as usize];
        self.pool
            .submit(self.cmd, &self.acquired, rendered, &self.fence)?;
        self.recorded_once = true;
        self.drawn = cfg;
        let stale = self.swapchain.present(image.index, rendered.raw)? || image.suboptimal;
        if stale {
            self.resize = true;
        }
        self.frames += 1;
        self.update_title(&cfg);
        if let Some((path, key)) = shot {
            self.fence.wait()?;
            self.saved_screenshot(&path, key)?;
        }
        Ok(!last)
    }

    /// Wait for the previous frame, read its GPU time, and rebuild the swapchain after a resize.
    fn finish_previous_frame(&mut self, size: (u32, u32)) -> Result<()> {
        self.fence.wait()?;
        if self.recorded_once {
            self.read_frame_times()?;
            self.measure_rate();
        }
        if self.resize {
            self.ctx.wait_idle()?;
            self.swapchain.recreate(size)?;
            // The new swapchain may have another image count: one `rendered` semaphore each.
            let ctx = &self.ctx;
            per_image(&mut self.rendered, self.swapchain.images.len(), |i| {
                Semaphore::new(ctx, &format!("rendered {i}"))
            })?;
            self.resize = false;
        }
        Ok(())
    }

    /// The CPU side of the frame: the animated mesh, and the level chosen by distance.
    fn advance_scene(&mut self) {
        if self.controls.animate {
            let t = self.start.elapsed().as_secs_f32();
            (self.scene).update_mesh(self.base_mesh.wobbled(t));
        }
        if self.controls.lod && !self.controls.adaptive {
            let (_, r) = self.scene.bounding_sphere();
            let (max, d) = (self.controls.lod_max, self.camera.distance);
            self.controls.cfg.level = self.scene.patterns.level_for_distance(d, r, max);
        } else {
            self.controls.lod_max = self.controls.cfg.level;
        }
    }

    /// The configuration this frame draws, prepared: at `adaptive_level` (adaptive mode's
    /// largest level) or the uniform level lowered to keep the frame under a second, lowered
    /// to what the driver can draw, and `pn` shown where Loop refuses the mesh.
    fn prepare_config(
        &mut self,
        opts: &ViewOptions,
        adaptive_level: Option<u32>,
    ) -> Result<DrawConfig> {
        let mut cfg = self.controls.cfg;
        self.limit_displacement(&mut cfg, opts);
        if let Some(l) = adaptive_level {
            cfg.level = l;
        }
        if let Err(e @ crate::render::RenderError::DriverLevel { max, .. }) =
            crate::render::driver::check_level(&self.ctx, &cfg)
        {
            // Show the finest level the driver can make rather than failing mid-demo, and say
            // why once per level asked for.
            if self.level_note != Some(cfg.level) {
                log::warn!("{e}: showing level {max}");
                self.level_note = Some(cfg.level);
            }
            cfg.level = self
                .scene
                .patterns
                .levels()
                .filter(|&l| l <= max)
                .last()
                .unwrap_or(1);
        }
        let wire = self.controls.wireframe;
        if adaptive_level.is_none() {
            self.fit_frame_budget(&mut cfg, wire);
        }
        let mut prepare = |cfg: &DrawConfig| {
            let none = crate::render::Capture::None;
            self.scene
                .prepare(&self.ctx, &self.pool, &mut self.renderer, cfg, none, wire)
        };
        let refused = opts
            .loop_refusal
            .as_ref()
            .filter(|_| cfg.surface.facts().needs_every_face);
        let prepared = match refused {
            Some(why) => Err(anyhow::anyhow!("{why}")),
            None => prepare(&cfg).map_err(anyhow::Error::from),
        };
        match prepared {
            // A mesh this surface cannot draw (Loop: non-manifold, or faces dropped at
            // loading): say so and show the fallback surface.
            Err(e) if cfg.surface != Surface::FALLBACK => {
                let fallback = Surface::FALLBACK;
                // Derived tags with three crease corners in a triangle (a tags file was checked
                // at loading): the command line splits such triangles when it starts with stpn
                // (src/cli/input.rs).
                let hint = match e.downcast_ref::<crate::render::RenderError>() {
                    Some(crate::render::RenderError::Tags(_)) => {
                        " (start the demo with --surface stpn, which splits such triangles)"
                    }
                    _ => "",
                };
                let file = format!("'{}'", opts.source);
                let e = e.to_string();
                let e = if e.contains(&file) {
                    e
                } else {
                    format!("{file}: {e}")
                };
                log::warn!("{e}{hint}: showing {} instead", fallback.name());
                self.controls.refused = Some(cfg.surface);
                cfg.surface = fallback;
                prepare(&cfg)?;
                self.controls.cfg.surface = fallback;
            }
            other => other?,
        }
        if self.controls.cage {
            self.scene.prepare_cage(&self.ctx, &mut self.renderer)?;
        }
        Ok(cfg)
    }
}

impl Drop for State {
    fn drop(&mut self) {
        let _ = self.ctx.wait_idle();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The swapchain recreated with more images than the first had: the frame indexes
    /// `rendered[image]` for every image (the bug: semaphores stayed at the first count).
    #[test]
    fn per_image_follows_the_image_count() {
        let mut made = 0;
        let mut v: Vec<usize> = Vec::new();
        per_image(&mut v, 2, |i| -> Result<usize, ()> {
            made += 1;
            Ok(i)
        })
        .unwrap();
        assert_eq!(v, [0, 1]);
        per_image(&mut v, 4, |i| -> Result<usize, ()> {
            made += 1;
            Ok(i)
        })
        .unwrap();
        assert_eq!(v, [0, 1, 2, 3]);
        assert_eq!(made, 4, "existing items are kept");
        per_image(&mut v, 3, |i| -> Result<usize, ()> { Ok(i) }).unwrap();
        assert_eq!(v, [0, 1, 2]);
        assert_eq!(next(&Surface::ALL, Surface::Stpn), Surface::Loop);
        assert_eq!(next(&Surface::ALL, Surface::Loop), Surface::Flat);
    }

    /// The keys the terminal's help names are the keys of docs/window.md's table (but for the
    /// table's aliases `=` and `_` of `+` and `-`).
    #[test]
    fn key_help_and_the_docs_keys_table_agree() {
        let mouse = ["left", "right", "middle", "drag", "wheel", "or"];
        let help: std::collections::BTreeSet<&str> = (KEY_HELP.trim_start_matches("keys: "))
            .split(", ")
            .flat_map(|entry| entry.split(" = ").next().unwrap().split(['/', ' ']))
            .filter(|k| !k.is_empty() && !mouse.contains(k))
            .collect();
        let doc = include_str!("../../docs/window.md");
        let table = doc.split("## Keys and mouse").nth(1).unwrap();
        let table = table.split("\n## ").next().unwrap();
        let documented: std::collections::BTreeSet<&str> = (table.lines())
            .filter(|l| l.starts_with("| ") && !l.starts_with("| input"))
            .flat_map(|l| l.split(" | ").next().unwrap().split('`').skip(1).step_by(2))
            .filter(|k| !["=", "_"].contains(k))
            .collect();
        assert_eq!(help, documented);
        for key in ["R", "Z", "Home", "B", "F11", "F12", "Esc", "[", "+"] {
            assert!(help.contains(key), "{key}");
        }
    }
}
