//! Adaptive levels for a camera: [`Scene::set_levels`] keeps the scene's level pass
//! ([`LevelPass`]) holding the bounds of the elements a configuration draws (computed on the CPU
//! once per mesh, surface, displacement and parameters, again when any of them changes or the
//! mesh animates) and the camera's [`LodView`]; a frame that carries [`Scene::level_pass`] in
//! `FrameWork::level_pass` has the GPU write every element's levels right before its draws
//! (docs/adaptivity.md, "Levels per frame"). What the levels draw is tallied with the pass's
//! CPU mirror (`lod::frame::frame_levels`), for the printed line, export's header and the
//! window's panel.

use super::static_adaptive::StaticLevels;
use super::{Camera, DrawConfig, LevelPass, RenderError, Scene};
use crate::gpu::vk;
use crate::lod::frame::{frame_levels, lod_records, LevelStats, LodRecord, LodView};
use crate::lod::levels::ElementLevels;
use crate::lod::{Frustum, LevelReport, Lod, View};
use crate::surface::{Displace, Surface, SurfaceParams};

/// The view adaptive levels are chosen for, in the scene's (drawn) coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LevelView {
    pub camera: Camera,
    /// The image's size in pixels (the metric counts pixels of `height`; `width` sets the
    /// frustum's aspect).
    pub width: u32,
    pub height: u32,
    /// The largest error allowed on screen, in pixels.
    pub pixel_error: f32,
    /// Cull elements outside the view frustum or, where a surface has a normal cone, facing
    /// away from the eye (their level becomes 0: nothing drawn).
    pub cull: bool,
}

/// What the bounds on the GPU were made from.
#[derive(Clone, Copy, Debug, PartialEq)]
struct BoundsKey {
    surface: Surface,
    displace: Displace,
    params: SurfaceParams,
    /// The per-build options (the normal field the direction bounds read among them).
    build: crate::surface::BuildOptions,
    /// The largest level (the height map's pyramid level follows it).
    max: u32,
    generation: u64,
    /// The levels buffer written (another mesh after a re-upload or Loop's faces).
    levels: vk::Buffer,
}

/// The scene's level pass, the bounds it holds and the camera of the last
/// [`Scene::set_levels`].
pub(super) struct SceneLevels {
    /// None where the device could not make it.
    pass: Option<LevelPass>,
    key: Option<BoundsKey>,
    records: Vec<LodRecord>,
    view: Option<(Surface, LodView)>,
}

impl Scene {
    /// Choose every element's levels for drawing `cfg` adaptively seen by `view` (`cfg.level`
    /// the largest; a power-of-two rounding for the pattern driver, integer for tess): the
    /// level pass's bounds are brought up to date and its camera kept for the frames that
    /// carry [`Scene::level_pass`], which write the levels on the GPU. Prepare the scene for
    /// `cfg` first (the loop surface's elements exist from then). Returns what the levels draw,
    /// from the pass's CPU mirror, inner levels counted as the driver draws them.
    ///
    /// Where the device cannot hold the pass's buffers, the mirror's levels are uploaded
    /// instead (the same levels; [`Scene::level_pass`] is then `None`) and a warning says so.
    pub fn set_levels(&mut self, cfg: &DrawConfig, view: &LevelView) -> LevelReport {
        let max = cfg.level;
        let dyadic = cfg.dyadic_levels();
        let eye = view.camera.eye();
        let metric = View::new(eye, view.camera.fov_y, view.height, view.pixel_error, max);
        let aspect = view.width as f32 / view.height.max(1) as f32;
        let frustum = Frustum::from_view_proj(view.camera.view_proj(aspect));
        let count = self.elements(cfg.surface).element_count;
        let lod_view = LodView::new(
            &metric,
            view.cull.then_some(&frustum),
            view.cull,
            dyadic,
            count,
        );
        let on_gpu = self.update_bounds(cfg);
        let levels = frame_levels(&lod_view, &self.levels.as_ref().expect("bounds").records);
        if cfg.driver.kind().refines_on_cpu() {
            // The static driver refines at the mirror's levels on the CPU: no level pass.
            let report = level_report(&levels, dyadic, max);
            let g = self.generation;
            self.static_levels = Some(StaticLevels::new(cfg, g, levels));
            if let Some(l) = &mut self.levels {
                l.view = None;
            }
            return report;
        }
        match on_gpu {
            Ok(()) => {
                let l = self.levels.as_mut().expect("bounds");
                l.view = Some((cfg.surface, lod_view));
            }
            Err(e) => {
                log::warn!("{e}: adaptive levels are chosen on the CPU instead");
                if let Some(l) = &mut self.levels {
                    l.view = None;
                }
                self.elements_mut(cfg.surface).upload_levels(&levels);
            }
        }
        level_report(&levels, dyadic, max)
    }

    /// The level pass and the camera of the last [`Scene::set_levels`], for
    /// `FrameWork::level_pass` of every adaptive frame drawn with `cfg`: `None` unless that call
    /// was for `cfg`'s elements, largest level and rounding (or the device could not hold the
    /// pass: the levels were uploaded).
    pub fn level_pass(&self, cfg: &DrawConfig) -> Option<(&LevelPass, LodView)> {
        let l = self.levels.as_ref()?;
        let key = l.key?;
        let (surface, view) = l.view?;
        let same = surface == cfg.surface
            && key.levels == self.elements(cfg.surface).levels.raw
            && view.max_level == cfg.level.max(1)
            && view.dyadic() == cfg.dyadic_levels()
            && !cfg.driver.kind().refines_on_cpu();
        same.then_some((l.pass.as_ref()?, view))
    }

    /// The levels the last adaptive frame drawn with `cfg` left in the mesh's levels buffer (the
    /// GPU's, read back: only once the frame is done), tallied as the driver draws them.
    pub fn drawn_levels(&self, cfg: &DrawConfig) -> (Vec<ElementLevels>, LevelReport) {
        let levels: Vec<ElementLevels> = self.elements(cfg.surface).levels.read_pod();
        let dyadic = cfg.dyadic_levels();
        let count = self.elements(cfg.surface).element_count as usize;
        let levels = levels[..count].to_vec();
        let report = level_report(&levels, dyadic, cfg.level);
        (levels, report)
    }

    /// The level pass's bounds for `cfg`, computed and uploaded when what they are made of
    /// changed. The bounds are kept on the CPU even when the upload fails (the mirror uses them).
    fn update_bounds(&mut self, cfg: &DrawConfig) -> Result<(), RenderError> {
        let mesh = self.elements(cfg.surface);
        let key = BoundsKey {
            surface: cfg.surface,
            displace: cfg.displace,
            params: cfg.params,
            build: cfg.build,
            max: cfg.level,
            generation: self.generation,
            levels: mesh.levels.raw,
        };
        if self.levels.as_ref().is_some_and(|l| l.key == Some(key)) {
            return Ok(());
        }
        let mut l = self.levels.take().unwrap_or(SceneLevels {
            pass: None,
            key: None,
            records: Vec::new(),
            view: None,
        });
        let records = {
            let lod = Lod::new(&self.mirror(cfg, cfg.level)?, &cfg.params);
            lod_records(&lod, self.records(cfg.surface))
        };
        l.key = None;
        l.records = records;
        let uploaded = match &mut l.pass {
            Some(pass) => pass.upload(self.elements(cfg.surface), &l.records),
            None => LevelPass::new(&self.ctx).and_then(|mut pass| {
                pass.upload(self.elements(cfg.surface), &l.records)?;
                l.pass = Some(pass);
                Ok(())
            }),
        };
        if uploaded.is_ok() {
            l.key = Some(key);
        }
        self.levels = Some(l);
        uploaded
    }
}

/// What `levels` draw on a driver that rounds as `dyadic` says, up to `max`.
fn level_report(levels: &[ElementLevels], dyadic: bool, max: u32) -> LevelReport {
    let stats = LevelStats::new(levels, dyadic, max);
    let uniform_level = stats.histogram.keys().max().copied().unwrap_or(1);
    let u = uniform_level as u64;
    LevelReport {
        histogram: stats.histogram,
        culled: stats.culled,
        adaptive_triangles: stats.triangles,
        uniform_level,
        uniform_triangles: levels.len() as u64 * u * u,
    }
}
