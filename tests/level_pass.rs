//! The level pass on the GPU (glsl/lod/levels.comp through `render::LevelPass`, writing the
//! mesh's real levels buffer) against its CPU mirror (`lod::frame::frame_levels`) on Spot, for
//! `flat`, `phong`, `pn`, `stpn` and `loop`, with and without displacement, for a far camera, a
//! close-up that culls (frustum and back faces) and a grazing one from inside the mesh's
//! bounding sphere, for every rounding (the snapped integer levels' and the gliding ones' with
//! the lift's second dispatch: src/lod/frame/lift.rs); and once more without the edges' share of the transition
//! triangles, so that the inner levels' raise for them is compared too.
//!
//! The two evaluate the same formulas in f32, but GLSL's `sqrt` and `length` are not correctly
//! rounded, so: continuous levels agree to a relative 1e-4; where that much moves a level
//! across a rounding threshold (an integer, a power of two, the inner level's raise for its
//! transition triangles) the drawn levels may differ, which must be rare (at most 1% of the
//! elements, counted); culling agrees except for spheres within 1e-5 of the mesh's radius of a
//! plane or cones within 1e-5 radians of facing away (the facing-away test is written without
//! inverse trigonometric functions, which GPUs evaluate loosely). Every edge two elements share has
//! bit-identical levels in both on the GPU.

mod common;

use common::{model, with_gpu};
use glam::{Mat4, Vec3};
use meshrefine::gpu::vk;
use meshrefine::lod::frame::{
    corner_indices, element_levels, frame_levels, lod_records, LodRecord, LodView, Rounding,
    CULL_BACK_FACES, LIFT,
};
use meshrefine::lod::levels::{drawn_level, ElementLevels};
use meshrefine::lod::{Frustum, Lod, View};
use meshrefine::render::frame::{cmd_render, FrameWork, TargetView};
use meshrefine::render::{Capture, DrawConfig, Driver, LevelPass, Scene, Submit};
use meshrefine::surface::{stpn, BuildOptions, Displace, Mirror, Sources, Surface, SurfaceParams};
use std::collections::HashMap;

fn close(a: f32, b: f32, rel: f32) -> bool {
    a == b || (a - b).abs() <= rel * a.abs().max(b.abs())
}

/// Whether `x` lies within a relative `rel` of a rounding threshold of `drawn_level`.
fn near_threshold(x: f32, dyadic: bool, max: u32) -> bool {
    drawn_level(x * (1.0 - 1e-4), dyadic, max) != drawn_level(x * (1.0 + 1e-4), dyadic, max)
}

/// (eye, view-projection) of the three cameras around a mesh of centre `c` and radius `r`.
fn cameras(c: Vec3, r: f32) -> Vec<(&'static str, Vec3, Mat4)> {
    let cam = |eye: Vec3, target: Vec3| {
        let mut proj = Mat4::perspective_rh(0.8, 16.0 / 9.0, 0.001 * r, 10.0 * r);
        proj.y_axis.y = -proj.y_axis.y;
        (eye, proj * Mat4::look_at_rh(eye, target, Vec3::Y))
    };
    let far = cam(c + Vec3::new(0.3, 0.4, 1.0).normalize() * (6.0 * r), c);
    let close = cam(
        c + Vec3::new(0.4, 0.25, 1.0).normalize() * (1.6 * r),
        c + Vec3::new(0.7 * r, 0.2 * r, 0.0),
    );
    let grazing = cam(
        c + Vec3::new(0.0, 0.55 * r, 0.3 * r),
        c + Vec3::new(0.0, 0.5 * r, -r),
    );
    vec![
        ("far", far.0, far.1),
        ("close", close.0, close.1),
        ("grazing", grazing.0, grazing.1),
    ]
}

/// How far sphere `s` is from culling's decisions: its distance to being outside a plane
/// (world units), and its cone's angle from facing away (radians).
fn cull_margins(v: &LodView, r: &LodRecord) -> (f32, f32) {
    let c = Vec3::new(r.sphere[0], r.sphere[1], r.sphere[2]);
    let plane = v
        .planes
        .iter()
        .map(|p| (Vec3::new(p[0], p[1], p[2]).dot(c) + p[3] + r.sphere[3]).abs())
        .fold(f32::INFINITY, f32::min);
    let eye = Vec3::new(v.eye_k[0], v.eye_k[1], v.eye_k[2]);
    let d3 = c - eye;
    let d = d3.length();
    let cone = if r.cone[3] > 0.0 && d > r.sphere[3] {
        let axis = Vec3::new(r.cone[0], r.cone[1], r.cone[2]);
        let sum = (d3.dot(axis) / d).clamp(-1.0, 1.0).acos()
            + (r.sphere[3] / d).asin()
            + r.cone[3].clamp(-1.0, 1.0).acos();
        (sum - (std::f32::consts::FRAC_PI_2 - 1e-4)).abs()
    } else {
        f32::INFINITY
    };
    (plane, cone)
}

#[test]
fn gpu_levels_match_the_cpu() {
    with_gpu(16, 16, |h| {
        let mesh = model("spot_control_tri_vn.obj");
        let (tags, _) = stpn::derive(&mesh);
        let mut scene = Scene::new(&h.ctx, &h.pool, &h.renderer, mesh, 4).unwrap();
        let cfg = DrawConfig {
            surface: Surface::Loop,
            ..DrawConfig::new(Driver::Tess, 4)
        };
        scene
            .prepare(&h.ctx, &h.pool, &mut h.renderer, &cfg, Capture::None, false)
            .unwrap();
        let (c, r) = scene.bounding_sphere();
        let mut pass = LevelPass::new(&h.ctx).unwrap();
        let (mut compared, mut culled, mut shared, mut raised) = (0usize, 0usize, 0usize, 0usize);
        // Elements whose levels the lift changed (the mirror's, against its first pass).
        let mut lifted = 0usize;
        let mut thresholds = 0usize;
        for (surface, displace) in [
            (Surface::Flat, Displace::Sine),
            (Surface::Phong, Displace::None),
            (Surface::Pn, Displace::None),
            (Surface::Pn, Displace::Noise),
            (Surface::Stpn, Displace::None),
            (Surface::Loop, Displace::None),
        ] {
            let params = SurfaceParams {
                amplitude: 0.01 * r,
                frequency: 12.0 / r,
                ..SurfaceParams::for_radius(r)
            };
            let sources = Sources {
                tags: Some(&tags),
                loop_: scene.sources(4).loop_,
                ..Sources::default()
            };
            let mirror =
                Mirror::new(surface, displace, &BuildOptions::default(), &sources).unwrap();
            let lod = Lod::new(&mirror, &params);
            let records = scene.records(surface);
            let gpu_mesh = scene.elements(surface);
            let full = lod_records(&lod, records);
            // The same without the edges' transition needs: the inner levels' raise does it all.
            let mut bare = full.clone();
            for b in &mut bare {
                for e in &mut b.edges {
                    e.needs = [[0.0; 4]; 4];
                }
            }
            let n = records.len();
            let keys: Vec<[u32; 3]> = records.iter().map(|r| corner_indices(&lod, r)).collect();
            for ((name, eye, vp), bounds) in cameras(c, r)
                .into_iter()
                .flat_map(|cam| [(cam, &full), (cam, &bare)])
            {
                let name = if std::ptr::eq(bounds, &bare) {
                    format!("{name} (no edge needs)")
                } else {
                    name.to_string()
                };
                pass.upload(gpu_mesh, bounds).unwrap();
                let frustum = Frustum::from_view_proj(vp);
                for rounding in Rounding::ALL {
                    let dyadic = rounding.dyadic();
                    let what = format!(
                        "{} + {}, {name} camera, {rounding:?}",
                        surface.name(),
                        displace.name(),
                    );
                    let view = LodView::new(
                        &View::new(eye, 0.8, 720, 1.0, 64),
                        Some(&frustum),
                        true,
                        rounding,
                        n as u32,
                    );
                    h.pool
                        .submit_and_wait(|cmd| {
                            pass.cmd_record(cmd, gpu_mesh, &view);
                            cmd.barrier_to_host();
                        })
                        .unwrap();
                    let gpu: Vec<ElementLevels> = gpu_mesh.levels.read_pod();
                    let cpu = frame_levels(&view, bounds);
                    // The mirror's levels for a pixel error 0.1% larger and smaller: where the
                    // GPU's rounding differs, it lies between them (never coarser than a
                    // slightly larger error allows: the bound holds within 0.1%).
                    let at = |px: f32| {
                        let v = LodView::new(
                            &View::new(eye, 0.8, 720, px, 64),
                            Some(&frustum),
                            true,
                            rounding,
                            n as u32,
                        );
                        frame_levels(&v, bounds)
                    };
                    let (lenient, strict) = (at(1.001), at(0.999));
                    let mut rounding = 0;
                    for i in 0..n {
                        let (g, k) = (gpu[i], cpu[i]);
                        if g.culled() != k.culled() {
                            let (plane, cone) = cull_margins(&view, &bounds[i]);
                            assert!(
                                plane <= 1e-5 * r
                                    || (view.flags & CULL_BACK_FACES != 0 && cone <= 1e-5),
                                "{what}: element {i} culled {} on the GPU, {} on the CPU \
                                 (margins {plane}, {cone})",
                                g.culled(),
                                k.culled()
                            );
                            rounding += 1;
                            continue;
                        }
                        culled += k.culled() as usize;
                        // A lifted edge is a whole level: where a threshold of either element
                        // decides the lift, one side may hold it and the other the edge's own
                        // continuous level (counted below as a threshold, without the
                        // bracket: lifting is not monotone in the pixel error).
                        // (The gliding lift takes continuous levels: no threshold of its own.)
                        let lifts = view.flags & LIFT != 0 && !dyadic;
                        let lift_threshold = lifts
                            && (0..3).any(|e| {
                                !close(g.edges[e], k.edges[e], 1e-4)
                                    && (g.edges[e].fract() == 0.0 || k.edges[e].fract() == 0.0)
                            });
                        if lift_threshold {
                            rounding += 1;
                            continue;
                        }
                        for e in 0..3 {
                            assert!(
                                close(g.edges[e], k.edges[e], 1e-4),
                                "{what}: element {i} edge {e}: GPU {} CPU {}",
                                g.edges[e],
                                k.edges[e]
                            );
                        }
                        if k.culled() {
                            continue;
                        }
                        let drawn = |l: &ElementLevels| {
                            (
                                l.edges.map(|e| drawn_level(e, dyadic, 64)),
                                drawn_level(l.inner, dyadic, 64),
                            )
                        };
                        if drawn(&g) != drawn(&k) || !close(g.inner, k.inner, 1e-4) {
                            // A threshold: of the rounding, or of the raise for transitions.
                            rounding += 1;
                            let near = k.edges.iter().any(|&e| near_threshold(e, dyadic, 64))
                                || near_threshold(k.inner, dyadic, 64)
                                || k.inner.fract() == 0.0
                                || g.inner.fract() == 0.0;
                            assert!(near, "{what}: element {i}: GPU {g:?} CPU {k:?}");
                            let ((ge, gi), (le, li), (se, si)) =
                                (drawn(&g), drawn(&lenient[i]), drawn(&strict[i]));
                            // A neighbour's threshold may change the lift.
                            assert!(
                                lifts
                                    || (le.iter().zip(&ge).all(|(l, g)| l <= g)
                                        && ge.iter().zip(&se).all(|(g, s)| g <= s)
                                        // The raise for transitions is not monotone in the
                                        // pixel error: the inner level between the two,
                                        // either way.
                                        && (li.min(si)..=li.max(si)).contains(&gi)),
                                "{what}: element {i}: GPU draws {:?} between {:?} and {:?}",
                                (ge, gi),
                                (le, li),
                                (se, si)
                            );
                            continue;
                        }
                        let top = k.edges.iter().fold(0.0f32, |a, &e| a.max(e));
                        raised += (k.inner.fract() == 0.0 && k.inner > top) as usize;
                        lifted += (element_levels(&view, &bounds[i]) != k) as usize;
                        compared += 1;
                    }
                    thresholds += rounding;
                    assert!(
                        rounding * 100 <= n,
                        "{what}: {rounding} of {n} elements differ at a threshold"
                    );
                    // Shared edges: the same bits in both elements that draw them, on the GPU
                    // (a culled element's levels are all 0).
                    let mut seen: HashMap<(u32, u32), u32> = HashMap::new();
                    for (i, idx) in keys.iter().enumerate() {
                        if gpu[i].culled() {
                            assert_eq!(gpu[i], ElementLevels::CULLED, "{what}: element {i}");
                            continue;
                        }
                        for e in 0..3 {
                            let (a, b) = (idx[e], idx[(e + 1) % 3]);
                            let bits = gpu[i].edges[e].to_bits();
                            if let Some(old) = seen.insert((a.min(b), a.max(b)), bits) {
                                assert_eq!(old, bits, "{what}: element {i} edge {e}");
                                shared += 1;
                            }
                        }
                    }
                }
            }
        }
        eprintln!(
            "{compared} elements equal, {thresholds} at a threshold, {culled} culled, \
             {shared} shared edges, {raised} raised, {lifted} lifted"
        );
        assert!(compared > 20_000 && culled > 6000 && raised > 5000 && shared > 40_000);
        assert!(lifted > 1000, "{lifted} elements lifted");
        drop(pass);
    });
}

/// Spot's cage as `pn` on the instanced pattern driver at level 4, prepared, with its bounds.
fn spot_pn(h: &mut meshrefine::render::Headless) -> (Scene, DrawConfig, Vec<LodRecord>) {
    let mut scene = Scene::new(
        &h.ctx,
        &h.pool,
        &h.renderer,
        model("spot_control_tri.obj"),
        4,
    )
    .unwrap();
    let cfg = DrawConfig {
        surface: Surface::Pn,
        ..DrawConfig::new(Driver::Pattern(Submit::Instanced), 4)
    };
    scene
        .prepare(&h.ctx, &h.pool, &mut h.renderer, &cfg, Capture::None, false)
        .unwrap();
    let mirror = Mirror::new(cfg.surface, cfg.displace, &cfg.build, &Sources::default()).unwrap();
    let bounds = lod_records(&Lod::new(&mirror, &cfg.params), &scene.data.records);
    (scene, cfg, bounds)
}

/// A frame that carries the level pass (`FrameWork::level_pass`) runs it before drawing, into
/// the drawn mesh's levels, with its barriers inside a real frame (the validation layer
/// watches): the levels it leaves are the mirror's.
#[test]
fn a_frame_runs_the_level_pass_before_drawing() {
    with_gpu(64, 36, |h| {
        let (scene, cfg, bounds) = spot_pn(h);
        let (c, r) = scene.bounding_sphere();
        let mut pass = LevelPass::new(&h.ctx).unwrap();
        pass.upload(&scene.gpu, &bounds).unwrap();
        let (_, eye, vp) = cameras(c, r)[1];
        let frustum = Frustum::from_view_proj(vp);
        let view = LodView::new(
            &View::new(eye, 0.8, 36, 0.5, 64),
            Some(&frustum),
            true,
            cfg.rounding(),
            0,
        );
        let target = TargetView {
            color: h.target.color.raw,
            color_view: h.target.color.view,
            depth: h.target.depth.raw,
            depth_view: h.target.depth.view,
            extent: h.target.extent(),
            final_layout: vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
            resolve: None,
        };
        let work = FrameWork {
            level_pass: Some((&pass, view)),
            ..FrameWork::new(&scene, cfg)
        };
        h.pool
            .submit_and_wait(|cmd| {
                cmd_render(cmd, &h.renderer, &target, &work, None, None);
                cmd.barrier_to_host();
            })
            .unwrap();
        let gpu: Vec<ElementLevels> = scene.gpu.levels.read_pod();
        let cpu = frame_levels(&view, &bounds);
        let (mut culled, mut refined) = (0, 0);
        for (i, (g, k)) in gpu.iter().zip(&cpu).enumerate() {
            assert_eq!(g.culled(), k.culled(), "element {i}");
            assert!(close(g.inner, k.inner, 1e-4), "element {i}: {g:?} {k:?}");
            culled += k.culled() as usize;
            refined += (k.inner > 1.0) as usize;
        }
        assert!(
            culled > 10 && refined > 10,
            "{culled} culled, {refined} refined"
        );
        drop(pass);
    });
}

/// Bounds too many for one storage-buffer descriptor are dispatched in chunks, each bound by its
/// own set: chunks of 1, 7 and 100 of Spot's 372 elements (levels poisoned before each run)
/// write the bits one dispatch writes, at integer levels and gliding ones, where the lift reads
/// neighbours in other chunks (counted from the mirror: edges lifted across a chunk's border).
#[test]
fn chunked_dispatches_write_the_levels_one_writes() {
    with_gpu(16, 16, |h| {
        let (mut scene, cfg, bounds) = spot_pn(h);
        let (c, r) = scene.bounding_sphere();
        let n = bounds.len();
        let (_, eye, vp) = cameras(c, r)[1];
        // Integer levels (the lift for transitions), and gliding ones (the lift to the insides).
        for rounding in [cfg.rounding(), Rounding::Snapped] {
            let view = LodView::new(
                &View::new(eye, 0.8, 720, 1.0, 64),
                Some(&Frustum::from_view_proj(vp)),
                true,
                rounding,
                n as u32,
            );
            let poison: Vec<ElementLevels> =
                bytemuck::cast_slice(&vec![0xdead_beef_u32; 4 * n]).to_vec();
            let mut run = |chunk: Option<u32>| -> (Vec<u32>, usize) {
                let mut pass = LevelPass::with_max_chunk(&h.ctx, chunk).unwrap();
                pass.upload(&scene.gpu, &bounds).unwrap();
                scene.gpu.upload_levels(&poison);
                h.pool
                    .submit_and_wait(|cmd| {
                        pass.cmd_record(cmd, &scene.gpu, &view);
                        cmd.barrier_to_host();
                    })
                    .unwrap();
                let levels: Vec<ElementLevels> = scene.gpu.levels.read_pod();
                (bytemuck::cast_slice(&levels).to_vec(), pass.dispatches())
            };
            let (whole, one) = run(None);
            assert_eq!(one, 1);
            assert!(!whole.contains(&0xdead_beef));
            assert!(view.flags & LIFT != 0);
            let lifted = frame_levels(&view, &bounds);
            for chunk in [1usize, 7, 100] {
                let mut across = 0;
                for (i, b) in bounds.iter().enumerate() {
                    let first = element_levels(&view, b);
                    for e in 0..3 {
                        let j = (b.neighbours[e] / 4) as usize;
                        across += (lifted[i].edges[e] != first.edges[e] && i / chunk != j / chunk)
                            as usize;
                    }
                }
                assert!(
                    across > 10,
                    "{rounding:?}, chunks of {chunk}: {across} edges lifted across a border"
                );
                let chunk = chunk as u32;
                let (split, dispatches) = run(Some(chunk));
                assert!(
                    dispatches > 1,
                    "chunks of {chunk}: {dispatches} dispatch(es)"
                );
                assert!(
                    split == whole,
                    "{rounding:?}, chunks of {chunk} write other levels"
                );
            }
        }
    });
}
