//! Adaptive levels chosen on the CPU: [`Scene::set_levels`] computes every element's
//! [`ElementLevels`] for a camera with the `lod` module's bounds, metric and culling
//! (docs/adaptivity.md) and uploads them ([`GpuMesh::upload_levels`]), for the drivers to draw
//! with `FrameWork::adaptive`. The one entry point the command line calls; the level pass on the
//! GPU writes the same buffer.
//!
//! [`GpuMesh::upload_levels`]: super::GpuMesh::upload_levels

use super::{Camera, DrawConfig, Driver, Scene};
use crate::lod::levels::{drawn_level, ElementLevels};
use crate::lod::{Frustum, LevelReport, Lod, View};

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

impl Scene {
    /// Every element's levels for drawing `cfg` adaptively seen by `view`: each stored edge's
    /// level and the inner level from the surface's bounds (`Lod::edge`, `Lod::element`,
    /// `View::levels`), capped at `cfg.level`; culled elements keep their edges' levels (their
    /// neighbours share them) and get inner level 0. Uploaded to the elements `cfg` draws
    /// (prepare the scene for `cfg` first: the loop surface's elements exist from then); returns
    /// what was chosen, inner levels counted as the driver draws them (`drawn_level`).
    pub fn set_levels(&mut self, cfg: &DrawConfig, view: &LevelView) -> LevelReport {
        let max = cfg.level;
        let dyadic = matches!(cfg.driver, Driver::Pattern(_));
        let eye = view.camera.eye();
        let metric = View::new(eye, view.camera.fov_y, view.height, view.pixel_error, max);
        let aspect = view.width as f32 / view.height.max(1) as f32;
        let frustum = Frustum::from_view_proj(view.camera.view_proj(aspect));
        let mut report = LevelReport {
            uniform_level: 1,
            ..LevelReport::default()
        };
        let levels: Vec<ElementLevels> = {
            let inputs = self.inputs(max);
            let records = self.records(cfg.surface);
            let mut lod = Lod::new(cfg.surface, cfg.displace, &cfg.params, &inputs.element(0));
            (records.iter().enumerate())
                .map(|(t, rec)| {
                    lod.inputs = inputs.element(t);
                    let element = lod.element(rec);
                    let edges = [0, 1, 2].map(|e| lod.edge(rec, e));
                    let (edges, inner) = metric.levels(&element, &edges);
                    let culled = view.cull
                        && (frustum.outside(&element.sphere)
                            || element
                                .cone
                                .is_some_and(|c| c.back_facing(&element.sphere, eye)));
                    if culled {
                        report.culled += 1;
                        return ElementLevels { edges, inner: 0.0 };
                    }
                    let n = drawn_level(inner, dyadic, max);
                    *report.histogram.entry(n).or_default() += 1;
                    report.adaptive_triangles += n as u64 * n as u64;
                    report.uniform_level = report.uniform_level.max(n);
                    ElementLevels { edges, inner }
                })
                .collect()
        };
        let u = report.uniform_level as u64;
        report.uniform_triangles = levels.len() as u64 * u * u;
        self.elements_mut(cfg.surface).upload_levels(&levels);
        report
    }
}
