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

mod input;
mod ui;

use crate::gpu::sample_count;
use crate::gpu::{
    surface_extensions, vk, Buffer, BufferDesc, Cmd, CommandPool, Context, ContextDesc, Fence,
    Messages, Overlay, QueryPools, Semaphore, Swapchain, SwapchainFrame, DEPTH_FORMAT,
};
use crate::mesh::Mesh;
use crate::render::frame::{cmd_render, FrameWork, TargetView};
use crate::render::{
    software_frame_seconds, Camera, DrawConfig, FrameUniforms, Renderer, Scene, View,
};
use crate::surface::Surface;
use anyhow::{anyhow, Context as _, Result};
use raw_window_handle::{HasDisplayHandle, HasWindowHandle};
use std::io::Write as _;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;
use ui::{Controls, PanelInfo, Ui};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::window::Window;

/// The window system could not be opened (no reachable X server, say): callers may fall back
/// to a headless render.
#[derive(Debug, thiserror::Error)]
#[error("cannot connect to the display '{0}'")]
pub struct NoWindowSystem(pub String);

/// Options of `meshrefine view`.
#[derive(Clone, Debug)]
pub struct ViewOptions {
    pub cfg: DrawConfig,
    /// Exit after this many frames.
    pub frames: Option<u64>,
    /// Save the last frame here.
    pub screenshot: Option<PathBuf>,
    pub wireframe: bool,
    /// Start with the cage overlay (the coarse mesh's edges) on.
    pub cage: bool,
    pub animate: bool,
    /// Start with LOD by distance on.
    pub lod: bool,
    /// The height map (None: the generated one).
    pub heightmap: Option<crate::surface::Heightmap>,
    /// The scalar tags (None: derived from the mesh's hard edges).
    pub tags: Option<Vec<crate::surface::stpn::VertexTag>>,
    /// Why the loop surface must not subdivide this mesh though it loaded (the file had faces
    /// the loader dropped): switching to loop then warns with it and shows pn.
    pub loop_refusal: Option<String>,
    /// The mesh as the user named it, for messages.
    pub source: String,
    /// On a software device, lower what a frame draws to keep it under a second
    /// (`--no-frame-budget` turns it off: frames then draw what is asked, however slow).
    pub frame_budget: bool,
    /// Samples per pixel (`--msaa`; `None`: 4 where supported, else the most the device has).
    pub msaa: Option<u32>,
    /// Adaptive mode's starting settings, and whether the demo starts in it.
    pub adaptive: AdaptiveView,
}

/// Adaptive mode in the window: each element at the levels its bound needs for the current
/// camera and window size (`Scene::set_levels`), the largest level as `cfg.level`
/// (docs/window.md, "Adaptive mode").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptiveView {
    /// Start in adaptive mode (else uniform: every element at `cfg.level`).
    pub on: bool,
    pub pixel_error: f32,
    pub cull: bool,
    /// The first camera (drawn coordinates); None: the one that frames the mesh.
    pub camera: Option<Camera>,
    /// The largest level; None: [`DEFAULT_MAX_LEVEL`], or less where the tess driver cannot
    /// draw it.
    pub max_level: Option<u32>,
}

/// The pixel error adaptive mode starts with when none is given.
pub const DEFAULT_PIXEL_ERROR: f32 = 1.0;

/// The largest level adaptive mode starts with when none is given.
pub const DEFAULT_MAX_LEVEL: u32 = 64;

/// The window offers every power-of-two level up to this one (and the level it starts at):
/// `+` reaches it whatever the start level. A pattern of level 256 is 33,153 vertices.
pub const WINDOW_LEVELS: u32 = 256;

pub const KEY_HELP: &str = "keys: drag = orbit, wheel = zoom, 1/2/3 = static/pattern/tess, \
P/U/I = push/ubo/instanced, S = next surface, D = next displacement, N = normals view, \
+/- = level (max level when adaptive), M = adaptive/uniform, [/] = pixel error halve/double, \
C = culling, F = freeze levels, L = LOD by distance, W = wireframe, K = cage, A = animate, \
H = panel, Esc = quit";

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

/// Run the demo until the window closes (or `frames` frames). Returns the context's message list
/// so the caller can check validation and leaks after everything is dropped.
pub fn run(desc: ContextDesc, mesh: Mesh, opts: ViewOptions) -> Result<Arc<Messages>> {
    let event_loop = EventLoop::new().map_err(|e| {
        log::debug!("winit: {e}");
        let display = std::env::var("WAYLAND_DISPLAY")
            .or_else(|_| std::env::var("DISPLAY"))
            .unwrap_or_default();
        NoWindowSystem(display)
    })?;
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
            return Err(anyhow!(
                "the window system failed (was the window closed by another program?): {}",
                why.as_deref()
                    .and_then(|w| w.lines().last())
                    .unwrap_or("no reason given")
            ));
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
    controls: Controls,
    /// What the last frame drew (LOD and the tessellator's limit applied).
    drawn: DrawConfig,
    max_level: u32,
    /// The level last lowered to what the driver can draw (said once).
    level_note: Option<u32>,
    /// Set while the frame draws a lower level than asked, to keep frames under a second on a
    /// software device: what the panel says about it.
    budget_note: Option<String>,
    /// Whether the frame budget applies ([`ViewOptions::frame_budget`]).
    frame_budget: bool,
    /// Why adaptive mode draws this frame uniformly (the static driver, or a configuration the
    /// driver cannot draw adaptively): what the panel says about it.
    mode_note: Option<String>,
    /// The levels the last frame drew with, when it drew adaptively.
    levels: Option<crate::lod::LevelReport>,
    /// CPU time of choosing the last adaptive frame's levels, in milliseconds.
    level_ms: f64,
    /// The largest level the last adaptive frame drew (the frame budget may lower it).
    adaptive_level: Option<u32>,
    /// The camera and window size frozen levels are chosen for.
    frozen: Option<(Camera, vk::Extent2D)>,
    /// The slowest GPU time per refined triangle measured on a slow adaptive frame (over a
    /// quarter second) of this driver, surface and displacement, in nanoseconds.
    adaptive_rate: Option<(DrawConfig, f64)>,
    /// What the last frame drew (configuration, wireframe, adaptively), and whether the frame
    /// before drew the same: only then were its pipelines compiled before it (lavapipe compiles
    /// at the first draw, inside the frame's GPU time).
    last_drawn: Option<(DrawConfig, bool, bool)>,
    warm: bool,
    start: Instant,
    frames: u64,
    recorded_once: bool,
    resize: bool,
    /// Quit was asked for: the next frame is the last (and saves the screenshot).
    quit: bool,
    drag: Option<(f64, f64)>,
    cursor: (f64, f64),
    fps_window: (Instant, u64),
    fps: f64,
    gpu_ms: f64,
}

impl App {
    fn create(&mut self, event_loop: &ActiveEventLoop) -> Result<State> {
        let attrs = Window::default_attributes()
            .with_title("meshrefine")
            .with_inner_size(winit::dpi::LogicalSize::new(1280.0, 720.0));
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
        let renderer = Renderer::multisampled(&ctx, swapchain.format, DEPTH_FORMAT, samples)?;
        // With multisampling the panel is drawn over the resolved image, without depth.
        let overlay_depth = (samples == vk::SampleCountFlags::TYPE_1).then_some(DEPTH_FORMAT);
        let overlay = Overlay::new(&ctx, swapchain.format, overlay_depth)?;
        let ui = Ui::new(&window, ctx.info.limits.max_image_dimension2_d as usize);
        let pool = CommandPool::new(&ctx, "window commands")?;
        let cmd = pool.allocate(1)?[0];
        let mesh = self.mesh.take().expect("created once");
        let cfg = self.opts.cfg;
        let a = self.opts.adaptive;
        let adaptive_max = a.max_level.unwrap_or_else(|| {
            let limit = crate::render::Driver::Tess.kind().level_limit(&ctx);
            let max = limit.map_or(DEFAULT_MAX_LEVEL, |(max, _)| max.min(DEFAULT_MAX_LEVEL));
            1 << max.max(1).ilog2()
        });
        // Every power of two up to WINDOW_LEVELS (and the levels asked for), whatever the start.
        let max_level = cfg.level.max(adaptive_max).max(WINDOW_LEVELS);
        let mut levels: Vec<u32> = (0..=WINDOW_LEVELS.trailing_zeros())
            .map(|s| 1 << s)
            .collect();
        levels.push(cfg.level);
        levels.push(adaptive_max);
        let patterns = crate::pattern::PatternSet::from_levels(&levels);
        let mut scene = Scene::with_patterns(&ctx, &pool, &renderer, mesh.clone(), patterns)?;
        if let Some(map) = self.opts.heightmap.clone() {
            scene.set_heightmap(&ctx, &pool, &renderer, map)?;
        }
        if let Some(tags) = self.opts.tags.clone() {
            scene.set_tags(&ctx, &pool, &renderer, tags)?;
        }
        // The window keeps frames under a second itself (`fit_frame_budget`, `choose_levels`)
        // and says so in the panel.
        scene.skip_slow_warning();
        let (c, r) = scene.bounding_sphere();
        let mut rendered = Vec::new();
        per_image(&mut rendered, swapchain.images.len(), |i| {
            Semaphore::new(&ctx, &format!("rendered {i}"))
        })?;
        // Informational only: a closed or full stdout must not stop (or panic) the demo.
        let _ = writeln!(std::io::stdout().lock(), "{KEY_HELP}");
        Ok(State {
            base_mesh: mesh,
            scene,
            queries: QueryPools::new(&ctx, 1)?,
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
            camera: a.camera.unwrap_or_else(|| Camera::framing(c, r)),
            mode_note: None,
            levels: None,
            level_ms: 0.0,
            adaptive_level: None,
            frozen: None,
            adaptive_rate: None,
            last_drawn: None,
            warm: false,
            controls: Controls {
                cfg,
                wireframe: self.opts.wireframe,
                cage: self.opts.cage,
                animate: self.opts.animate,
                lod: self.opts.lod,
                view: View::Shaded,
                initial: cfg.params,
                submit: cfg.driver.submit().unwrap_or_default(),
                adaptive: a.on,
                pixel_error: a.pixel_error,
                max_level: adaptive_max,
                cull: a.cull,
                freeze: false,
            },
            drawn: cfg,
            max_level,
            level_note: None,
            budget_note: None,
            frame_budget: self.opts.frame_budget,
            start: Instant::now(),
            frames: 0,
            recorded_once: false,
            resize: false,
            quit: false,
            drag: None,
            cursor: (0.0, 0.0),
            fps_window: (Instant::now(), 0),
            fps: 0.0,
            gpu_ms: 0.0,
        })
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
        self.advance_scene();
        let (cfg, adaptive) = self.prepare_frame(opts)?;
        let drawn = Some((cfg, self.controls.wireframe, adaptive));
        self.warm = self.last_drawn == drawn;
        self.last_drawn = drawn;
        let Some(image) = self.swapchain.acquire(self.acquired.raw)? else {
            self.resize = true;
            return Ok(true);
        };
        let last = self.quit || opts.frames.is_some_and(|n| self.frames + 1 >= n);
        let screenshot = last && opts.screenshot.is_some();
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
        if screenshot {
            self.fence.wait()?;
            let path = opts.screenshot.as_ref().unwrap();
            self.save_screenshot(path)?;
            let _ = writeln!(std::io::stdout().lock(), "saved {}", path.display());
        }
        Ok(!last)
    }

    /// Wait for the previous frame, read its GPU time, and rebuild the swapchain after a resize.
    fn finish_previous_frame(&mut self, size: (u32, u32)) -> Result<()> {
        self.fence.wait()?;
        if self.recorded_once {
            self.gpu_ms = self.queries.gpu_ms(0)?;
            self.measure_adaptive_rate();
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
            // A wobble of 3% of the mesh's size, whatever its units.
            let (_, r) = self.scene.bounding_sphere();
            self.scene.update_mesh(
                self.base_mesh.animated(t, 0.03 * r),
                self.controls.cfg.surface,
            );
        }
        if self.controls.lod && !self.controls.adaptive {
            let (_, r) = self.scene.bounding_sphere();
            self.controls.cfg.level = self
                .scene
                .patterns
                .level_for_distance(self.camera.distance, r);
        }
    }

    /// The configuration this frame draws, prepared, and whether it draws adaptively (then
    /// with its levels chosen and uploaded): adaptive mode draws adaptively with the pattern
    /// and tess drivers where the driver can (`DriverKind::check_adaptive`), and otherwise
    /// uniformly, saying why in the panel.
    fn prepare_frame(&mut self, opts: &ViewOptions) -> Result<(DrawConfig, bool)> {
        self.mode_note = None;
        self.levels = None;
        if !self.controls.freeze {
            self.frozen = None;
        } else if self.frozen.is_none() {
            self.frozen = Some((self.camera, self.swapchain.extent));
        }
        if self.controls.adaptive {
            let driver = self.controls.cfg.driver;
            if driver == crate::render::Driver::Static {
                self.mode_note = Some(
                    "the static driver draws every element at one level (uniformly): 2 or 3 draws adaptively"
                        .to_string(),
                );
            } else {
                // Start from the largest level the last frame drew (the budget may have lowered
                // it): the pattern driver's adaptive draws are rebuilt only when it changes.
                let max = self.adaptive_max(driver);
                let guess = self.adaptive_level.map_or(max, |l| l.min(max));
                let cfg = self.prepare_config(opts, Some(guess))?;
                let cfg = self.choose_levels(opts, cfg, max)?;
                let kind = cfg.driver.kind();
                match kind.check_adaptive(&self.ctx, &self.scene, &cfg) {
                    Ok(()) => return Ok((cfg, true)),
                    Err(e) => {
                        self.levels = None;
                        self.mode_note = Some(format!("{e}: drawing uniformly"));
                    }
                }
            }
        }
        self.adaptive_level = None;
        Ok((self.prepare_config(opts, None)?, false))
    }

    /// The largest level adaptive mode asks of `driver`: the panel's, a power of two for the
    /// pattern driver (its hierarchical patterns split 1 to 4).
    fn adaptive_max(&self, driver: crate::render::Driver) -> u32 {
        let max = self.controls.max_level.max(1);
        match driver {
            crate::render::Driver::Pattern(_) => 1 << max.ilog2(),
            _ => max,
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
                log::warn!(
                    "'{}': {e}{hint}: showing {} instead",
                    opts.source,
                    fallback.name()
                );
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

    /// On a software device, lower `cfg.level` to the finest level whose frame the slower
    /// estimate ([`software_frame_seconds`]) puts under a second (the wireframe
    /// pass counted as a second draw), and say so in the panel: the window stays responsive
    /// whatever level is asked for. Other devices draw what is asked.
    fn fit_frame_budget(&mut self, cfg: &mut DrawConfig, wire: bool) {
        self.budget_note = None;
        if self.ctx.info.device_type != crate::gpu::vk::PhysicalDeviceType::CPU
            || !self.frame_budget
        {
            return;
        }
        let elements = self.scene.elements(cfg.surface).element_count as u64;
        let passes = if wire { 2 } else { 1 };
        let fits = |level: u32| {
            let mut c = *cfg;
            c.level = level;
            let refined = elements * c.refined_per_element() as u64 * passes;
            software_frame_seconds(refined).is_none()
        };
        if fits(cfg.level) {
            return;
        }
        let asked = cfg.level;
        cfg.level = self
            .scene
            .patterns
            .levels()
            .filter(|&l| l < asked && fits(l))
            .last()
            .unwrap_or(1);
        let note = format!(
            "level {asked} would take over a second a frame on this software device: drawing level {}",
            cfg.level
        );
        if self.level_note != Some(asked) {
            log::warn!("{note}");
            self.level_note = Some(asked);
        }
        self.budget_note = Some(note);
    }

    /// This frame's levels for `cfg` (prepared; the previous frame is done with the levels) up to
    /// `max`, seen by the camera and window (or the frozen ones), uploaded; on a software device
    /// the largest level lowered until the slower estimate of the adaptive triangles is under a
    /// second, said in the panel. Returns `cfg` at the largest level drawn, prepared.
    fn choose_levels(
        &mut self,
        opts: &ViewOptions,
        mut cfg: DrawConfig,
        max: u32,
    ) -> Result<DrawConfig> {
        let (camera, extent) = self.frozen.unwrap_or((self.camera, self.swapchain.extent));
        let view = crate::render::LevelView {
            camera,
            width: extent.width,
            height: extent.height,
            pixel_error: self.controls.pixel_error,
            cull: self.controls.cull,
        };
        let prepared = cfg.level;
        // What the bound asks for up to `max` (or the driver's limit), then the budget's cap.
        cfg.level = max.min(self.driver_max(&cfg));
        let t0 = Instant::now();
        let mut report = self.scene.set_levels(&cfg, &view);
        let level = self.fit_adaptive_budget(&cfg, &report);
        let mut seconds = t0.elapsed().as_secs_f64();
        if level != cfg.level {
            cfg.level = level;
            let t0 = Instant::now();
            report = self.scene.set_levels(&cfg, &view);
            seconds += t0.elapsed().as_secs_f64();
        }
        if cfg.level != prepared {
            cfg = self.prepare_config(opts, Some(cfg.level))?;
            if cfg.level != level {
                // Lowered again to what the driver draws: the levels must not exceed it.
                report = self.scene.set_levels(&cfg, &view);
            }
        }
        self.level_ms = seconds * 1e3;
        self.levels = Some(report);
        self.adaptive_level = Some(cfg.level);
        Ok(cfg)
    }

    /// The largest level the driver of `cfg` draws on this device among the window's levels.
    fn driver_max(&self, cfg: &DrawConfig) -> u32 {
        let limit = cfg.driver.kind().level_limit(&self.ctx).map(|(max, _)| max);
        (self.scene.patterns.levels())
            .filter(|&l| limit.is_none_or(|max| l <= max))
            .filter(|&l| {
                !matches!(cfg.driver, crate::render::Driver::Pattern(_)) || l.is_power_of_two()
            })
            .last()
            .unwrap_or(1)
    }

    /// After a slow adaptive frame (over a quarter second, so that the triangles dominate its
    /// time) drawn as the one before it (no pipeline compiled in it): its GPU time per refined triangle, kept if slower than the last one measured for
    /// the same driver, surface and displacement.
    fn measure_adaptive_rate(&mut self) {
        let d = self.drawn;
        if self.levels.is_none() || !self.warm || self.gpu_ms < 250.0 {
            return;
        }
        let coarse = self.scene.elements(d.surface).element_count as u64;
        let passes = if self.controls.wireframe { 2 } else { 1 };
        let triangles = self.refined(&d, coarse) * passes;
        if triangles == 0 {
            return;
        }
        let ns = self.gpu_ms * 1e6 / triangles as f64;
        let same =
            |c: &DrawConfig| (c.driver, c.surface, c.displace) == (d.driver, d.surface, d.displace);
        match &mut self.adaptive_rate {
            Some((c, rate)) if same(c) => *rate = rate.max(ns),
            other => *other = Some((d, ns)),
        }
    }

    /// On a software device, the largest level at most `cfg.level` whose adaptive frame (the
    /// elements of `report`, each at its inner level capped there; the wireframe pass counted
    /// as a second draw) the slower estimate (or the slower rate measured on this
    /// configuration's slow frames, adaptive frames being slower a triangle on lavapipe than
    /// the uniform ones the estimate comes from) puts under a second, said in the panel;
    /// `cfg.level` elsewhere.
    fn fit_adaptive_budget(&mut self, cfg: &DrawConfig, report: &crate::lod::LevelReport) -> u32 {
        if self.ctx.info.device_type != vk::PhysicalDeviceType::CPU || !self.frame_budget {
            return cfg.level;
        }
        let passes = if self.controls.wireframe { 2 } else { 1 };
        let measured = (self.adaptive_rate)
            .filter(|(c, _)| {
                (c.driver, c.surface, c.displace) == (cfg.driver, cfg.surface, cfg.displace)
            })
            .map_or(0.0, |(_, ns)| ns);
        let fits = |cap: u32| {
            let refined: u64 = (report.histogram.iter())
                .map(|(&n, &count)| count * cfg.driver.refined_per_element(n.min(cap)) as u64)
                .sum();
            software_frame_seconds(refined * passes).is_none()
                && (refined * passes) as f64 * measured * 1e-9 < 1.0
        };
        let asked = cfg.level;
        if fits(asked) {
            return asked;
        }
        let dyadic = cfg.dyadic_levels();
        let level = (self.scene.patterns.levels())
            .filter(|&l| l < asked && (!dyadic || l.is_power_of_two()) && fits(l))
            .last()
            .unwrap_or(1);
        let note = format!(
            "max level {asked} would take over a second a frame on this software device at {} px: drawing up to level {level}",
            self.controls.pixel_error
        );
        if self.level_note != Some(asked) {
            log::warn!("{note}");
            self.level_note = Some(asked);
        }
        self.budget_note = Some(note);
        level
    }

    /// The triangles `cfg` draws from `coarse` elements: at its level, or adaptively each drawn
    /// element at its inner level.
    fn refined(&self, cfg: &DrawConfig, coarse: u64) -> u64 {
        match &self.levels {
            Some(r) => (r.histogram.iter())
                .map(|(&n, &count)| count * cfg.driver.refined_per_element(n) as u64)
                .sum(),
            None => coarse * cfg.refined_per_element() as u64,
        }
    }

    /// Record the frame into `self.cmd`: the scene (adaptively when `adaptive`), the panel on
    /// top, and the screenshot copy.
    fn record(
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
        let uniforms =
            FrameUniforms::new(&self.camera, aspect, cfg, &self.scene, self.controls.view);
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
        let work = FrameWork {
            wireframe: self.controls.wireframe,
            adaptive,
            cage: self.scene.cage.as_ref().filter(|_| self.controls.cage),
            level_pass: self.scene.level_pass(cfg).filter(|_| adaptive),
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

    fn save_screenshot(&mut self, path: &std::path::Path) -> Result<()> {
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

    /// Lay out the overlay panel for this frame, with the last frame's statistics.
    fn run_ui(&mut self) -> ui::UiFrame {
        let levels: Vec<u32> = self.scene.patterns.levels().collect();
        let device = self.ctx.info.describe();
        let d = self.drawn;
        let coarse = self.scene.elements(d.surface).element_count as u64;
        let info = PanelInfo {
            device: &device,
            levels: &levels,
            wireframe_supported: self.renderer.wireframe_supported(),
            fps: self.fps,
            gpu_ms: self.gpu_ms,
            drawn: d,
            coarse,
            refined: self.refined(&d, coarse),
            geometry_bytes: self.scene.geometry_bytes(&d),
            upload_bytes: self.scene.upload_bytes(&d),
            table_bytes: self
                .scene
                .loop_
                .as_ref()
                .filter(|_| d.surface.uses_loop_faces())
                .map(|l| l.data.table_bytes()),
            has_texcoords: self.scene.data.uvs.is_some(),
            animating: self.controls.animate,
            note: self.budget_note.as_deref(),
            mode_note: self.mode_note.as_deref(),
            adaptive_rows: self
                .adaptive_summary(&d, coarse)
                .map(|a| a.rows())
                .unwrap_or_default(),
        };
        self.ui.run(&self.window, &mut self.controls, &info)
    }

    fn update_title(&mut self, cfg: &DrawConfig) {
        let (t0, n0) = self.fps_window;
        let dt = t0.elapsed().as_secs_f64();
        if dt < 0.5 {
            return;
        }
        self.fps = (self.frames - n0) as f64 / dt;
        self.fps_window = (Instant::now(), self.frames);
        let coarse = self.scene.elements(cfg.surface).element_count as u64;
        let bytes = self.scene.geometry_bytes(cfg);
        let c = &self.controls;
        let flags = format!(
            "{}{}{}",
            if c.wireframe { " wire" } else { "" },
            if c.cage { " cage" } else { "" },
            if c.animate { " animated" } else { "" },
        );
        if let Some(a) = self.adaptive_summary(cfg, coarse) {
            self.window.set_title(&format!(
                "meshrefine | {} {}{flags} | {:.0} fps | GPU {:.2} ms | {coarse} -> {} | {:.2} MB geometry",
                cfg.label(),
                a.mode(),
                self.fps,
                self.gpu_ms,
                a.counts(),
                bytes as f64 / 1e6,
            ));
            return;
        }
        self.window.set_title(&format!(
            "meshrefine | {} level {}{}{}{flags} | {:.0} fps | GPU {:.2} ms | {} -> {} triangles | {:.2} MB geometry | max level {}",
            cfg.label(),
            cfg.level,
            if c.lod && !c.adaptive { " (LOD)" } else { "" },
            // Adaptive mode that could not draw adaptively (the panel says why).
            if c.adaptive { " (uniform: adaptive mode off here)" } else { "" },
            self.fps,
            self.gpu_ms,
            coarse,
            self.refined(cfg, coarse),
            bytes as f64 / 1e6,
            self.max_level,
        ));
    }
}

impl State {
    /// What the last adaptive frame (drawing `cfg` of `coarse` elements) chose; None when it
    /// drew uniformly.
    fn adaptive_summary(&self, cfg: &DrawConfig, coarse: u64) -> Option<AdaptiveSummary> {
        let r = self.levels.as_ref()?;
        Some(AdaptiveSummary {
            pixel_error: self.controls.pixel_error,
            max_level: cfg.level,
            cull: self.controls.cull,
            frozen: self.frozen.is_some(),
            triangles: self.refined(cfg, coarse),
            uniform_level: r.uniform_level,
            uniform_triangles: coarse * cfg.driver.refined_per_element(r.uniform_level) as u64,
            histogram: compact_histogram(&r.histogram),
            culled: r.culled,
            level_ms: self.level_ms,
        })
    }
}

/// What an adaptive frame chose, for the panel and the title.
struct AdaptiveSummary {
    pixel_error: f32,
    max_level: u32,
    cull: bool,
    frozen: bool,
    /// Triangles drawn, each element at its inner level.
    triangles: u64,
    /// The smallest uniform level that meets the same bound (`LevelReport::uniform_level`),
    /// and the triangles every element makes there.
    uniform_level: u32,
    uniform_triangles: u64,
    histogram: String,
    culled: u64,
    /// CPU time of choosing the levels (`Scene::set_levels`).
    level_ms: f64,
}

impl AdaptiveSummary {
    /// `adaptive 1 px max level 64 cull on frozen`.
    fn mode(&self) -> String {
        format!(
            "adaptive {} px max level {} cull {}{}",
            self.pixel_error,
            self.max_level,
            if self.cull { "on" } else { "off" },
            if self.frozen { " frozen" } else { "" },
        )
    }

    /// How many fewer triangles than the uniform level (`4.2x`; `-` when nothing is drawn).
    fn ratio(&self) -> String {
        if self.triangles == 0 {
            return "-".to_string();
        }
        format!(
            "{:.1}x",
            self.uniform_triangles as f64 / self.triangles as f64
        )
    }

    /// The title's counts: triangles against the uniform level, levels, culling, cost.
    fn counts(&self) -> String {
        format!(
            "{} triangles, uniform level {} {} ({} fewer) | levels {} | culled {} | levels on the GPU, CPU mirror {:.1} ms",
            self.triangles,
            self.uniform_level,
            self.uniform_triangles,
            self.ratio(),
            self.histogram,
            self.culled,
            self.level_ms,
        )
    }

    /// The panel's rows.
    fn rows(&self) -> Vec<(&'static str, String)> {
        let mut rows = vec![
            (
                "uniform level",
                format!(
                    "{}: {} triangles, {}",
                    self.uniform_level,
                    self.uniform_triangles,
                    self.ratio()
                ),
            ),
            ("levels (level:n)", self.histogram.clone()),
            ("culled", self.culled.to_string()),
            ("choosing levels", format!("{:.2} ms (CPU)", self.level_ms)),
        ];
        if self.frozen {
            rows.push((
                "levels",
                "frozen: the camera moves, they do not".to_string(),
            ));
        }
        rows
    }
}

/// Elements per level in power-of-two ranges, ascending (`1:20 2:31 3-4:120 8:40`): the
/// dyadic levels one by one, the tessellator's integer levels compactly.
fn compact_histogram(histogram: &std::collections::BTreeMap<u32, u64>) -> String {
    // Per range's top: elements, and whether any level in it is not the top.
    let mut bins: std::collections::BTreeMap<u32, (u64, bool)> = Default::default();
    for (&n, &count) in histogram {
        let top = n.max(1).next_power_of_two();
        let bin = bins.entry(top).or_default();
        bin.0 += count;
        bin.1 |= n != top;
    }
    let pairs: Vec<String> = (bins.iter())
        .map(|(&top, &(count, range))| match range {
            false => format!("{top}:{count}"),
            true => format!("{}-{top}:{count}", top / 2 + 1),
        })
        .collect();
    if pairs.is_empty() {
        "none".to_string()
    } else {
        pairs.join(" ")
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

    /// Dyadic levels are shown one by one, integer levels in power-of-two ranges.
    #[test]
    fn histograms_are_compact() {
        let h = |pairs: &[(u32, u64)]| compact_histogram(&pairs.iter().copied().collect());
        assert_eq!(h(&[(1, 3), (2, 5), (4, 7), (8, 1)]), "1:3 2:5 4:7 8:1");
        assert_eq!(
            h(&[(3, 1), (4, 2), (5, 4), (11, 1), (64, 2)]),
            "3-4:3 5-8:4 9-16:1 64:2"
        );
        assert_eq!(h(&[]), "none");
    }
}
