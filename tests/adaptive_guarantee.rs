//! The pixel-error guarantee end to end on the GPU: Spot seen close up, levels written by the
//! level pass (`Scene::set_levels`, `FrameWork::level_pass`) and drawn adaptively by the
//! pattern driver's real pipelines, read back through the capture variant; every drawn
//! triangle (transition triangles and snapped boundary vertices included) is sampled at
//! interior and edge points, and the true surface there (the CPU mirror, `eval_with`) must be
//! within the pixel error of the triangle's linear interpolation of the captured corners,
//! counted in the metric's pixels (`d·K/|p − eye|`) wherever the sample is inside the view.
//!
//! Tolerance: 1e-3 relative on the bound (the captured corners equal the mirror's to a few ulp,
//! tests/adaptive_pattern.rs). Elements whose levels the largest level caps are skipped
//! (nothing is promised there). The check is shown not to be vacuous: levels chosen for half
//! the pixel error pass, levels chosen for twice the pixel error fail it.

mod common;

use common::{model, with_gpu};
use glam::{Vec3, Vec4};
use meshrefine::lod::View;
use meshrefine::pattern::adaptive::Hierarchy;
use meshrefine::render::{Camera, Capture, DrawConfig, Driver, Headless, LevelView, Scene, Submit};
use meshrefine::surface::{eval_with, Displace, Surface, SurfaceParams};

const MAX: u32 = 64;
const SIZE: (u32, u32) = (1920, 1080);

/// A camera close to Spot, looking past part of it (src/lod/tests/view.rs `close_camera`).
fn close_camera(scene: &Scene) -> Camera {
    let (c, r) = scene.bounding_sphere();
    let eye = c + Vec3::new(0.4, 0.25, 1.0).normalize() * (1.6 * r);
    let target = c + Vec3::new(0.7 * r, 0.2 * r, 0.0);
    Camera::looking(eye, target, 50f32.to_radians(), r).unwrap()
}

/// What the check found: elements checked, elements skipped as capped, the worst sample's
/// metric pixels.
struct Found {
    checked: usize,
    capped: usize,
    worst: f32,
}

/// Levels for `chosen_px`, drawn by `cfg`, captured, checked against `checked_px`'s metric.
fn draw_and_measure(
    h: &mut Headless,
    scene: &mut Scene,
    cfg: &DrawConfig,
    chosen_px: f32,
    checked_px: f32,
) -> Found {
    h.prepared_elements(scene, cfg, Capture::Vertices).unwrap();
    let camera = close_camera(scene);
    let (width, height) = SIZE;
    scene.set_levels(
        cfg,
        &LevelView {
            camera,
            width,
            height,
            pixel_error: chosen_px,
            cull: true,
        },
    );
    assert!(scene.level_pass(cfg).is_some(), "no level pass");
    h.adaptive = true;
    let cap = h.capture(scene, cfg, &camera).unwrap();
    h.adaptive = false;
    let (levels, _) = scene.drawn_levels(cfg);
    let eye = camera.eye();
    let metric = View::new(eye, camera.fov_y, height, checked_px, MAX);
    let vp = camera.view_proj(width as f32 / height as f32);
    let inside = |p: Vec3| {
        let c = vp * Vec4::new(p.x, p.y, p.z, 1.0);
        c.x.abs() <= c.w && c.y.abs() <= c.w && c.z >= 0.0 && c.z <= c.w
    };
    let pv = meshrefine::pattern::vertex_count(MAX) as usize;
    let records = scene.records(cfg.surface);
    let inputs = scene.inputs(MAX);
    let mut found = Found {
        checked: 0,
        capped: 0,
        worst: 0.0,
    };
    for (t, slots) in cap.vertices.chunks(pv).enumerate() {
        let Some(inner) = slots.iter().find(|v| v.position[3] == 1.0).map(|v| v.id[2]) else {
            continue; // culled
        };
        let l = levels[t];
        if l.inner >= MAX as f32 || l.edges.iter().any(|&e| e >= MAX as f32) {
            found.capped += 1;
            continue;
        }
        found.checked += 1;
        let at = |w: [f32; 3]| {
            let sp = eval_with(
                cfg.surface,
                cfg.displace,
                &cfg.params,
                &records[t],
                w,
                &inputs.element(t),
            );
            sp.position
        };
        for tri in Hierarchy::level_indices(MAX, inner).chunks_exact(3) {
            let v = [tri[0], tri[1], tri[2]].map(|i| &slots[i as usize]);
            assert!(
                v.iter().all(|v| v.position[3] == 1.0),
                "element {t}: corner not written"
            );
            let p = v.map(|v| Vec3::from_slice(&v.position[..3]));
            if p[0] == p[1] || p[1] == p[2] || p[2] == p[0] {
                continue; // welded by snapping: not drawn
            }
            let b = v.map(|v| [v.coord[0], v.coord[1], v.coord[2]]);
            for c in 0..=4u32 {
                for a in 0..=4 - c {
                    if [a, c, 4 - a - c].contains(&4) {
                        continue; // a corner
                    }
                    let w = [(4 - a - c) as f32, a as f32, c as f32].map(|x| x / 4.0);
                    let bary: [f32; 3] =
                        std::array::from_fn(|k| b[0][k] * w[0] + b[1][k] * w[1] + b[2][k] * w[2]);
                    let s = at(bary);
                    if !inside(s) {
                        continue;
                    }
                    let lin = p[0] * w[0] + p[1] * w[1] + p[2] * w[2];
                    let px = metric.pixels((s - lin).length(), s);
                    found.worst = found.worst.max(px);
                }
            }
        }
    }
    found
}

#[test]
fn drawn_adaptive_meshes_meet_the_pixel_error() {
    with_gpu(64, 36, |h| {
        let mut scene = h.scene(model("spot_control_tri.obj"), MAX).unwrap();
        let (_, r) = scene.bounding_sphere();
        let mut cfg = DrawConfig::new(Driver::Pattern(Submit::Instanced), MAX)
            .with_surface(Surface::Pn, Displace::None);
        cfg.params = SurfaceParams::for_radius(r);
        let tol = 1.0 + 1e-3;
        let at_1 = draw_and_measure(h, &mut scene, &cfg, 1.0, 1.0);
        eprintln!(
            "pattern at 1 px: {} elements checked, {} capped, worst {} px",
            at_1.checked, at_1.capped, at_1.worst
        );
        assert!(at_1.checked > 50, "only {} elements checked", at_1.checked);
        assert!(at_1.worst <= tol, "worst {} px", at_1.worst);
        // Not vacuous: the worst sample comes near the bound (powers of two can leave up to a
        // factor four), finer levels pass, coarser ones fail.
        assert!(at_1.worst > 0.05, "worst {} px", at_1.worst);
        let finer = draw_and_measure(h, &mut scene, &cfg, 0.5, 1.0);
        assert!(finer.worst <= 0.5 * tol, "worst {} px", finer.worst);
        // The bound is conservative (curvature bounds over whole elements, powers of two):
        // levels chosen for 2 and 4 px still draw within 1 px here, those for 8 px do not.
        for px in [2.0, 4.0] {
            let f = draw_and_measure(h, &mut scene, &cfg, px, 1.0);
            eprintln!("levels for {px} px, checked at 1 px: worst {} px", f.worst);
            assert!(f.worst <= px * tol, "worst {} px", f.worst);
        }
        let coarser = draw_and_measure(h, &mut scene, &cfg, 8.0, 1.0);
        eprintln!(
            "levels for 8 px, checked at 1 px: worst {} px",
            coarser.worst
        );
        assert!(
            coarser.worst > 1.0,
            "levels for 8 px met 1 px: the check sees nothing"
        );
    });
}
