//! The levels the command line draws with (`Scene::set_levels`, written by the level pass on
//! the GPU in every adaptive frame): what `set_levels` reports is what the GPU wrote (the
//! pass's mirror), the same bits for an edge from both of its elements in the buffer the
//! drivers read, and culling that only zeroes inner levels.

mod common;

use common::random_levels::element_corners;
use common::{model, with_gpu};
use meshrefine::lod::frame::{frame_levels, lod_records, LodView};
use meshrefine::lod::levels::ElementLevels;
use meshrefine::lod::{Lod, View};
use meshrefine::render::{Camera, Capture, DrawConfig, Driver, LevelView};
use meshrefine::surface::{Displace, Surface, SurfaceParams};
use std::collections::HashMap;

/// The bounds of `scene`'s elements for `cfg` made here from its mirror, and the levels the
/// level pass's CPU mirror chooses from them ([`levels_from`]).
fn mirror_levels(
    scene: &meshrefine::render::Scene,
    cfg: &DrawConfig,
    camera: &Camera,
) -> (Vec<meshrefine::lod::frame::LodRecord>, Vec<ElementLevels>) {
    let max = cfg.level;
    let lod = Lod::new(&scene.mirror(cfg, max).unwrap(), &cfg.params).drawn_as(cfg.rounding());
    let bounds = lod_records(&lod, scene.records(cfg.surface));
    let levels = levels_from(&bounds, cfg, camera);
    (bounds, levels)
}

/// The level view the mirror comparisons draw with: 1280x720, 1 px, no culling.
fn view_at_1px(camera: Camera) -> LevelView {
    LevelView {
        camera,
        width: 1280,
        height: 720,
        pixel_error: 1.0,
        cull: false,
    }
}

/// The levels the level pass's CPU mirror chooses from `bounds` for `camera` as
/// [`view_at_1px`] sees it, `cfg`'s largest level and rounding.
fn levels_from(
    bounds: &[meshrefine::lod::frame::LodRecord],
    cfg: &DrawConfig,
    camera: &Camera,
) -> Vec<ElementLevels> {
    let metric = View::new(camera.eye(), camera.fov_y, 720, 1.0, cfg.level);
    let lod_view = LodView::new(&metric, None, false, cfg.rounding(), bounds.len() as u32);
    frame_levels(&lod_view, bounds)
}

/// The GPU's inner levels are the mirror's within 1e-4 (relative), one for each element.
fn assert_levels_agree(gpu: &[ElementLevels], mirror: &[ElementLevels], what: &str) {
    assert_eq!(gpu.len(), mirror.len(), "{what}");
    for (i, (g, m)) in gpu.iter().zip(mirror).enumerate() {
        assert!(
            (g.inner - m.inner).abs() <= 1e-4 * m.inner.max(1.0),
            "{what}: element {i}: {g:?} {m:?}"
        );
    }
}

#[test]
fn gpu_levels_match_the_mirror_and_share_edges() {
    with_gpu(64, 64, |h| {
        for surface in [Surface::Pn, Surface::Phong, Surface::Loop] {
            let max = 16;
            let mut scene = h.scene(model("spot_control_tri.obj"), max).unwrap();
            let (c, r) = scene.bounding_sphere();
            let mut cfg = DrawConfig::new(Driver::Tess, max).with_surface(surface, Displace::None);
            cfg.params = SurfaceParams::for_radius(r);
            h.prepared_elements(&mut scene, &cfg, Capture::None)
                .unwrap();
            let framing = Camera::framing(c, r);
            let close = Camera::looking(
                c + glam::Vec3::new(0.2, 0.1, 0.5) * r,
                c,
                45f32.to_radians(),
                r,
            )
            .unwrap();
            for camera in [framing, close] {
                let view = view_at_1px(camera);
                let what = format!("{} at {:?}", surface.name(), camera.eye());
                let got = scene.set_levels(&cfg, &view).unwrap();
                // Drawn on the GPU: the mirror runs when the tally is read (below), not before.
                assert!(!got.is_tallied(), "{what}: the mirror ran unread");
                assert!(scene.level_pass(&cfg).is_some(), "{what}: no level pass");
                h.adaptive = true;
                h.draw(&mut scene, &cfg, &camera).unwrap();
                let (gpu, drawn) = scene.drawn_levels(&cfg);
                // The mirror, from bounds made here.
                let (_, mirror) = mirror_levels(&scene, &cfg, &camera);
                assert_levels_agree(&gpu, &mirror, &what);
                assert_eq!(got.histogram, drawn.histogram, "{what}");
                assert_eq!(got.culled, 0, "{what}");
                // The buffer the drivers read: each edge the same bits from both sides.
                let levels: Vec<ElementLevels> = gpu;
                let corners = element_corners(&scene, surface);
                let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
                for (c, l) in corners.iter().zip(&levels) {
                    assert!(l.inner >= l.edges.iter().fold(1.0f32, |m, &e| m.max(e)));
                    for k in 0..3 {
                        let (a, b) = (c[k], c[(k + 1) % 3]);
                        let bits = *edges
                            .entry((a.min(b), a.max(b)))
                            .or_insert(l.edges[k].to_bits());
                        assert_eq!(bits, l.edges[k].to_bits(), "{what}: edge {a}-{b}");
                    }
                }
                // Culling zeroes the culled elements' levels (none computed for them), changes
                // no other element's, and counts them.
                let culled = scene
                    .set_levels(&cfg, &LevelView { cull: true, ..view })
                    .unwrap();
                h.draw(&mut scene, &cfg, &camera).unwrap();
                let (after, drawn) = scene.drawn_levels(&cfg);
                assert_eq!(culled.histogram, drawn.histogram, "{what}");
                let zero = after.iter().filter(|l| l.culled()).count() as u64;
                assert_eq!(zero, culled.culled, "{what}");
                for (a, b) in levels.iter().zip(&after) {
                    assert!(b == a || *b == ElementLevels::CULLED, "{what}: {a:?} {b:?}");
                }
                let drawn: u64 = culled.histogram.values().sum();
                assert_eq!(drawn + culled.culled, levels.len() as u64, "{what}");
                if camera == close || surface != Surface::Loop {
                    // Outside the close-up's frustum, or facing away from the framing camera.
                    assert!(culled.culled > 0, "{what}: nothing culled");
                }
            }
        }
    });
}

/// Culling never changes the image: on a closed mesh wound outwards (spot) seen from outside the
/// elements facing away are culled; on the same mesh wound inside out (every face's corners
/// reversed, whose visible faces are those facing away), on spot beside an inside-out copy of
/// itself, and with the eye inside the mesh, none is culled for facing away, only for lying
/// outside the view. Each is drawn adaptively with culling on and off, on every driver, and the
/// images are compared pixel for pixel.
#[test]
fn culling_keeps_the_image_of_a_mesh_wound_either_way() {
    with_gpu(160, 120, |h| {
        let outward = meshrefine::mesh::default_mesh();
        let flip = |m: &meshrefine::mesh::Mesh| {
            let mut m = m.clone();
            for t in &mut m.triangles {
                t.p.swap(1, 2);
                t.n.swap(1, 2);
                if let Some(tc) = &mut t.t {
                    tc.swap(1, 2);
                }
            }
            m
        };
        let inside_out = flip(&outward);
        let spot_positions = outward.positions.len();
        assert!(inside_out.signed_volume() < 0.0 && outward.signed_volume() > 0.0);
        // Spot wound outwards beside a smaller copy of it wound inside out: the whole encloses
        // a positive volume, but the copy's visible faces face away.
        let mut mixed = outward.clone();
        let (lo, hi) = outward.bounds();
        let mut copy = flip(&outward);
        for p in &mut copy.positions {
            *p = *p * 0.5 + glam::Vec3::new(1.5 * (hi.x - lo.x), 0.0, 0.0);
        }
        let base = mixed.positions.len() as u32;
        let base_n = mixed.normals.len() as u32;
        mixed.positions.extend(copy.positions.iter().copied());
        mixed.normals.extend(copy.normals.iter().copied());
        mixed.triangles.extend(copy.triangles.iter().map(|t| {
            let mut t = *t;
            t.p = t.p.map(|i| i + base);
            t.n = t.n.map(|i| i + base_n);
            t.t = None;
            t
        }));
        mixed.triangles.iter_mut().for_each(|t| t.t = None);
        assert!(mixed.signed_volume() > 0.0 && !mixed.closed_outward());
        for (name, mesh, closed) in [
            ("outward", outward, true),
            ("inside out", inside_out, false),
            ("one piece inside out", mixed, false),
        ] {
            let max = 8;
            let mut scene = h.scene(mesh, max).unwrap();
            let (c, r) = scene.bounding_sphere();
            // Close enough that part of the mesh is outside the view, and from inside the
            // mesh (the centre of its bounds, where its winding number is 1 or -1): there the
            // visible faces are those facing away.
            let outside = Camera::looking(
                c + glam::Vec3::new(0.3, 0.2, 0.9) * r,
                c,
                45f32.to_radians(),
                r,
            )
            .unwrap();
            // (Spot's positions come first in every mesh here.)
            let spot = &scene.data.mesh.positions[..spot_positions];
            let lo = spot.iter().fold(glam::Vec3::INFINITY, |a, &p| a.min(p));
            let hi = spot.iter().fold(glam::Vec3::NEG_INFINITY, |a, &p| a.max(p));
            let inside_eye = (lo + hi) * 0.5;
            let inside = Camera::looking(
                inside_eye,
                inside_eye + glam::Vec3::new(0.2, -0.1, 1.0),
                60f32.to_radians(),
                r,
            )
            .unwrap();
            let w = scene.data.mesh.winding_number(inside_eye);
            assert!((w.abs() - 1.0).abs() < 1e-6, "{name}: winding number {w}");
            for (where_, camera) in [("outside", outside), ("inside", inside)] {
                for driver in [
                    Driver::Static,
                    Driver::Pattern(meshrefine::render::Submit::Push),
                    Driver::Tess,
                ] {
                    let mut cfg =
                        DrawConfig::new(driver, max).with_surface(Surface::Pn, Displace::None);
                    cfg.params = SurfaceParams::for_radius(r);
                    h.prepared_elements(&mut scene, &cfg, Capture::None)
                        .unwrap();
                    let (all, none_culled) = adaptive_image(h, &mut scene, &cfg, &camera, false);
                    let (culled_img, culled) = adaptive_image(h, &mut scene, &cfg, &camera, true);
                    let what = format!("{name}, {where_}, {}", driver.name());
                    assert_eq!(none_culled, 0, "{what}");
                    assert!(culled > 0, "{what}: nothing culled");
                    let bg = meshrefine::render::clear_color_srgb8();
                    let drawn = all.chunks_exact(4).filter(|p| p[..3] != bg[..3]).count();
                    assert!(drawn > 160 * 120 / 4, "{what}: {drawn} pixels drawn");
                    let differ = differing(&all, &culled_img);
                    assert_eq!(differ, 0, "{what}: culling changed {differ} pixels");
                }
            }
            assert_eq!(scene.closed, closed, "{name}");
        }
    });
}

/// Where a closed mesh's surface shows its back side from outside, culling keeps what faces
/// away: Spot's control cage drawn `flat` folds through itself where the head meets the body
/// (a face facing away is the first one seen there from below), and the hard-edged cylinder as
/// `pn`, `phong` or `stpn` with open seams shows its inside through the cracks. Images with culling on and off,
/// one sample per pixel, compared pixel for pixel.
#[test]
fn culling_keeps_what_a_fold_or_a_crack_shows() {
    with_gpu(320, 180, |h| {
        let cases = [
            (
                "spot folded",
                meshrefine::mesh::default_mesh(),
                Surface::Flat,
            ),
            (
                "cylinder cracked",
                model("cylinder_hard_normals.obj"),
                Surface::Pn,
            ),
            // Open seams turn facing-away culling off for every surface but `flat`.
            (
                "cylinder cracked",
                model("cylinder_hard_normals.obj"),
                Surface::Phong,
            ),
            (
                "cylinder cracked",
                model("cylinder_hard_normals.obj"),
                Surface::Stpn,
            ),
        ];
        for (name, mesh, surface) in cases {
            let mut scene = h.scene(mesh, 8).unwrap();
            let (c, r) = scene.bounding_sphere();
            let eye = c + glam::Vec3::new(1.5, -1.0, -2.0).normalize() * (2.6 * r);
            let camera = Camera::looking(eye, c, 45f32.to_radians(), r).unwrap();
            let mut cfg = DrawConfig::new(Driver::Pattern(meshrefine::render::Submit::Push), 8)
                .with_surface(surface, Displace::None);
            cfg.params = SurfaceParams::for_radius(r);
            if name == "cylinder cracked" {
                cfg.build.seams = meshrefine::surface::Seams::Open;
            }
            h.prepared_elements(&mut scene, &cfg, Capture::None)
                .unwrap();
            let (all, _) = adaptive_image(h, &mut scene, &cfg, &camera, false);
            let (culled_img, culled) = adaptive_image(h, &mut scene, &cfg, &camera, true);
            let differ = differing(&all, &culled_img);
            let name = format!("{name} ({})", surface.name());
            assert_eq!(differ, 0, "{name}: culling changed {differ} pixels");
            assert_eq!(
                culled, 0,
                "{name}: culled {culled}, every element is in view"
            );
            assert!(scene.closed, "{name}");
        }
    });
}

/// `cfg` drawn adaptively at 1 px for `camera` at the context's size, culling on or off: the
/// image and how many elements were culled.
fn adaptive_image(
    h: &mut meshrefine::render::Headless,
    scene: &mut meshrefine::render::Scene,
    cfg: &DrawConfig,
    camera: &Camera,
    cull: bool,
) -> (Vec<u8>, u64) {
    let e = h.target.color.desc.extent;
    let (width, height) = (e.width, e.height);
    let view = LevelView {
        camera: *camera,
        width,
        height,
        pixel_error: 1.0,
        cull,
    };
    let chosen = scene.set_levels(cfg, &view).unwrap();
    h.adaptive = true;
    let img = h.render(scene, cfg, camera).unwrap();
    h.adaptive = false;
    (img.rgba, chosen.report().culled)
}

/// How many pixels of two RGBA images differ.
fn differing(a: &[u8], b: &[u8]) -> usize {
    (a.chunks_exact(4).zip(b.chunks_exact(4)))
        .filter(|(x, y)| x != y)
        .count()
}

/// The bounds are computed once per mesh, surface and displacement: a new camera, pixel error
/// or largest level keeps them (the window changes those every frame or key press, and a large
/// mesh's bounds take seconds), another surface makes new ones, and the levels chosen at a
/// smaller largest level from the kept bounds are capped there.
#[test]
fn bounds_are_kept_while_only_the_view_or_the_largest_level_change() {
    with_gpu(64, 64, |h| {
        let mut scene = h.scene(model("spot_control_tri.obj"), 16).unwrap();
        let (c, r) = scene.bounding_sphere();
        let cfg = |surface: Surface, max: u32| {
            let mut cfg = DrawConfig::new(Driver::Tess, max).with_surface(surface, Displace::None);
            cfg.params = SurfaceParams::for_radius(r);
            cfg
        };
        let view = |pixel_error: f32, eye: glam::Vec3| LevelView {
            camera: Camera::looking(c + eye * r, c, 45f32.to_radians(), r).unwrap(),
            width: 320,
            height: 180,
            pixel_error,
            cull: true,
        };
        let pn16 = cfg(Surface::Pn, 16);
        h.prepared_elements(&mut scene, &pn16, Capture::None)
            .unwrap();
        let first = scene
            .set_levels(&pn16, &view(1.0, glam::Vec3::Z * 3.0))
            .unwrap();
        let bounds = scene.level_bounds().unwrap().clone();
        assert!(first.histogram.keys().all(|&l| l <= 16));
        for (max, pixel_error, eye) in [
            (16, 0.25, glam::Vec3::new(0.3, 0.2, 0.5)),
            (4, 0.25, glam::Vec3::new(0.3, 0.2, 0.5)),
            (8, 2.0, glam::Vec3::X * 4.0),
        ] {
            let chosen = scene
                .set_levels(&cfg(Surface::Pn, max), &view(pixel_error, eye))
                .unwrap();
            let kept = scene.level_bounds().unwrap();
            assert!(
                std::sync::Arc::ptr_eq(kept, &bounds),
                "bounds made again at max {max}, {pixel_error} px"
            );
            assert!(
                chosen.histogram.keys().all(|&l| l <= max),
                "{:?}",
                chosen.histogram
            );
        }
        let phong = cfg(Surface::Phong, 16);
        h.prepared_elements(&mut scene, &phong, Capture::None)
            .unwrap();
        scene
            .set_levels(&phong, &view(1.0, glam::Vec3::Z * 3.0))
            .unwrap();
        assert!(!std::sync::Arc::ptr_eq(
            scene.level_bounds().unwrap(),
            &bounds
        ));
    });
}

/// An animated mesh's levels follow it: after `update_mesh` the bounds are made again from the
/// moved mesh (not those of the first pose, which would leave levels too low and cones that
/// cull what is seen), and the GPU level pass reads them: its levels are the mirror's from the
/// moved mesh's own bounds, for a local surface and for Loop (whose M1 the GPU makes again).
#[test]
fn an_animated_mesh_gets_new_bounds_and_levels() {
    with_gpu(64, 64, |h| {
        for surface in [Surface::Pn, Surface::Loop] {
            let max = 16;
            let base = model("spot_control_tri.obj");
            let mut scene = h.scene(base.clone(), max).unwrap();
            let (c, r) = scene.bounding_sphere();
            let mut cfg = DrawConfig::new(Driver::Tess, max).with_surface(surface, Displace::None);
            cfg.params = SurfaceParams::for_radius(r);
            let eye = c + glam::Vec3::new(0.2, 0.1, 0.5) * r;
            let camera = Camera::looking(eye, c, 45f32.to_radians(), r).unwrap();
            let view = view_at_1px(camera);
            h.prepared_elements(&mut scene, &cfg, Capture::None)
                .unwrap();
            scene.set_levels(&cfg, &view).unwrap();
            let before = scene.level_bounds().unwrap().clone();
            scene.update_mesh(base.animated(0.7, 0.05 * r));
            h.prepared_elements(&mut scene, &cfg, Capture::None)
                .unwrap();
            let got = scene.set_levels(&cfg, &view).unwrap();
            let what = surface.name();
            h.adaptive = true;
            h.draw(&mut scene, &cfg, &camera).unwrap();
            let (gpu, drawn) = scene.drawn_levels(&cfg);
            let (bounds, mirror) = mirror_levels(&scene, &cfg, &camera);
            assert!(
                scene.level_bounds().unwrap()[..] == bounds[..],
                "{what}: the scene's bounds are not the moved mesh's"
            );
            assert!(
                before[..] != bounds[..],
                "{what}: the pose did not change the bounds"
            );
            assert_levels_agree(&gpu, &mirror, what);
            // The first pose's bounds would choose other levels: the check above tells them
            // apart.
            let stale = levels_from(&before, &cfg, &camera);
            assert!(
                stale
                    .iter()
                    .zip(&mirror)
                    .any(|(s, m)| (s.inner - m.inner).abs() > 1e-4 * m.inner.max(1.0)),
                "{what}: the first pose's bounds choose the same levels"
            );
            assert_eq!(got.histogram, drawn.histogram, "{what}");
        }
    });
}
