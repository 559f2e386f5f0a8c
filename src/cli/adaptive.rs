//! Adaptive drawing from the command line (`--pixel-error`, `--max-level`, `--cull`, `--geomorph`, `--eye`,
//! `--look-at`, `--fov` on render, export, view and bench; `info` shares the checks and the
//! camera): the checks of the values, the camera in the drawn frame, and the levels for it
//! ([`Scene::set_levels`], written by the level pass on the GPU in every frame).
#![forbid(unsafe_code)]

use super::args::{AdaptiveOpts, Cli, Command, TypedF32, ViewpointOpts};
use super::numbers::TypedVec3;
use super::options::Given;
use crate::note;
use anyhow::{bail, Result};
use glam::{DVec3, Vec3};
use meshrefine::gpu::{Context, DeviceInfo};
use meshrefine::lod::LevelReport;
use meshrefine::render::{
    Camera, Capture, ChosenLevels, DrawConfig, Driver, Framing, Headless, LevelView, Scene,
    Viewpoint,
};
use meshrefine::surface::shown_number;

/// One sentence for the first bad value of a pixel error and its camera, before any work.
/// `level_given`: `--level` was given too.
pub fn check_view(px: &TypedF32, v: &ViewpointOpts, level_given: bool) -> Result<()> {
    check_pixel_error(px)?;
    if level_given {
        bail!("--pixel-error and --level are exclusive: adaptive levels come from the pixel error, --level asks for one level everywhere");
    }
    check_camera(v)
}

pub use meshrefine::lod::px;

/// The narrowest vertical field of view: narrower, single precision cannot place the view
/// frustum's planes (the image breaks up, culling fails).
pub const MIN_FOV: f32 = 0.01;

/// The camera's and the adaptive drawing's values of `cli`'s command, whether or not it reads
/// them (info without --pixel-error and a uniform export ignore them, with a warning after
/// this): the pixel error, a `--max-level` the command's driver cannot take as its largest
/// level (not for the window, whose keys switch drivers and which rounds it for each, nor for
/// bench, whose drivers are checked row by row), and the camera.
pub fn check_values(cli: &Cli) -> Result<()> {
    let (viewpoint, px, max_level, driver) = match &cli.command {
        Command::Render(a) => (
            &a.adaptive.viewpoint,
            &a.adaptive.pixel_error,
            a.adaptive.max_level,
            Some(a.technique.driver),
        ),
        Command::View(a) => (&a.adaptive.viewpoint, &a.adaptive.pixel_error, None, None),
        Command::Export(a) => (
            &a.adaptive.viewpoint,
            &a.adaptive.pixel_error,
            a.adaptive.max_level,
            Some(a.driver.driver()),
        ),
        Command::Bench(a) => (&a.adaptive.viewpoint, &a.adaptive.pixel_error, None, None),
        Command::Info(a) => (
            &a.camera.viewpoint,
            &a.pixel_error,
            Some(a.max_level),
            Some(a.driver),
        ),
        Command::Devices => return Ok(()),
    };
    if let Some(px) = px {
        check_pixel_error(px)?;
    }
    if let (Some(l), Some(driver)) = (max_level, driver) {
        check_max_level_rounding(l, driver)?;
    }
    check_camera(viewpoint)
}

/// One sentence for a pixel error that is not a finite number above zero.
pub fn check_pixel_error(px: &TypedF32) -> Result<()> {
    if !(px.value.is_finite() && px.value > 0.0) {
        bail!(
            "--pixel-error {} is not a finite number > 0{}",
            px.text,
            px.in_f32()
        );
    }
    Ok(())
}

/// One sentence for a bad `--fov`, an `--eye` or `--look-at` that is not finite, or an `--eye`
/// and `--look-at` with no view direction.
pub fn check_camera(v: &ViewpointOpts) -> Result<()> {
    for (name, p) in [("eye", &v.eye), ("look-at", &v.look_at)] {
        if let Some(p) = p {
            p.check(name).map_err(anyhow::Error::msg)?;
        }
    }
    let fov = v.fov.value;
    if !(fov.is_finite() && (MIN_FOV..180.0).contains(&fov)) {
        let inside = |x: f64| (MIN_FOV as f64..180.0).contains(&x);
        bail!(
            "--fov {} is not within [{MIN_FOV}, 180) degrees{}",
            v.fov.text,
            v.fov.in_f32_range(inside)
        );
    }
    if let (Some(e), Some(t)) = (&v.eye, &v.look_at) {
        let (eye, target) = (Vec3::from(e.value), Vec3::from(t.value));
        // In f64: points far apart (1e20) are a direction, though their distance leaves f32.
        let offset = eye.as_dvec3() - target.as_dvec3();
        let distance = offset.length();
        if !(distance > 0.0 && distance.is_finite()) {
            bail!(
                "{}",
                no_direction((eye, Some(&e.text)), (target, Some(&t.text)))
            );
        }
    }
    Ok(())
}

/// How far from the mesh `--eye` and `--look-at` may be, in bounding radii from the centre of
/// its bounding box: the camera is placed in single precision in the drawn frame (the mesh
/// centred, at unit radius), where farther points leave the range in which its distance and
/// view and projection matrices are computed.
pub const MAX_VIEWPOINT_RADII: f64 = 1e12;

/// One sentence for an `--eye` or `--look-at` farther from the mesh than
/// [`MAX_VIEWPOINT_RADII`] (`frame` maps the mesh to its drawn frame, where the bounding box's
/// centre is the origin and its half diagonal 1).
pub fn check_distance(v: &ViewpointOpts, frame: &Frame) -> Result<()> {
    for (name, p) in [("--eye", &v.eye), ("--look-at", &v.look_at)] {
        let Some(p) = p else { continue };
        let radii = ((Vec3::from(p.value).as_dvec3() - frame.centre) * frame.scale).length();
        if radii.is_nan() || radii > MAX_VIEWPOINT_RADII {
            bail!(
                "{name} {} is {radii:.1e} bounding radii from the mesh's centre: at most {MAX_VIEWPOINT_RADII:.0e} are supported",
                p.text
            );
        }
    }
    Ok(())
}

/// The sentence for a camera without a view direction: its eye and target, each as typed where
/// given (`Some(text)`) or the default camera's.
pub fn no_direction(
    (eye, eye_typed): (Vec3, Option<&str>),
    (target, target_typed): (Vec3, Option<&str>),
) -> String {
    let why = if eye == target {
        "they are the same point"
    } else {
        "they are too close together for one"
    };
    let name = |p: Vec3, typed: Option<&str>, option: &str, default: &str| match typed {
        Some(text) => format!("{option} {text}"),
        None => format!(
            "the default camera's {default} ({})",
            shown_point(p.to_array())
        ),
    };
    format!(
        "{} and {} give no view direction: {why}",
        name(eye, eye_typed, "--eye", "eye"),
        name(target, target_typed, "--look-at", "target")
    )
}

/// A point as an option takes it, each coordinate as [`shown_number`] writes it (`1e38`, not
/// its 39 digits).
fn shown_point(p: [f32; 3]) -> String {
    p.map(shown_number).join(",")
}

/// The adaptive options of `cli`'s command, checked: the pixel error and camera, and `--level`
/// (render, export, view) not given with it.
pub fn check(cli: &Cli, given: &Given) -> Result<()> {
    // render and view draw adaptively by default: their camera options are checked then too.
    let (opts, level, by_default): (&AdaptiveOpts, &str, bool) = match &cli.command {
        Command::Render(a) => (&a.adaptive, "level", !given.has("level")),
        Command::View(a) => (&a.adaptive, "level", !(given.has("level") || a.lod)),
        Command::Export(a) => (&a.adaptive, "level", false),
        Command::Bench(a) => (&a.adaptive, "levels", false),
        Command::Info(_) | Command::Devices => return Ok(()),
    };
    if let (Command::View(a), Some(_)) = (&cli.command, &opts.pixel_error) {
        if a.lod {
            bail!("--pixel-error and --lod are exclusive: --lod starts the window choosing one level by distance, --pixel-error each element's level from the pixel error");
        }
    }
    let Some(px) = &opts.pixel_error else {
        if by_default {
            check_view(&DEFAULT_PIXEL_ERROR.into(), &opts.viewpoint, false)?;
        } else if !matches!(cli.command, Command::Export(_)) {
            // Uniform render, view and bench draw from the camera asked for too.
            check_camera(&opts.viewpoint)?;
        }
        return Ok(());
    };
    // Every driver draws adaptively (static: refined on the CPU when the levels change).
    check_view(px, &opts.viewpoint, level == "level" && given.has("level"))?;
    Ok(())
}

/// The pattern driver's largest adaptive level without `--max-level`: its hierarchical
/// patterns up to 64 (docs/adaptivity.md) are a few megabytes; finer needs `--max-level`.
pub const PATTERN_MAX_LEVEL: u32 = 64;

/// The pixel error `render` and `view` draw at when neither `--pixel-error` nor `--level` is
/// given (the window's too): the bounds are 1.3 to 3.6 times the true chord error on most
/// surfaces (docs/adaptivity.md), so 1 px draws within about 0.55 to 0.7 px, which
/// looks right, at half the triangles of 0.5 px.
pub const DEFAULT_PIXEL_ERROR: f32 = meshrefine::app::DEFAULT_PIXEL_ERROR;

/// Adaptive drawing as asked on the command line, checked ([`check`]).
#[derive(Clone, Copy, Debug)]
pub struct Adaptive<'a> {
    pub opts: &'a AdaptiveOpts,
    pub pixel_error: f32,
    pub cull: bool,
    /// `--geomorph` (default on): `DrawConfig::geomorph`.
    pub geomorph: bool,
    /// Neither `--pixel-error` nor `--level` was given: where adaptive drawing cannot apply,
    /// the command draws at the uniform default level with a note instead of an error.
    pub by_default: bool,
}

impl AdaptiveOpts {
    /// `--geomorph` and `--max-level` as given.
    pub fn geomorph_asked(&self) -> (Option<bool>, Option<u32>) {
        (self.geomorph, self.max_level)
    }

    /// Adaptive drawing when `--pixel-error` was given, culling as `--cull` says or else
    /// `cull_default`.
    pub fn enabled(&self, cull_default: bool) -> Option<Adaptive<'_>> {
        self.pixel_error.as_ref().map(|px| Adaptive {
            opts: self,
            pixel_error: px.value,
            cull: self.cull.unwrap_or(cull_default),
            geomorph: self.geomorph.unwrap_or(true),
            by_default: false,
        })
    }

    /// `render` and the headless `view`: adaptive at `--pixel-error`, else at
    /// [`DEFAULT_PIXEL_ERROR`] unless `uniform` (`--level` given: one level everywhere),
    /// culling unless `--cull off` (elements facing away only on a closed mesh:
    /// [`Scene::closed`]).
    pub fn or_default(&self, uniform: bool) -> Option<Adaptive<'_>> {
        match self.enabled(true) {
            None if !uniform => Some(Adaptive {
                opts: self,
                pixel_error: DEFAULT_PIXEL_ERROR,
                cull: self.cull.unwrap_or(true),
                geomorph: self.geomorph.unwrap_or(true),
                by_default: true,
            }),
            a => a,
        }
    }
}

/// The map from the mesh's coordinates to the drawn ones (`p ↦ (p − centre) · scale`), as
/// `Mesh::for_viewing` moves a mesh.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    pub centre: DVec3,
    pub scale: f64,
}

impl Frame {
    pub fn drawn(&self, p: Vec3) -> Vec3 {
        ((p.as_dvec3() - self.centre) * self.scale).as_vec3()
    }

    pub fn mesh(&self, p: Vec3) -> Vec3 {
        (p.as_dvec3() / self.scale + self.centre).as_vec3()
    }
}

/// [`Adaptive::max_level`] on `device` with `--max-level` `given`.
fn max_level_on(device: &DeviceInfo, given: Option<u32>, driver: Driver) -> Result<u32> {
    let limit = driver.kind().level_limit(device);
    let pattern = !driver.kind().integer_levels();
    if let Some(l) = given {
        check_max_level(device, l, driver)?;
        return Ok(l);
    }
    let limit = limit.map_or(1024, |(max, _)| max.min(1024));
    Ok(if pattern {
        PATTERN_MAX_LEVEL.min(1 << limit.ilog2())
    } else {
        limit
    })
}

/// `--max-level l` for `driver` on `device`: within what the driver draws there (the one level
/// policy's sentence, `driver::check_level`, naming the option), and a power of two where its
/// adaptive levels are ([`check_max_level_rounding`]).
pub fn check_max_level(device: &DeviceInfo, l: u32, driver: Driver) -> Result<()> {
    let cfg = DrawConfig::new(driver, l);
    if let Err(e) = meshrefine::render::driver::check_level_on(device, &cfg) {
        bail!("--max-level {l}: {e}");
    }
    check_max_level_rounding(l, driver)
}

/// `--max-level l` for the pattern and static drivers must be a power of two (the pattern
/// driver's adaptive patterns, its hierarchy of 1-to-4 splits and its integer patterns beside
/// it, are built up to one; the static driver takes its levels), with or without geomorphing.
pub fn check_max_level_rounding(l: u32, driver: Driver) -> Result<()> {
    if !driver.kind().integer_levels() && !l.is_power_of_two() {
        let lower = 1u32 << l.ilog2();
        let why = if driver.kind().refines_on_cpu() {
            "it refines at the pattern driver's levels, whose patterns are built up to a power of two"
        } else {
            "its adaptive patterns are built up to a power of two, geomorphing or not"
        };
        bail!(
            "--max-level {l} is not a power of two, as the {} driver's largest level must be ({why}); use {lower} or {}",
            driver.name(),
            lower * 2
        );
    }
    Ok(())
}

impl Adaptive<'_> {
    /// The largest level any element gets: `--max-level` (refused past what `driver` draws on
    /// the device, and when not a power of two for a driver whose levels are, the pattern and
    /// static drivers), else the largest `driver` draws there, at most 1024; for the pattern
    /// and static drivers [`PATTERN_MAX_LEVEL`].
    pub fn max_level(&self, ctx: &Context, driver: Driver) -> Result<u32> {
        max_level_on(&ctx.info, self.opts.max_level, driver)
    }

    /// The camera in the drawn frame: the camera fitted to what `scene` draws with `cfg`
    /// ([`Scene::framing_points`]) in an image of `aspect` at `--fov`, moved to `--eye` and
    /// `--look-at` where given (mesh coordinates, mapped by `frame`).
    pub fn camera(
        &self,
        scene: &Scene,
        cfg: &DrawConfig,
        aspect: f32,
        frame: &Frame,
    ) -> Result<Camera> {
        (self.opts.viewpoint).camera(&scene.framing_points(cfg), aspect, frame)
    }

    /// Prepare `scene` for `cfg` (whose level is the largest), choose every element's levels
    /// for the camera and an image of `size`, and make `h` draw adaptively. Returns the camera
    /// (drawn frame) and what was chosen (tallied by the CPU mirror when read); the caller
    /// then fits the draws to the device ([`Adaptive::lower_to_fit`]).
    pub fn set_up(
        &self,
        h: &mut Headless,
        scene: &mut Scene,
        cfg: &DrawConfig,
        capture: Capture,
        (width, height): (u32, u32),
        frame: &Frame,
    ) -> Result<(Camera, ChosenLevels)> {
        scene.skip_slow_warning();
        h.adaptive = true;
        h.prepared_elements(scene, cfg, capture)?;
        let camera = self.camera(scene, cfg, width as f32 / height as f32, frame)?;
        let report = scene.set_levels(cfg, &self.level_view(camera, (width, height)))?;
        h.adaptive = true;
        Ok((camera, report))
    }

    /// What chooses the levels: the camera, an image of `size`, the pixel error and culling.
    pub fn level_view(&self, camera: Camera, (width, height): (u32, u32)) -> LevelView {
        LevelView {
            camera,
            width,
            height,
            pixel_error: self.pixel_error,
            cull: self.cull,
        }
    }

    /// Where the draws up to `cfg`'s largest level do not fit the device (millions of
    /// elements, or integer levels past their patterns' cap), those up to the largest level
    /// `report` chose may: the same levels, set again for `camera` and an image of `size` with
    /// `cfg` lowered to them (returned with them). `None`: `cfg` fits, or lowering does not help.
    /// The caller says where the levels miss the pixel error ([`Adaptive::note_unmet`]) once
    /// nothing else refuses them: no note on levels that are not drawn.
    #[allow(clippy::too_many_arguments)]
    pub fn lower_to_fit(
        &self,
        h: &mut Headless,
        scene: &mut Scene,
        cfg: &DrawConfig,
        capture: Capture,
        camera: Camera,
        size: (u32, u32),
        report: &ChosenLevels,
    ) -> Result<Option<(DrawConfig, ChosenLevels)>> {
        if cannot_adapt(h, scene, cfg, capture)?.is_none() {
            return Ok(None);
        }
        let Some(lowered) = chosen_max(cfg, report) else {
            return Ok(None);
        };
        if cannot_adapt(h, scene, &lowered, capture)?.is_some() {
            return Ok(None);
        }
        let report = scene.set_levels(&lowered, &self.level_view(camera, size))?;
        Ok(Some((lowered, report)))
    }

    /// Says on standard error where the pixel error is not met: elements with no finite error
    /// bound, and elements whose bound needs a level above the largest (`cfg.level`).
    pub fn note_unmet(&self, cfg: &DrawConfig, report: &LevelReport) {
        for line in report.unmet.notes(self.pixel_error, cfg.level) {
            note(format_args!("{line}"));
        }
    }

    /// The two lines that say what was drawn (export's header): the camera in mesh
    /// coordinates, the image size and pixel error, and the elements drawn at each level.
    pub fn header(
        &self,
        camera: &Camera,
        frame: &Frame,
        (width, height): (u32, u32),
        report: &LevelReport,
    ) -> [String; 2] {
        // The values given, exactly; the framing camera's mapped back to mesh coordinates.
        let v = &self.opts.viewpoint;
        let [ex, ey, ez] = (v.eye().unwrap_or(frame.mesh(camera.eye()).to_array())).map(px);
        let [tx, ty, tz] = (v.look_at().unwrap_or(frame.mesh(camera.target).to_array())).map(px);
        // +Y but looking (nearly) straight up or down (`Camera::up`).
        let [ux, uy, uz] = camera.up().to_array().map(px);
        [
            format!(
                "camera eye {ex} {ey} {ez} target {tx} {ty} {tz} up {ux} {uy} {uz} fov-y {} size {width} {height} pixel-error {}",
                self.opts.viewpoint.fov.value,
                px(self.pixel_error)
            ),
            format!("levels {}", report.histogram_line()),
        ]
    }
}

impl ViewpointOpts {
    /// `--eye` or `--look-at` was given: a camera placed by the user, not fitted.
    pub fn placed(&self) -> bool {
        self.eye.is_some() || self.look_at.is_some()
    }

    /// `--eye`'s point, where given.
    pub fn eye(&self) -> Option<[f32; 3]> {
        self.eye.as_ref().map(|p| p.value)
    }

    /// `--look-at`'s point, where given.
    pub fn look_at(&self) -> Option<[f32; 3]> {
        self.look_at.as_ref().map(|p| p.value)
    }

    /// The viewpoint asked for, in the drawn frame (`frame` maps the mesh's coordinates to it).
    pub fn drawn(&self, frame: &Frame) -> Viewpoint {
        Viewpoint {
            eye: self.eye().map(|e| frame.drawn(Vec3::from(e))),
            look_at: self.look_at().map(|t| frame.drawn(Vec3::from(t))),
            fov_y: self.fov.value.to_radians(),
        }
    }

    /// The camera (drawn frame) for an image of `aspect` showing `framing`, the surface as drawn
    /// (drawn frame): the default camera, fitted at `--fov`, moved to `--eye` and `--look-at`
    /// where given, the one not given completed from it ([`Viewpoint::camera`]).
    pub fn camera(&self, framing: &Framing, aspect: f32, frame: &Frame) -> Result<Camera> {
        check_distance(self, frame)?;
        let v = self.drawn(frame);
        let fitted = Camera::fit_with_fov(framing, aspect, v.fov_y);
        v.complete(fitted).ok_or_else(|| {
            anyhow::anyhow!(
                "{}",
                self.no_direction(frame.mesh(fitted.eye()), frame.mesh(fitted.target))
            )
        })
    }

    /// The sentence for a camera without a view direction ([`no_direction`]): `--eye` and
    /// `--look-at` as typed, where not given the fitted camera's `eye` or `target` (mesh
    /// coordinates).
    pub fn no_direction(&self, eye: Vec3, target: Vec3) -> String {
        fn given(p: &Option<TypedVec3>, fallback: Vec3) -> (Vec3, Option<&str>) {
            match p {
                Some(p) => (Vec3::from(p.value), Some(p.text.as_str())),
                None => (fallback, None),
            }
        }
        no_direction(given(&self.eye, eye), given(&self.look_at, target))
    }
}

/// Why `cfg`, its levels chosen, cannot be drawn adaptively in `scene` (prepared here for
/// `capture`), if it cannot (`DriverKind::check_adaptive`).
pub fn cannot_adapt(
    h: &mut Headless,
    scene: &mut Scene,
    cfg: &DrawConfig,
    capture: Capture,
) -> Result<Option<String>> {
    h.prepared_elements(scene, cfg, capture)?;
    let refusal = cfg.driver.kind().check_adaptive(&h.ctx, scene, cfg).err();
    Ok(refusal.map(|e| e.to_string()))
}

/// `cfg` at the largest level drawn among the levels of `report`, where that draws the same
/// below `cfg.level` ([`DrawConfig::lowered_to`]).
fn chosen_max(cfg: &DrawConfig, report: &ChosenLevels) -> Option<DrawConfig> {
    cfg.lowered_to(*report.report().histogram.keys().max()?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use meshrefine::gpu::vk;
    use meshrefine::render::Submit;

    /// A device whose tessellator draws up to `tess` segments an edge.
    fn device(tess: u32) -> DeviceInfo {
        DeviceInfo {
            name: "test".into(),
            driver_name: "test".into(),
            driver_info: String::new(),
            driver_id: vk::DriverId::MESA_LLVMPIPE,
            device_type: vk::PhysicalDeviceType::CPU,
            api_version: vk::API_VERSION_1_3,
            limits: vk::PhysicalDeviceLimits {
                max_tessellation_generation_level: tess,
                ..Default::default()
            },
            pipeline_statistics: false,
            vertex_stores: false,
            fill_mode_non_solid: false,
            depth_bias_clamp: false,
            max_memory_allocation_size: 1 << 30,
            transform_feedback: false,
            max_transform_feedback_buffer_size: 0,
        }
    }

    /// The default `--max-level` (docs/adaptivity.md): the tessellator's own limit, at most
    /// 1,024; 64 for the pattern and static drivers whatever the device; a level given is
    /// checked against the device.
    #[test]
    fn the_default_max_level_follows_the_driver_and_device() {
        let pattern = Driver::Pattern(Submit::Instanced);
        for (tess, want) in [(32, 32), (64, 64), (100, 100), (2048, 1024)] {
            let d = device(tess);
            assert_eq!(max_level_on(&d, None, Driver::Tess).unwrap(), want);
            assert_eq!(max_level_on(&d, None, pattern).unwrap(), PATTERN_MAX_LEVEL);
            assert_eq!(
                max_level_on(&d, None, Driver::Static).unwrap(),
                PATTERN_MAX_LEVEL
            );
        }
        assert_eq!(
            max_level_on(&device(32), Some(16), Driver::Tess).unwrap(),
            16
        );
        assert!(max_level_on(&device(32), Some(33), Driver::Tess).is_err());
        assert!(max_level_on(&device(32), Some(48), pattern).is_err());
    }
}
