//! The default camera frames what is drawn: the refined surface, displacement included, fitted
//! to the viewport ([`framing_points`], [`Scene::framing_camera`], [`Camera::fit`]). Every
//! command's default camera is this one (docs/architecture.md, "One frame path"); `info`, which
//! has no GPU scene, evaluates the same points with [`framing_points`].

use super::{Camera, DrawConfig, Scene};
use crate::lod::Sphere;
use crate::surface::bounds::DisplaceBound;
use crate::surface::{ElementRecord, Mirror, SurfaceParams};
use glam::{Vec3, Vec4};

/// About how many surface points [`framing_points`] evaluates at most (each element gets at
/// least its corners).
const FRAMING_SAMPLES: usize = 60_000;

/// The finest sampling level [`framing_points`] uses per element.
const FRAMING_MAX_LEVEL: usize = 8;

/// An element's reach: the sphere around its points without displacement (centred on their
/// bounding box), its radius this many times larger, grown by the displacement's largest height
/// there. The default camera keeps its eye outside it. It is meant to hold the element's
/// bounding sphere for its levels (around its control net, grown by the displacement's height),
/// so that no element holds the eye of a fitted camera: a margin checked on every test mesh,
/// surface and displacement (`tests/cli_camera.rs`), not a proven bound; an eye that still
/// lands in a sphere only costs that element its pixel-error guarantee, which render notes.
pub const REACH: f32 = 2.0;

/// What the default camera fits ([`Camera::fit_with_fov`]): the surface's points, and each
/// element's reach, a sphere (centre, radius) the eye stays outside.
#[derive(Clone, Debug, Default)]
pub struct Framing {
    pub points: Vec<Vec3>,
    pub reach: Vec<Vec4>,
}

impl Framing {
    /// Points with no element around them (no reach).
    pub fn points(points: Vec<Vec3>) -> Self {
        Self {
            points,
            reach: Vec::new(),
        }
    }
}

/// Points of the surface `mirror` evaluates with `params` on `records` (its elements), on a
/// uniform lattice of each element at a modest level (up to 8, fewer for large meshes): what
/// the default camera fits into the image, with each element's reach ([`REACH`]). `coarse` (the coarse vertices) where no point is finite.
pub fn framing_points(
    mirror: &Mirror,
    params: &SurfaceParams,
    records: &[ElementRecord],
    coarse: &[Vec3],
) -> Framing {
    let per_element = FRAMING_SAMPLES / records.len().max(1);
    // (n + 1)(n + 2) / 2 samples per element at level n.
    let n = (1..=FRAMING_MAX_LEVEL)
        .rev()
        .find(|n| (n + 1) * (n + 2) / 2 <= per_element)
        .unwrap_or(1);
    let mut points = Vec::with_capacity(records.len() * (n + 1) * (n + 2) / 2);
    let mut reach = Vec::with_capacity(records.len());
    let bound = mirror.displace().facts().bound;
    // The reach is around the surface without displacement, as the levels' spheres are.
    let displaced = !matches!(bound, DisplaceBound::Zero);
    let bare = SurfaceParams {
        amplitude: 0.0,
        ..*params
    };
    let mut own = Vec::with_capacity((n + 1) * (n + 2) / 2);
    for (t, rec) in records.iter().enumerate() {
        own.clear();
        for i in 0..=n {
            for j in 0..=n - i {
                let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
                let b = [(n - i - j) as f32 / n as f32, u, v];
                let p = mirror.eval(params, t, rec, b).position;
                if p.is_finite() {
                    points.push(p);
                }
                let q = if displaced {
                    mirror.eval(&bare, t, rec, b).position
                } else {
                    p
                };
                if q.is_finite() {
                    own.push(q);
                }
            }
        }
        if !own.is_empty() {
            let (lo, hi) = own
                .iter()
                .fold((own[0], own[0]), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
            let centre = (lo + hi) * 0.5;
            let radius = own
                .iter()
                .map(|p| (*p - centre).length())
                .fold(0.0, f32::max);
            let height = bound.max_height(params, &Sphere { centre, radius });
            reach.push(centre.extend(radius * REACH + height));
        }
    }
    if points.is_empty() {
        return Framing::points(coarse.to_vec());
    }
    Framing { points, reach }
}

impl Scene {
    /// Points of the surface `cfg` draws (its surface, displacement and parameters, with the
    /// height map and tags the scene holds, the height map read at `cfg.level`): [`framing_points`]
    /// of the scene's elements. For `loop` before the scene was prepared for it (its M1 faces
    /// are made then), the coarse vertices: the limit surface lies in their convex hull.
    pub fn framing_points(&self, cfg: &DrawConfig) -> Framing {
        let loop_faces = cfg.surface.uses_loop_faces();
        if loop_faces && self.loop_.is_none() {
            return Framing::points(self.data.mesh.positions.clone());
        }
        let Ok(mirror) = self.mirror(cfg, cfg.level) else {
            // What cannot be drawn (prepare says why) is framed by its coarse vertices.
            return Framing::points(self.data.mesh.positions.clone());
        };
        let records = self.records(cfg.surface);
        framing_points(&mirror, &cfg.params, records, &self.data.mesh.positions)
    }

    /// The camera that shows all of what `cfg` draws ([`Scene::framing_points`]) in an image
    /// of `aspect` (width / height), from the usual direction at 45 degrees ([`Camera::fit`]).
    pub fn framing_camera(&self, cfg: &DrawConfig, aspect: f32) -> Camera {
        Camera::fit_with_fov(&self.framing_points(cfg), aspect, 45f32.to_radians())
    }
}
