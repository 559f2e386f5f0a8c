//! What an animated frame uploads, counted where the bytes go ([`Context::host_bytes`]: every
//! write into a host-visible buffer and every push constant), not from the scene's own
//! accounting: on the GPU drivers the bytes per frame do not grow with the levels, and what
//! a moved mesh adds to a frame is what the window's panel reports
//! ([`Scene::animated_upload_bytes`]).
//!
//! [`Context::host_bytes`]: meshrefine::gpu::Context::host_bytes
//! [`Scene::animated_upload_bytes`]: meshrefine::render::Scene::animated_upload_bytes

mod common;

use common::{model, with_gpu};
use meshrefine::mesh::Mesh;
use meshrefine::render::tess::patches_per_draw;
use meshrefine::render::{Camera, Capture, DrawConfig, Driver, Headless, LevelView, Scene, Submit};
use meshrefine::surface::{Displace, Surface, SurfaceParams, RECORD_BYTES};

/// One frame as the window draws it, the mesh moved to `pose` first if one is given: the
/// bytes the CPU handed the device, and the level histogram drawn.
fn frame(
    h: &mut Headless,
    scene: &mut Scene,
    cfg: &DrawConfig,
    view: &LevelView,
    pose: Option<Mesh>,
) -> (u64, String) {
    let before = h.ctx.host_bytes();
    if let Some(mesh) = pose {
        scene.update_mesh(mesh);
    }
    h.prepared_elements(scene, cfg, Capture::None).unwrap();
    let chosen = scene.set_levels(cfg, view).unwrap();
    h.draw(scene, cfg, &view.camera).unwrap();
    let histogram = format!("{:?}", chosen.report().histogram);
    (h.ctx.host_bytes() - before, histogram)
}

/// Adaptive frames at `view`: one moved to a new pose (making what the view needs), a still
/// one and one moved again; the bytes of the still and the last one, whose difference is
/// checked to be the panel's figure, and the still frame's level histogram.
fn still_and_moved(
    h: &mut Headless,
    scene: &mut Scene,
    cfg: &DrawConfig,
    view: &LevelView,
    pose: &mut impl FnMut() -> Mesh,
) -> (u64, u64, String) {
    frame(h, scene, cfg, view, Some(pose()));
    let (still, levels) = frame(h, scene, cfg, view, None);
    let (moved, _) = frame(h, scene, cfg, view, Some(pose()));
    let what = format!("{:?} {}", cfg.driver, cfg.surface.name());
    assert_eq!(
        moved - still,
        scene.animated_upload_bytes(cfg, true),
        "{what} at {} px: the moved frame's bytes are not the panel's",
        view.pixel_error
    );
    (still, moved, levels)
}

/// A scene of Spot's control mesh, a configuration of `driver` for `surface` at largest level
/// 16, and the level view of a close camera at `pixel_error` (culling on).
fn close_up(
    h: &Headless,
    driver: Driver,
    surface: Surface,
) -> (
    Scene,
    DrawConfig,
    impl Fn(f32) -> LevelView,
    impl FnMut() -> Mesh,
) {
    let base = model("spot_control_tri.obj");
    let scene = h.scene(base.clone(), 16).unwrap();
    let (c, r) = scene.bounding_sphere();
    let mut cfg = DrawConfig::new(driver, 16).with_surface(surface, Displace::None);
    cfg.params = SurfaceParams::for_radius(r);
    let eye = c + glam::Vec3::new(0.3, 0.2, 1.2) * r;
    let camera = Camera::looking(eye, c, 0.8, r).unwrap();
    let view = move |pixel_error| LevelView {
        camera,
        width: 160,
        height: 90,
        pixel_error,
        cull: true,
    };
    // The window's animation, a new pose each call.
    let mut t = 0.0;
    let pose = move || {
        t += 0.3;
        base.wobbled(t)
    };
    (scene, cfg, view, pose)
}

/// The draws the tess driver records for `cfg` uniformly (none for the other drivers).
fn tess_draws(h: &Headless, scene: &Scene, cfg: &DrawConfig) -> u64 {
    if cfg.driver != Driver::Tess {
        return 0;
    }
    let mesh = scene.elements(cfg.surface);
    let per_draw = patches_per_draw(&h.ctx, cfg.level, mesh.element_count, false);
    let chunks = mesh.chunks(0..mesh.element_count);
    chunks
        .iter()
        .map(|c| c.count.div_ceil(per_draw) as u64)
        .sum()
}

/// On every GPU driver and submission, adaptive and uniform, for a local surface and Loop: a
/// still frame and a moved one upload the same bytes at two pixel errors sixteen times apart
/// (other levels, checked); at two uniform levels a moved frame adds the same bytes; and the
/// moved frame adds exactly what the panel says.
#[test]
fn an_animated_frame_uploads_the_same_bytes_whatever_the_levels() {
    with_gpu(160, 90, |h| {
        let drivers = [
            (Driver::Pattern(Submit::Push), Surface::Pn),
            (Driver::Pattern(Submit::Ubo), Surface::Phong),
            (Driver::Pattern(Submit::Instanced), Surface::Pn),
            (Driver::Tess, Surface::Pn),
            (Driver::Pattern(Submit::Instanced), Surface::Loop),
            (Driver::Tess, Surface::Loop),
        ];
        for (driver, surface) in drivers {
            let (mut scene, cfg, view, mut pose) = close_up(h, driver, surface);
            let what = format!("{driver:?} {}", surface.name());
            // Adaptive: the first frame at each pixel error makes what it needs; then a still
            // frame and a moved one.
            h.adaptive = true;
            let mut seen = Vec::new();
            for pixel_error in [4.0, 0.25] {
                let (still, moved, levels) =
                    still_and_moved(h, &mut scene, &cfg, &view(pixel_error), &mut pose);
                seen.push((still, moved, levels));
            }
            assert_ne!(
                seen[0].2, seen[1].2,
                "{what}: the same levels at both errors"
            );
            assert_eq!(
                (seen[0].0, seen[0].1),
                (seen[1].0, seen[1].1),
                "{what}: the bytes per frame follow the levels"
            );
            // Uniform: levels 2 and 16.
            h.adaptive = false;
            let mut uniform = Vec::new();
            for level in [2, 16] {
                let cfg = DrawConfig { level, ..cfg };
                let v = view(1.0);
                h.draw(&mut scene, &cfg, &v.camera).unwrap();
                let bytes = |h: &mut Headless, scene: &mut Scene, pose: Option<Mesh>| {
                    let before = h.ctx.host_bytes();
                    if let Some(mesh) = pose {
                        scene.update_mesh(mesh);
                    }
                    h.draw(scene, &cfg, &v.camera).unwrap();
                    h.ctx.host_bytes() - before
                };
                let still = bytes(h, &mut scene, None);
                let moved = bytes(h, &mut scene, Some(pose()));
                assert_eq!(
                    moved - still,
                    scene.animated_upload_bytes(&cfg, false),
                    "{what} at level {level}: the moved frame's bytes are not the panel's"
                );
                uniform.push((still, moved));
            }
            // A moved mesh adds the same bytes at every level; a still frame's bytes differ
            // only by the tessellated draws' parameters (16 bytes a draw), as lavapipe's tess
            // draws are split by level ([`patches_per_draw`]).
            //
            // [`patches_per_draw`]: meshrefine::render::tess::patches_per_draw
            let added = |(still, moved): (u64, u64)| moved - still;
            assert_eq!(added(uniform[0]), added(uniform[1]), "{what}");
            let draw_bytes =
                |level| 16 * tess_draws(h, &scene, &DrawConfig { level, ..cfg }) as i64;
            assert_eq!(
                uniform[1].0 as i64 - uniform[0].0 as i64,
                draw_bytes(16) - draw_bytes(2),
                "{what}: a uniform frame's bytes follow the level"
            );
        }
    });
}

/// The static driver, the CPU baseline, refines on the CPU and uploads the refined vertices
/// when the mesh moves: the counter sees more bytes for finer levels, and a moved frame adds
/// what the panel says (the refined vertices, the levels chosen, and the coarse records only
/// where the fragments evaluate the normal field: `pn` with its quadratic normals, not
/// `phong`), adaptively and uniformly; a still frame uploads neither vertices nor levels.
#[test]
fn the_static_driver_uploads_more_for_finer_levels() {
    with_gpu(160, 90, |h| {
        for surface in [Surface::Pn, Surface::Phong] {
            let (mut scene, cfg, view, mut pose) = close_up(h, Driver::Static, surface);
            let what = surface.name();
            h.adaptive = true;
            let mut moved_bytes = Vec::new();
            for pixel_error in [4.0, 0.25] {
                let (still, moved, _) =
                    still_and_moved(h, &mut scene, &cfg, &view(pixel_error), &mut pose);
                assert!(still < 1024, "{what}: a still frame uploads {still} bytes");
                moved_bytes.push(moved);
            }
            assert!(
                moved_bytes[1] > 2 * moved_bytes[0],
                "{what}: finer levels, not more bytes: {moved_bytes:?}"
            );
            let records = scene.elements(surface).element_count as u64 * RECORD_BYTES as u64;
            let fragment_field = cfg.fragment_normal_field();
            assert_eq!(fragment_field, surface == Surface::Pn);
            let levels = scene.level_upload_bytes(&cfg);
            let refined = scene.static_vbo.as_ref().unwrap().adaptive.clone().unwrap();
            assert_eq!(
                scene.animated_upload_bytes(&cfg, true),
                refined.upload_bytes + levels + if fragment_field { records } else { 0 },
                "{what}"
            );
            // Uniform at levels 2 and 8: the refined mesh again, each time it moves.
            h.adaptive = false;
            let mut uniform = Vec::new();
            for level in [2, 8] {
                let cfg = DrawConfig { level, ..cfg };
                let camera = view(1.0).camera;
                h.draw(&mut scene, &cfg, &camera).unwrap();
                let before = h.ctx.host_bytes();
                h.draw(&mut scene, &cfg, &camera).unwrap();
                let still = h.ctx.host_bytes() - before;
                scene.update_mesh(pose());
                h.draw(&mut scene, &cfg, &camera).unwrap();
                let moved = h.ctx.host_bytes() - before - still;
                let panel = scene.animated_upload_bytes(&cfg, false);
                assert_eq!(moved - still, panel, "{what} at level {level}");
                uniform.push(moved);
            }
            assert!(uniform[1] > 4 * uniform[0], "{what}: {uniform:?}");
        }
    });
}

/// What a moved mesh uploads for what is not drawn waits until it is: after `loop` has been
/// drawn, a `pn` frame does not upload M0's positions; the cage's lines go up only while it is
/// drawn (the panel adds them); and a scene moved while the static driver drew `phong` (no
/// records uploaded) and `loop` (no M0), then drawn by the pattern driver as `phong`, `pn` and
/// `loop`,
/// evaluates exactly the vertices a scene made from the moved mesh does.
#[test]
fn what_is_not_drawn_is_uploaded_when_it_is() {
    with_gpu(160, 90, |h| {
        let instanced = Driver::Pattern(Submit::Instanced);
        let (mut scene, loop_cfg, view, mut pose) = close_up(h, instanced, Surface::Loop);
        let v = view(1.0);
        h.adaptive = true;
        frame(h, &mut scene, &loop_cfg, &v, None);
        let pn = DrawConfig {
            surface: Surface::Pn,
            ..loop_cfg
        };
        still_and_moved(h, &mut scene, &pn, &v, &mut pose);
        let panel = scene.animated_upload_bytes(&pn, true);
        // The cage: its lines when it is drawn, not before.
        assert_eq!(scene.cage_upload_bytes(), 0);
        h.cage = true;
        frame(h, &mut scene, &pn, &v, None);
        let lines = scene.cage_upload_bytes();
        assert!(lines > 0);
        let (still, _) = frame(h, &mut scene, &pn, &v, None);
        let (moved, _) = frame(h, &mut scene, &pn, &v, Some(pose()));
        assert_eq!(moved - still, panel + lines, "the cage's lines");
        h.cage = false;
        let (still, _) = frame(h, &mut scene, &pn, &v, None);
        let (moved, _) = frame(h, &mut scene, &pn, &v, Some(pose()));
        assert_eq!(moved - still, panel, "a hidden cage's lines");

        // Moved while static draws phong, then loop: the records and M0 wait.
        h.adaptive = false;
        let camera = v.camera;
        let moved_mesh = pose();
        scene.update_mesh(moved_mesh.clone());
        for surface in [Surface::Phong, Surface::Loop] {
            let st = DrawConfig {
                driver: Driver::Static,
                level: 2,
                ..pn
            }
            .with_surface(surface, Displace::None);
            h.draw(&mut scene, &st, &camera).unwrap();
        }
        let mut fresh = h.scene(moved_mesh, 16).unwrap();
        for surface in [Surface::Phong, Surface::Pn, Surface::Loop] {
            let cfg = DrawConfig { level: 4, ..pn }.with_surface(surface, Displace::None);
            let got = h.capture(&mut scene, &cfg, &camera).unwrap().vertices;
            let want = h.capture(&mut fresh, &cfg, &camera).unwrap().vertices;
            assert!(!want.is_empty());
            assert!(
                got == want,
                "{}: not the moved mesh's vertices",
                surface.name()
            );
        }
    });
}
