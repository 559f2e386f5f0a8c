//! The `static` driver drawn adaptively (src/render/static_adaptive.rs), the CPU baseline of
//! adaptive refinement: at the levels `Scene::set_levels` chose (the level pass's CPU mirror),
//! the vertices it refines on the CPU and uploads equal what the pattern driver's real adaptive
//! pipelines evaluate at the same levels (read back through their capture variant), within the
//! pattern driver's mirror tolerance (tests/gpu_mirror.rs, tests/adaptive_pattern.rs: exact
//! without displacement and seams, 64 ulp of the radius for loop, 4 ulp more at split normals,
//! the displacements' own terms); it uploads again only when the drawn levels change; and at
//! random consistent levels the refined mesh of a closed mesh welds on exact bits into a closed
//! mesh (CPU only).

mod common;

use common::random_levels::random_levels;
use common::{model, with_gpu};
use glam::Vec3;
use meshrefine::pattern::adaptive::adaptive_element;
use meshrefine::pattern::PatternSet;
use meshrefine::render::static_adaptive::{drawn, refine_adaptive};
use meshrefine::render::{Camera, Capture, DrawConfig, Driver, Headless, LevelView, Scene, Submit};
use meshrefine::surface::{
    build_records, Displace, Mirror, RecordKind, Seams, Sources, Surface, SurfaceParams,
};
use std::collections::HashMap;

/// Draw `st` (static) adaptively for `view` (validated), then capture the pattern driver at
/// the levels the static frame drew and compare every drawn vertex. Returns the elements drawn.
fn compare(h: &mut Headless, scene: &mut Scene, st: DrawConfig, view: &LevelView, r: f32) -> usize {
    let max = st.level;
    h.adaptive = true;
    h.prepared_elements(scene, &st, Capture::None).unwrap();
    scene.set_levels(&st, view).unwrap();
    h.render(scene, &st, &view.camera).unwrap();
    let levels = scene.static_levels(&st).expect("levels chosen").to_vec();
    let records = scene.records(st.surface).to_vec();
    let mirror = scene.mirror(&st, max).unwrap();
    let refined = refine_adaptive(&st, &records, drawn(&levels, max), &mirror, false);
    let vbo = scene.static_vbo.as_ref().expect("the static buffer");
    assert!(vbo.adaptive.is_some(), "the static buffer is not adaptive");
    assert_eq!(vbo.vertex_count as usize, refined.vertices.len());
    assert_eq!(vbo.index_count as usize, refined.indices.len());

    let pc = DrawConfig {
        driver: Driver::Pattern(Submit::Instanced),
        ..st
    };
    h.prepared_elements(scene, &pc, Capture::Vertices).unwrap();
    scene.elements_mut(pc.surface).upload_levels(&levels);
    let cap = h.capture(scene, &pc, &view.camera).unwrap();
    h.adaptive = false;
    let tol = common::pattern_tolerance(&st, r, &records);
    let ntol = if st.displace == Displace::None {
        1e-5
    } else {
        2e-3
    };
    let what = format!("{} + {}", st.surface.name(), st.displace.name());
    let (mut at, mut elements) = (0, 0);
    for ((t, l), (_, slots)) in levels.iter().enumerate().zip(cap.adaptive_elements()) {
        let (first, end) = (refined.first[t], refined.first[t + 1]);
        let Some(e) = adaptive_element(l, max, false) else {
            assert_eq!(first, end, "{what}: culled element {t} has triangles");
            continue;
        };
        elements += 1;
        for (k, (&slot, c)) in e.vertices.iter().zip(slots).enumerate() {
            let s = refined.vertices[at + k];
            assert_eq!(
                c.position[3], 1.0,
                "{what}: element {t} slot {slot} not drawn"
            );
            for a in 0..3 {
                assert!(
                    (c.position[a] - s[a]).abs() <= tol,
                    "{what}: element {t} vertex {k}: static {:?} vs pattern {:?} (tolerance {tol:e})",
                    &s[..3],
                    &c.position[..3]
                );
                assert!(
                    (c.normal[a] - s[3 + a]).abs() <= ntol,
                    "{what}: element {t} vertex {k}: normal {:?} vs {:?}",
                    &s[3..],
                    &c.normal[..3]
                );
            }
        }
        at += e.vertices.len();
    }
    assert_eq!(at, refined.vertices.len());
    elements
}

#[test]
fn static_adaptive_equals_the_pattern_drivers_capture() {
    with_gpu(320, 180, |h| {
        let max = 16;
        let mesh = model("spot_control_tri.obj");
        let patterns = PatternSet::from_levels(&[max]);
        let mut scene = Scene::with_patterns(&h.ctx, &h.pool, &h.renderer, mesh, patterns).unwrap();
        let (c, r) = scene.bounding_sphere();
        // Close up: levels from 1 to 16 and culled elements.
        let eye = c + Vec3::new(0.6, 0.25, 0.9) * r;
        let camera = Camera::looking(eye, c, 45f32.to_radians(), 2.0 * r).unwrap();
        let view = LevelView {
            camera,
            width: 320,
            height: 180,
            pixel_error: 0.5,
            cull: true,
        };
        for (surface, displace) in [
            (Surface::Pn, Displace::None),
            (Surface::Phong, Displace::None),
            (Surface::Flat, Displace::Sine),
            (Surface::Loop, Displace::None),
        ] {
            let mut st = DrawConfig::new(Driver::Static, max).with_surface(surface, displace);
            st.params = SurfaceParams::for_radius(r);
            let drawn = compare(h, &mut scene, st, &view, r);
            let count = scene.elements(surface).element_count as usize;
            assert!(
                drawn > 0 && drawn < count,
                "{}: {drawn} of {count} drawn",
                surface.name()
            );
        }
    });
}

/// The buffer is refined and uploaded again only when the drawn levels change; choosing the
/// levels tallies them at once and makes no level pass.
#[test]
fn static_adaptive_uploads_when_the_levels_change() {
    with_gpu(160, 90, |h| {
        let max = 8;
        let mesh = model("icosahedron.obj");
        let patterns = PatternSet::from_levels(&[max]);
        let mut scene = Scene::with_patterns(&h.ctx, &h.pool, &h.renderer, mesh, patterns).unwrap();
        let (c, r) = scene.bounding_sphere();
        let mut st = DrawConfig::new(Driver::Static, max).with_surface(Surface::Pn, Displace::None);
        st.params = SurfaceParams::for_radius(r);
        let far = Camera::framing(c, r);
        let view = |camera, pixel_error| LevelView {
            camera,
            width: 160,
            height: 90,
            pixel_error,
            cull: false,
        };
        h.adaptive = true;
        let buffer = |scene: &Scene| scene.static_vbo.as_ref().map(|v| v.vertices.raw);
        // It refines at the mirror's levels, tallied at once; no level pass is made (its
        // bounds are not uploaded).
        let objects = meshrefine::gpu::live_objects();
        assert!(scene.set_levels(&st, &view(far, 4.0)).unwrap().is_tallied());
        assert_eq!(
            meshrefine::gpu::live_objects(),
            objects,
            "a level pass made"
        );
        h.render(&mut scene, &st, &far).unwrap();
        let first = buffer(&scene).expect("refined");
        let cost = scene.static_vbo.as_ref().unwrap().adaptive.clone().unwrap();
        assert!(cost.upload_bytes > 0);
        // What the panel reports: the buffer refined at the levels chosen, not every element
        // at the largest level.
        assert_eq!(scene.geometry_bytes(&st, true), cost.upload_bytes);
        // A moved mesh also uploads its records, which pn's fragments read (the normal field).
        let count = scene.elements(st.surface).element_count as u64;
        assert!(st.fragment_normal_field());
        assert_eq!(
            scene.upload_bytes(&st),
            cost.upload_bytes + count * meshrefine::surface::RECORD_BYTES as u64
        );
        assert!(cost.upload_bytes < st.geometry_bytes(20, false));
        // Animated, it also uploads the levels it chose (16 bytes an element); a driver whose
        // level pass chooses them uploads that pass's bounds instead (480 bytes an element).
        assert_eq!(scene.level_upload_bytes(&st), count * 16);
        let coarse = scene.upload_bytes(&st);
        assert_eq!(scene.animated_upload_bytes(&st, true), coarse + count * 16);
        let pattern = DrawConfig {
            driver: Driver::Pattern(Submit::Instanced),
            ..st
        };
        let coarse_levels = scene.set_levels(&pattern, &view(far, 4.0)).unwrap();
        assert!(scene.level_pass(&pattern).is_some());
        assert_eq!(scene.level_upload_bytes(&pattern), count * 480);
        let records = scene.upload_bytes(&pattern);
        assert_eq!(scene.animated_upload_bytes(&pattern, false), records);
        assert_eq!(
            scene.animated_upload_bytes(&pattern, true),
            records + count * 480
        );
        // Independent of the levels: levels for a sixteenth of the pixel error, other levels,
        // upload the same (the level pass reads the same bounds whatever it chooses).
        let fine_levels = scene.set_levels(&pattern, &view(far, 0.25)).unwrap();
        assert!(scene.level_pass(&pattern).is_some());
        assert_ne!(
            fine_levels.report().histogram,
            coarse_levels.report().histogram
        );
        assert_eq!(
            scene.animated_upload_bytes(&pattern, true),
            records + count * 480
        );
        scene.set_levels(&st, &view(far, 4.0)).unwrap();
        h.render(&mut scene, &st, &far).unwrap();
        assert_eq!(
            buffer(&scene),
            Some(first),
            "the same levels uploaded again"
        );
        scene.set_levels(&st, &view(far, 0.25)).unwrap();
        h.render(&mut scene, &st, &far).unwrap();
        let finer = scene.static_vbo.as_ref().unwrap().adaptive.clone().unwrap();
        assert_ne!(finer.drawn, cost.drawn);
        assert!(finer.upload_bytes > cost.upload_bytes);
        // Drawn uniformly again: every element at the level.
        h.adaptive = false;
        h.render(&mut scene, &st, &far).unwrap();
        assert!(scene.static_vbo.as_ref().unwrap().adaptive.is_none());
    });
}

/// At random consistent levels (edges differing from the inner levels, so boundary vertices are
/// snapped), the static driver's refined Spot welds on exact position bits into a closed,
/// consistently wound mesh of Spot's Euler characteristic: no crack, no T-junction.
#[test]
fn static_adaptive_is_watertight() {
    let mesh = model("spot_control_tri.obj");
    let records = build_records(RecordKind::Corners, &mesh, Seams::default());
    let corners: Vec<[u32; 3]> = mesh.triangles.iter().map(|t| t.p).collect();
    // stpn's tags, derived from the mesh as render derives them.
    let (tags, _) = meshrefine::surface::stpn::derive(&mesh);
    let max = 16;
    let r = mesh.bounding_radius();
    for (k, (surface, displace)) in [
        (Surface::Flat, Displace::None),
        (Surface::Pn, Displace::None),
        (Surface::Phong, Displace::None),
        (Surface::Pn, Displace::Sine),
        (Surface::Pn, Displace::Noise),
        (Surface::Stpn, Displace::None),
        (Surface::Flat, Displace::Noise),
    ]
    .into_iter()
    .enumerate()
    {
        let mut cfg = DrawConfig::new(Driver::Static, max).with_surface(surface, displace);
        cfg.params = SurfaceParams::for_radius(r);
        let levels = random_levels(&corners, max, 0.0, 11 + k as u32);
        let d = drawn(&levels, max);
        let snapped = d
            .iter()
            .flatten()
            .filter(|l| l.edges.iter().any(|&e| e < l.inner))
            .count();
        assert!(snapped > 100, "{snapped} elements with a coarser edge");
        let sources = Sources {
            tags: Some(&tags),
            ..Default::default()
        };
        let mirror = Mirror::new(cfg.surface, cfg.displace, &cfg.build, &sources);
        let refined = refine_adaptive(&cfg, &records, d, &mirror.unwrap(), false);
        let mut ids: HashMap<[u32; 3], u32> = HashMap::new();
        let weld: Vec<u32> = (refined.vertices.iter())
            .map(|v| {
                let key = [v[0].to_bits(), v[1].to_bits(), v[2].to_bits()];
                let n = ids.len() as u32;
                *ids.entry(key).or_insert(n)
            })
            .collect();
        let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
        let tris = refined.indices.len() / 3;
        for t in refined.indices.chunks_exact(3) {
            let t = [t[0], t[1], t[2]].map(|i| weld[i as usize]);
            assert!(
                t[0] != t[1] && t[1] != t[2] && t[2] != t[0],
                "degenerate triangle"
            );
            for e in 0..3 {
                let (a, b) = (t[e], t[(e + 1) % 3]);
                // +1 one way, -1 the other: a closed, consistently wound mesh sums to 0.
                *edges.entry((a.min(b), a.max(b))).or_default() += if a < b { 1 } else { -1 };
            }
        }
        let what = format!("{} + {}", surface.name(), displace.name());
        let open: Vec<_> = edges.iter().filter(|(_, &n)| n != 0).collect();
        assert!(
            open.is_empty(),
            "{what}: {} open edges, e.g. {:?}",
            open.len(),
            open[0]
        );
        assert_eq!(
            edges.len() * 2,
            tris * 3,
            "{what}: an edge used more than twice"
        );
        let euler = ids.len() as i64 - edges.len() as i64 + tris as i64;
        assert_eq!(euler, 2, "{what}: V - E + F");
    }
}
