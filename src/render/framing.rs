//! The default camera frames what is drawn: the refined surface, displacement included, fitted
//! to the viewport ([`Scene::framing_camera`], [`Camera::fit`]).

use super::{Camera, DrawConfig, Scene};
use glam::Vec3;

/// About how many surface points [`Scene::framing_points`] evaluates at most (each element
/// gets at least its corners).
const FRAMING_SAMPLES: usize = 60_000;

/// The finest sampling level [`Scene::framing_points`] uses per element.
const FRAMING_MAX_LEVEL: usize = 8;

impl Scene {
    /// Points of the surface `cfg` draws (its surface, displacement and parameters, with the
    /// height map and tags the scene holds), evaluated by the CPU mirror on a uniform lattice of
    /// each element at a modest level (up to 8, fewer for large meshes): what
    /// [`Scene::framing_camera`] fits into the image. For `loop` before the scene was prepared
    /// for it (its M1 faces are made then), the coarse vertices: the limit surface lies in
    /// their convex hull.
    pub fn framing_points(&self, cfg: &DrawConfig) -> Vec<Vec3> {
        let loop_faces = cfg.surface.uses_loop_faces();
        if loop_faces && self.loop_.is_none() {
            return self.data.mesh.positions.clone();
        }
        let records = self.records(cfg.surface);
        let per_element = FRAMING_SAMPLES / records.len().max(1);
        // (n + 1)(n + 2) / 2 samples per element at level n.
        let n = (1..=FRAMING_MAX_LEVEL)
            .rev()
            .find(|n| (n + 1) * (n + 2) / 2 <= per_element)
            .unwrap_or(1);
        let Ok(mirror) = self.mirror(cfg, cfg.level) else {
            // What cannot be drawn (prepare says why) is framed by its coarse vertices.
            return self.data.mesh.positions.clone();
        };
        let mut points = Vec::with_capacity(records.len() * (n + 1) * (n + 2) / 2);
        for (t, rec) in records.iter().enumerate() {
            for i in 0..=n {
                for j in 0..=n - i {
                    let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
                    let b = [(n - i - j) as f32 / n as f32, u, v];
                    let p = mirror.eval(&cfg.params, t, rec, b).position;
                    if p.is_finite() {
                        points.push(p);
                    }
                }
            }
        }
        if points.is_empty() {
            return self.data.mesh.positions.clone();
        }
        points
    }

    /// The camera that shows all of what `cfg` draws ([`Scene::framing_points`]) in an image
    /// of `aspect` (width / height), from the usual direction ([`Camera::fit`]): the default
    /// camera of `render`, adaptive `export` and the window.
    pub fn framing_camera(&self, cfg: &DrawConfig, aspect: f32) -> Camera {
        Camera::fit(&self.framing_points(cfg), aspect)
    }
}
