//! The camera's controls beyond orbit and zoom: pan (right or middle drag moves the orbit target
//! in the view plane), reset to the start framing (`R`), fit to the mesh (`Z`, `Home`), and the
//! camera as the title and the panel report it, in the mesh file's coordinates
//! (docs/window.md, "Keys and mouse").
#![forbid(unsafe_code)]

use crate::gpu::{CommandPool, Context};
use crate::render::{Camera, DrawConfig, Renderer, Scene, Viewpoint};
use glam::{DVec3, Vec3};
use std::sync::Arc;

/// Why the window cannot start from the viewpoint asked for.
const NO_DIRECTION: &str = "--eye and --look-at give no view direction with the camera that frames the surface: the eye is within 1e-4 radii of the surface of the point looked at";

/// The camera the demo starts with: the one default camera (render's), fitted to the surface
/// `cfg` draws at the field of view asked for, moved to the eye or point looked at given, the
/// other completed from it. For `loop` the scene is prepared first: its limit surface, which the
/// camera fits, exists once its M1 faces are made (where it cannot be drawn, the coarse
/// vertices frame it and the first frame says why).
pub(super) fn start_camera(
    (ctx, pool, renderer): (&Arc<Context>, &CommandPool, &mut Renderer),
    scene: &mut Scene,
    cfg: &DrawConfig,
    viewpoint: &Viewpoint,
    aspect: f32,
) -> anyhow::Result<Camera> {
    if cfg.surface.uses_loop_faces() {
        let _ = scene.prepare(
            ctx,
            pool,
            renderer,
            cfg,
            crate::render::Capture::None,
            false,
        );
    }
    (viewpoint.camera(&scene.framing_points(cfg), aspect))
        .ok_or_else(|| anyhow::anyhow!("{NO_DIRECTION}"))
}

/// The sphere (drawn coordinates) that fit-to-view frames and that pan keeps inside the depth
/// range: the coarse mesh's bounding sphere (the start camera fits the refined surface itself,
/// [`crate::render::Viewpoint`]).
pub(super) fn view_bounds(scene: &Scene) -> (Vec3, f32) {
    scene.bounding_sphere()
}

/// Move `camera`'s target in the view plane by a drag of `(dx, dy)` pixels in a window `height`
/// pixels high, so that what lies at the target's depth follows the pointer. The depth range
/// (the camera's radius around its target) grows to keep the sphere `bounds` inside it.
pub(super) fn pan(camera: &mut Camera, (dx, dy): (f32, f32), height: f32, bounds: (Vec3, f32)) {
    let forward = (camera.target - camera.eye()).normalize();
    // The image's own up (+Y, or the view's up looking straight down or up: `Camera::up`).
    let right = forward.cross(camera.up()).normalize();
    let up = right.cross(forward);
    let per_pixel = 2.0 * camera.distance * (camera.fov_y * 0.5).tan() / height.max(1.0);
    camera.target += (up * dy - right * dx) * per_pixel;
    let (centre, radius) = bounds;
    camera.radius = radius + (camera.target - centre).length();
}

/// `camera`'s eye and target in the mesh file's coordinates (drawn = (mesh − centre) · scale,
/// [`crate::mesh::Mesh::viewing_transform`]), as `render` takes them:
/// `--eye 1.2,0.4,2.1 --look-at 0,0.1,0`, with three decimals for a mesh of radius 1 (more
/// for smaller meshes, fewer for larger ones).
pub(super) fn camera_args(camera: &Camera, (centre, scale): (DVec3, f64)) -> String {
    let decimals = (3.0 + scale.log10().floor()).clamp(0.0, 12.0) as usize;
    let point = |p: Vec3| {
        let m = p.as_dvec3() / scale + centre;
        format!(
            "{:.*},{:.*},{:.*}",
            decimals, m.x, decimals, m.y, decimals, m.z
        )
    };
    format!(
        "--eye {} --look-at {}",
        point(camera.eye()),
        point(camera.target)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn project(camera: &Camera, p: Vec3, aspect: f32) -> glam::Vec2 {
        let c = camera.view_proj(aspect) * p.extend(1.0);
        glam::Vec2::new(c.x / c.w, c.y / c.w)
    }

    /// Fit-to-view keeps the direction, shows every point and comes close: from the framing
    /// direction it is the start camera's fit.
    #[test]
    fn fit_keeps_the_direction_and_shows_every_point() {
        let points: Vec<Vec3> = (0..20)
            .map(|i| {
                let t = i as f32 * 0.7;
                Vec3::new(t.sin() * 2.0, t.cos() * 0.5, (t * 1.3).sin()) + Vec3::X
            })
            .collect();
        let start = Camera::fit(&points, 16.0 / 9.0);
        let mut moved = start;
        moved.target += Vec3::new(1.0, 2.0, 3.0);
        moved.distance *= 3.0;
        assert_eq!(
            format!("{:?}", moved.fit_from(&points, 16.0 / 9.0)),
            format!("{start:?}")
        );
        moved.orbit(0.7, -0.3);
        for aspect in [16.0 / 9.0, 0.5] {
            let f = moved.fit_from(&points, aspect);
            assert_eq!((f.yaw, f.pitch), (moved.yaw, moved.pitch));
            let extent = points
                .iter()
                .map(|p| {
                    let q = project(&f, *p, aspect);
                    assert!(
                        q.x.abs() <= 1.0 && q.y.abs() <= 1.0,
                        "{q} outside at {aspect}"
                    );
                    q.abs().max_element()
                })
                .fold(0.0f32, f32::max);
            assert!(extent > 0.85, "{extent}: not close at {aspect}");
        }
    }

    /// A pan of (dx, dy) pixels moves the target's image by exactly that, and the depth range
    /// still holds the sphere.
    #[test]
    fn pan_moves_the_target_with_the_pointer() {
        let (c, r) = (Vec3::ZERO, 1.0);
        let mut orbited = Camera::framing(c, r);
        orbited.orbit(0.4, 0.2);
        // Looking straight down and straight up too, where the image's up is not +Y.
        let down = Camera::looking(Vec3::new(0.0, 3.0, 0.0), c, 0.8, r).unwrap();
        let up = Camera::looking(Vec3::new(0.0, -3.0, 0.0), c, 0.8, r).unwrap();
        for start in [orbited, down, up] {
            let mut cam = start;
            let (w, h) = (800.0, 600.0);
            let point = start.target;
            pan(&mut cam, (40.0, -30.0), h, (c, r));
            // The point that was at the centre is now 40 px right and 30 px up of it.
            let ndc = project(&cam, point, w / h);
            let px = glam::Vec2::new(ndc.x * w * 0.5, ndc.y * h * 0.5);
            assert!(
                (px - glam::Vec2::new(40.0, -30.0)).length() < 0.05,
                "{start:?}: {px}"
            );
            assert_eq!(
                (cam.yaw, cam.pitch, cam.distance),
                (start.yaw, start.pitch, start.distance)
            );
            assert!(cam.target.is_finite());
            let (near, far) = cam.depth_range();
            let d = (cam.eye() - c).length();
            assert!(near < d - r && far > d + r, "{near} {far} {d}");
        }
    }

    #[test]
    fn the_camera_is_reported_in_the_files_coordinates() {
        let cam = Camera::looking(Vec3::new(0.0, 0.0, 2.0), Vec3::ZERO, 0.8, 1.0).unwrap();
        let unit = camera_args(&cam, (DVec3::ZERO, 1.0));
        assert_eq!(unit, "--eye 0.000,0.000,2.000 --look-at 0.000,0.000,0.000");
        // A mesh of radius 100 around (10, 0, 0): drawn 1 is 100 in the file.
        let big = camera_args(&cam, (DVec3::new(10.0, 0.0, 0.0), 0.01));
        assert_eq!(big, "--eye 10.0,0.0,200.0 --look-at 10.0,0.0,0.0");
        // Read back as `render` reads them (`Camera::looking` in the drawn frame), they give
        // the camera again, to the decimals shown.
        let viewing = (DVec3::new(3.0, -1.0, 2.0), 0.5);
        let mut orbited = Camera::framing(Vec3::new(0.1, 0.2, 0.0), 1.0);
        orbited.orbit(0.9, -0.4);
        pan(&mut orbited, (25.0, 10.0), 600.0, (Vec3::ZERO, 1.0));
        let args = camera_args(&orbited, viewing);
        let numbers: Vec<Vec3> = (args.split(' '))
            .skip(1)
            .step_by(2)
            .map(|v| {
                let c: Vec<f64> = v.split(',').map(|x| x.parse().unwrap()).collect();
                ((DVec3::new(c[0], c[1], c[2]) - viewing.0) * viewing.1).as_vec3()
            })
            .collect();
        let back = Camera::looking(numbers[0], numbers[1], orbited.fov_y, 1.0).unwrap();
        assert!((back.eye() - orbited.eye()).length() < 1e-2, "{args}");
        assert!((back.target - orbited.target).length() < 1e-2, "{args}");
        assert!((back.yaw - orbited.yaw).abs() < 1e-2, "{args}");
        assert!((back.pitch - orbited.pitch).abs() < 1e-2, "{args}");
    }
}
