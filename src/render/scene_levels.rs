//! Adaptive levels for a camera: [`Scene::set_levels`] keeps the scene's level pass
//! ([`LevelPass`]) holding the bounds of the elements a configuration draws (computed on the CPU
//! once per mesh, surface, displacement and parameters, again when any of them changes or the
//! mesh animates) and the camera's [`LodView`]; a frame that carries [`Scene::level_pass`] in
//! `FrameWork::level_pass` has the GPU write every element's levels right before its draws
//! (docs/adaptivity.md, "Levels per frame"). What the levels draw is tallied with the pass's
//! CPU mirror (`lod::frame::frame_levels`), for the printed line, export's header and the
//! window's panel, when one of them reads it ([`ChosenLevels`]): a frame drawn on the GPU runs
//! no mirror. The static driver refines from the mirror's levels, so it runs it at once, and
//! its bounds stay on the CPU (no level pass).

use super::static_adaptive::StaticLevels;
use super::{Camera, DrawConfig, LevelPass, RenderError, Scene};
use crate::gpu::vk;
use crate::lod::cull::{eye_outside, eye_outside_spheres};
use crate::lod::frame::{
    culled_facing_away, frame_levels, lod_records, uniform_level, unmet, LevelStats, LodRecord,
    LodView, LIFT,
};
use crate::lod::levels::ElementLevels;
use crate::lod::{Frustum, LevelReport, Lod, View};
use crate::surface::{Displace, Surface, SurfaceParams};
use std::cell::OnceCell;
use std::sync::Arc;

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
    /// The height map's pyramid level the bounds read (`heightmap` only: it follows the
    /// largest level; no other bound depends on that level, so changing it alone keeps them).
    pyramid: Option<f32>,
    generation: u64,
    /// The levels buffer written (another mesh after a re-upload or Loop's faces).
    levels: vk::Buffer,
    /// Whether the driver's samples are lattice points, where the bounds depend on it
    /// (`loop`'s: src/surface/loop_bound.rs `aligned`).
    aligned: Option<(bool, bool)>,
}

/// The elements' spheres where no bounds are at hand ([`Scene::front_only`]): what they were
/// made from, and the last eye told outside them or not, with the answer.
pub(super) struct FrontSpheres {
    key: BoundsKey,
    spheres: Vec<crate::lod::Sphere>,
    outside: Option<(glam::Vec3, bool)>,
}

/// The scene's level pass, the bounds it holds and the camera of the last
/// [`Scene::set_levels`].
pub(super) struct SceneLevels {
    /// None where the device could not make it.
    pass: Option<LevelPass>,
    /// What the pass's bounds on the GPU were made from (None: nothing uploaded).
    key: Option<BoundsKey>,
    /// What `records` were made from.
    records_key: Option<BoundsKey>,
    records: Arc<[LodRecord]>,
    view: Option<(Surface, LodView)>,
    /// The last eye [`eye_outside`] answered for these records, and its answer.
    outside: Option<(glam::Vec3, bool)>,
}

/// What the levels of one [`Scene::set_levels`] draw: the [`LevelReport`] (it dereferences to
/// it), tallied from the level pass's CPU mirror the first time it is read. The mirror's inputs
/// are kept (a camera and shared bounds), so reading it later gives what `set_levels` chose.
pub struct ChosenLevels {
    mirror: Option<(LodView, Arc<[LodRecord]>)>,
    report: OnceCell<LevelReport>,
}

impl ChosenLevels {
    /// Levels already on the CPU (the static driver's, or uploaded instead of the pass).
    fn tallied(view: &LodView, records: &[LodRecord], levels: &[ElementLevels]) -> Self {
        Self {
            mirror: None,
            report: OnceCell::from(chosen_report(view, records, levels)),
        }
    }

    /// The report, the mirror run on the first call.
    pub fn report(&self) -> &LevelReport {
        self.report.get_or_init(|| {
            let (view, records) = self.mirror.as_ref().expect("a mirror or a tally");
            chosen_report(view, records, &frame_levels(view, records))
        })
    }

    /// Each element's levels, the mirror run again; `None` where they were tallied on the CPU
    /// and not kept (the static driver's, or uploaded instead of the pass).
    pub fn levels(&self) -> Option<Vec<ElementLevels>> {
        let (view, records) = self.mirror.as_ref()?;
        Some(frame_levels(view, records))
    }

    /// Whether the tally is made (read, or the levels were on the CPU already).
    pub fn is_tallied(&self) -> bool {
        self.report.get().is_some()
    }

    /// The report, owned.
    pub fn into_report(self) -> LevelReport {
        self.report();
        self.report.into_inner().expect("tallied")
    }
}

impl std::ops::Deref for ChosenLevels {
    type Target = LevelReport;

    fn deref(&self) -> &LevelReport {
        self.report()
    }
}

impl Scene {
    /// Choose every element's levels for drawing `cfg` adaptively seen by `view` (`cfg.level`
    /// the largest; a power-of-two rounding for the pattern driver, integer for tess): the
    /// level pass's bounds are brought up to date and its camera kept for the frames that
    /// carry [`Scene::level_pass`], which write the levels on the GPU. Prepare the scene for
    /// `cfg` first (the loop surface's elements exist from then). Returns what the levels draw,
    /// from the pass's CPU mirror (run when first read), inner levels counted as the driver
    /// draws them.
    ///
    /// Where the device cannot hold the pass's buffers, the mirror's levels are uploaded
    /// instead (the same levels; [`Scene::level_pass`] is then `None`) and a warning says so.
    /// The static driver refines at the mirror's levels: its bounds are not uploaded. Fails
    /// only where `cfg` cannot be drawn on this scene (its surface's inputs are missing), which
    /// [`Scene::prepare`] refuses first.
    pub fn set_levels(
        &mut self,
        cfg: &DrawConfig,
        view: &LevelView,
    ) -> Result<ChosenLevels, RenderError> {
        let max = cfg.level;
        let eye = view.camera.eye();
        let metric = View::new(eye, view.camera.fov_y, view.height, view.pixel_error, max);
        let aspect = view.width as f32 / view.height.max(1) as f32;
        let frustum = Frustum::from_view_proj(view.camera.view_proj(aspect));
        let count = self.elements(cfg.surface).element_count;
        let on_cpu = cfg.driver.kind().refines_on_cpu();
        let on_gpu = self.update_bounds(cfg, !on_cpu)?;
        let back_faces = view.cull && self.front_only(cfg, eye)?;
        let l = self.levels.as_mut().expect("update_bounds leaves bounds");
        let records = l.records.clone();
        let lod_view = LodView::new(
            &metric,
            view.cull.then_some(&frustum),
            back_faces,
            cfg.rounding(),
            count,
        )
        .with_lattice_bounds(cfg.surface.uses_loop_faces());
        if on_cpu {
            // The static driver refines at the mirror's levels on the CPU: no level pass.
            l.view = None;
            let levels = frame_levels(&lod_view, &records);
            let chosen = ChosenLevels::tallied(&lod_view, &records, &levels);
            // The levels view reads them, as it reads the pass's on the other drivers.
            self.elements_mut(cfg.surface).upload_levels(&levels);
            let g = self.generation;
            self.static_levels = Some(StaticLevels::new(cfg, g, levels));
            return Ok(chosen);
        }
        Ok(match on_gpu {
            Ok(()) => {
                // A mesh too large for the lift's buffer in one descriptor is not lifted: the
                // mirror then does without it too.
                let mut lod_view = lod_view;
                if !l.pass.as_ref().is_some_and(LevelPass::lifts) {
                    lod_view.flags &= !LIFT;
                }
                l.view = Some((cfg.surface, lod_view));
                ChosenLevels {
                    mirror: Some((lod_view, records)),
                    report: OnceCell::new(),
                }
            }
            Err(e) => {
                if !std::mem::replace(&mut self.cpu_levels_said, true) {
                    log::warn!(
                        "{e}; adaptive levels are chosen on the CPU instead, the same levels"
                    );
                }
                l.view = None;
                let levels = frame_levels(&lod_view, &records);
                self.elements_mut(cfg.surface).upload_levels(&levels);
                ChosenLevels::tallied(&lod_view, &records, &levels)
            }
        })
    }

    /// Whether only the front faces of `cfg`'s surface can be seen from `eye`: a closed surface
    /// seen from outside (outside the mesh and every element's bounds). An open one shows its
    /// back side (so does one with open seams, through their cracks, a `flat` one that folds
    /// through itself, and a displaced one, which may fold), and from inside the visible faces
    /// face away. Never for `loop`, whose limit surface the coarse mesh and its elements'
    /// bounds (around the limit surface) do not enclose between them: an eye outside both may
    /// be inside the surface. The level pass culls the elements facing away only then (those
    /// with a normal cone: none displaced, none of `loop`), and the wireframe the lines of
    /// faces turned away.
    pub fn front_only(&mut self, cfg: &DrawConfig, eye: glam::Vec3) -> Result<bool, RenderError> {
        let (mesh, cell) = (&self.data.mesh, &self.self_intersecting);
        if !self.closed || cfg.may_show_back_faces(|| *cell.get_or_init(|| mesh.self_intersects()))
        {
            return Ok(false);
        }
        // Computing the bounds, not uploading them, fails only as `Scene::prepare` would.
        let key = self.bounds_key(cfg);
        let current = |l: &SceneLevels| l.records_key == Some(key);
        if !self.levels.as_ref().is_some_and(current) {
            // Bounds not at hand (a uniform frame): the spheres alone, kept while what they are
            // made of stays (a still mesh seen from a moving camera), are much cheaper than
            // every bound (a moving mesh computes them every frame).
            if self.front_spheres.as_ref().is_none_or(|f| f.key != key) {
                let lod = Lod::new(&self.mirror(cfg, cfg.level)?, &cfg.params);
                let records = self.records(cfg.surface);
                let spheres: Option<Vec<_>> = (records.iter().enumerate())
                    .map(|(t, r)| lod.for_element(t).undisplaced_sphere(r))
                    .collect();
                self.front_spheres = spheres.map(|spheres| FrontSpheres {
                    key,
                    spheres,
                    outside: None,
                });
            }
            if let Some(f) = &mut self.front_spheres {
                return Ok(match f.outside {
                    Some((e, outside)) if e == eye => outside,
                    _ => {
                        let spheres = f.spheres.iter().copied();
                        let outside = eye_outside_spheres(eye, spheres, &self.data.mesh);
                        f.outside = Some((eye, outside));
                        outside
                    }
                });
            }
        }
        self.update_bounds(cfg, false)??;
        let l = self.levels.as_mut().expect("update_bounds leaves bounds");
        Ok(match l.outside {
            Some((e, outside)) if e == eye => outside,
            _ => {
                let outside = eye_outside(eye, &l.records, &self.data.mesh);
                l.outside = Some((eye, outside));
                outside
            }
        })
    }

    /// The bounds the last [`Scene::set_levels`] chose levels from (shared with the level
    /// pass's mirror): computed once per mesh, surface, displacement and parameters, and kept
    /// while only the camera, the pixel error or the largest level change.
    pub fn level_bounds(&self) -> Option<&Arc<[LodRecord]>> {
        self.levels.as_ref().map(|l| &l.records)
    }

    /// Bytes an adaptive frame drawing `cfg` uploads besides the coarse data when the coarse
    /// mesh moved (animation): the bounds the level pass reads, computed again on the CPU from
    /// the moved mesh ([`LodRecord`], 480 bytes an element), or, where the CPU chooses the
    /// levels (the static driver; a device that cannot hold the pass), the levels themselves
    /// ([`ElementLevels`], 16 bytes an element). Independent of the levels chosen.
    pub fn level_upload_bytes(&self, cfg: &DrawConfig) -> u64 {
        let per_element = if self.level_pass(cfg).is_some() {
            std::mem::size_of::<LodRecord>()
        } else {
            std::mem::size_of::<ElementLevels>()
        };
        self.elements(cfg.surface).element_count as u64 * per_element as u64
    }

    /// What an animated frame drawing `cfg` uploads (the window's panel): the coarse data
    /// ([`Scene::upload_bytes`]) and, for an adaptive frame, what its levels are chosen from
    /// ([`Scene::level_upload_bytes`]). The cage's lines, while it is drawn, add
    /// [`Scene::cage_upload_bytes`].
    pub fn animated_upload_bytes(&self, cfg: &DrawConfig, adaptive: bool) -> u64 {
        let levels = if adaptive {
            self.level_upload_bytes(cfg)
        } else {
            0
        };
        self.upload_bytes(cfg) + levels
    }

    /// What the cage overlay's lines upload when the mesh moved (two positions an edge), once
    /// the cage has been drawn; 0 before.
    pub fn cage_upload_bytes(&self) -> u64 {
        self.cage.as_ref().map_or(0, |c| c.upload_bytes())
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
            && view.rounding() == cfg.rounding()
            && !cfg.driver.kind().refines_on_cpu();
        same.then_some((l.pass.as_ref()?, view))
    }

    /// The levels the last adaptive frame drawn with `cfg` left in the mesh's levels buffer (the
    /// GPU's, read back: only once the frame is done), tallied as the driver draws them (the
    /// histogram and the culled elements; `set_levels`'s report has the uniform level).
    pub fn drawn_levels(&self, cfg: &DrawConfig) -> (Vec<ElementLevels>, LevelReport) {
        let levels: Vec<ElementLevels> = self.elements(cfg.surface).levels.read_pod();
        let dyadic = cfg.dyadic_levels();
        let count = self.elements(cfg.surface).element_count as usize;
        let levels = levels[..count].to_vec();
        let report = level_report(&levels, dyadic, cfg.level);
        (levels, report)
    }

    /// What the bounds of `cfg`'s elements are made from.
    fn bounds_key(&self, cfg: &DrawConfig) -> BoundsKey {
        BoundsKey {
            surface: cfg.surface,
            displace: cfg.displace,
            params: cfg.params,
            build: cfg.build,
            pyramid: (cfg.displace == Displace::Heightmap).then(|| self.heightmap_lod(cfg.level)),
            generation: self.generation,
            levels: self.elements(cfg.surface).levels.raw,
            aligned: (cfg.surface.uses_loop_faces())
                .then(|| crate::surface::loop_::bound::aligned(cfg.rounding())),
        }
    }

    /// The level pass's bounds for `cfg`, computed when what they are made of changed (the
    /// outer error: the surface's mirror cannot be built, nothing is changed), and uploaded then
    /// when `upload` (the inner error: the device could not hold them). The bounds are kept on
    /// the CPU even when the upload fails (the mirror uses them).
    fn update_bounds(
        &mut self,
        cfg: &DrawConfig,
        upload: bool,
    ) -> Result<Result<(), RenderError>, RenderError> {
        let key = self.bounds_key(cfg);
        let have = |l: &SceneLevels| l.records_key == Some(key) && (!upload || l.key == Some(key));
        if self.levels.as_ref().is_some_and(have) {
            return Ok(Ok(()));
        }
        let fresh = match &self.levels {
            Some(l) if l.records_key == Some(key) => None,
            _ => {
                let lod = Lod::new(&self.mirror(cfg, cfg.level)?, &cfg.params);
                Some(lod_records(
                    &lod.drawn_as(cfg.rounding()),
                    self.records(cfg.surface),
                ))
            }
        };
        let mut l = self.levels.take().unwrap_or(SceneLevels {
            pass: None,
            key: None,
            records_key: None,
            records: Arc::new([]),
            view: None,
            outside: None,
        });
        if let Some(records) = fresh {
            l.key = None;
            l.outside = None;
            l.records = records.into();
            l.records_key = Some(key);
        }
        if !upload {
            self.levels = Some(l);
            return Ok(Ok(()));
        }
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
        Ok(uploaded)
    }
}

/// What `levels`, chosen by `view` for `records`, draw, and where the pixel error is not met.
fn chosen_report(view: &LodView, records: &[LodRecord], levels: &[ElementLevels]) -> LevelReport {
    LevelReport {
        unmet: unmet(view, records, levels),
        uniform_level: uniform_level(view, records, levels),
        facing_away: culled_facing_away(view, records, levels),
        ..level_report(levels, view.dyadic(), view.max_level)
    }
}

/// What `levels` draw on a driver that rounds as `dyadic` says, up to `max`; without the
/// records, its uniform level is the largest level drawn ([`chosen_report`]'s is the smallest
/// uniform level meeting the bound).
fn level_report(levels: &[ElementLevels], dyadic: bool, max: u32) -> LevelReport {
    let stats = LevelStats::new(levels, dyadic, max);
    let uniform_level = stats.histogram.keys().max().copied().unwrap_or(1);
    LevelReport {
        histogram: stats.histogram,
        culled: stats.culled,
        uniform_level,
        ..LevelReport::default()
    }
}
