//! The tess driver drawing adaptively: at random integer levels, welded on exact bits into a
//! crack-free tessellation (the style of tests/watertight.rs); culled elements drawing nothing;
//! and geomorphing (docs/adaptivity.md, "Geomorphing"): the real pipelines drawing at random
//! continuous levels, read back, against the CPU mirror (`render::tess::morph`), the welded
//! result closed, and the popping sweep.

mod common;

use common::random_levels::{crack_free_vertices, element_corners, open_edges, random_levels};
use common::watertight::{check_tess_adaptive, config, scene_at, CLOSED, SURFACES};
use common::{model, with_gpu};
use glam::{DVec2, Mat4, Vec2, Vec3, Vec4};
use meshrefine::export::weld_triangles;
use meshrefine::lod::levels::ElementLevels;
use meshrefine::pattern::PatternSet;
use meshrefine::render::tess::morph::{
    geomorph_position, geomorph_weights, morph_levels, morph_weights,
};
use meshrefine::render::tess::{outer_levels, tess_triangle_count, tess_weights_levels};
use meshrefine::render::{Camera, Capture, DrawConfig, Driver, Headless, LevelView, Scene};
use meshrefine::surface::{Displace, Surface, SurfaceParams};
use std::collections::{HashMap, HashSet};

const MAX: u32 = 16;

/// Random consistent continuous levels (one per unique edge, inner at least its edges'): every
/// captured vertex equals the mirror's `geomorph_position` (the GPU's evaluation tolerance plus
/// 4 ulp of the radius for the blend); the tessellator's inside vertices lie on the ring lattice
/// `K/(3n)` the mirror derives their parents from; hundreds of vertices really morph; and the
/// triangles (transform feedback, what export writes) weld on exact bits into a closed mesh with
/// the crack-free vertex count (edge vertices morph with their edge's level, the same bits from
/// both sides).
#[test]
fn tess_geomorph_matches_the_mirror_and_is_watertight() {
    let cases = [
        ("icosahedron_vn.obj", Surface::Pn, Displace::None, 3),
        ("torus_16x8.obj", Surface::Phong, Displace::Sine, 5),
        ("spot_control_tri.obj", Surface::Pn, Displace::None, 7),
        // Loop's M1 faces glide on the tessellator (`DrawConfig::glides`).
        ("spot_control_tri.obj", Surface::Loop, Displace::None, 11),
        ("icosahedron_vn.obj", Surface::Stpn, Displace::Noise, 13),
        ("icosahedron_vn.obj", Surface::Flat, Displace::Noise, 17),
        ("icosahedron.obj", Surface::Loop, Displace::Sine, 19),
    ];
    with_gpu(64, 64, |h| {
        for (file, surface, displace, seed) in cases {
            let mesh = model(file);
            let mut scene = Scene::with_patterns(
                &h.ctx,
                &h.pool,
                &h.renderer,
                mesh,
                PatternSet::from_levels(&[MAX]),
            )
            .unwrap();
            let (c, r) = scene.bounding_sphere();
            let camera = Camera::framing(c, r);
            let mut cfg = DrawConfig::new(Driver::Tess, MAX).with_surface(surface, displace);
            cfg.params = SurfaceParams::for_radius(r);
            cfg.geomorph = true;
            assert!(cfg.glides() && cfg.dyadic_levels());
            let what = format!(
                "{file} {} + {} tess geomorph",
                surface.name(),
                displace.name()
            );
            h.prepared_elements(&mut scene, &cfg, Capture::Vertices)
                .unwrap();
            let corners = element_corners(&scene, surface);
            let levels = random_levels(&corners, MAX, 0.0, seed);
            match &mut scene.loop_ {
                Some(l) if surface.uses_loop_faces() => l.gpu.upload_levels(&levels),
                _ => scene.gpu.upload_levels(&levels),
            }
            h.adaptive = true;
            let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
            let records = scene.records(surface);
            let mirror = scene.mirror(&cfg, MAX).unwrap();
            let eps = f32::EPSILON * r;
            // Loop: sums of table-weighted M1 points (M1 made by the GPU's Loop pass).
            let base = if surface == Surface::Loop { 64.0 } else { 16.0 };
            let tol = (base + 4.0) * eps
                + match displace {
                    Displace::Sine => 2e-3 * cfg.params.amplitude.abs() + 8.0 * eps,
                    Displace::Noise => 1e-5 * cfg.params.amplitude.abs() + 8.0 * eps,
                    _ => 0.0,
                };
            let (mut morphing, mut worst, mut seen) = (0usize, 0.0f32, 0usize);
            for v in cap.vertices.iter().filter(|v| v.position[3] == 1.0) {
                seen += 1;
                let t = v.id[0] as usize;
                let (outer, inner) = morph_levels(&levels[t], MAX).unwrap();
                let tc = [v.coord[0], v.coord[1], v.coord[2]];
                if tc.iter().all(|&x| x >= 0.5 / inner as f32) {
                    let s = (3 * inner) as f32;
                    for x in tc {
                        let k = x * s;
                        assert!(
                            (k - k.round()).abs() < 1e-3,
                            "{what}: element {t}: {tc:?} is off the ring lattice of level {inner}"
                        );
                    }
                }
                let w = morph_weights(tc, outer, inner);
                let eval = |b: [f32; 3]| mirror.eval(&cfg.params, t, &records[t], b).position;
                let p = eval(w);
                let want = geomorph_position(tc, w, p, outer, inner, &levels[t], &eval);
                morphing += (want != p) as usize;
                let d = (Vec3::from_slice(&v.position[..3]) - want)
                    .abs()
                    .max_element();
                worst = worst.max(d);
                assert!(
                    d <= tol,
                    "{what}: element {t} at {tc:?}: {:?} vs mirror {want} (tolerance {tol:e})",
                    &v.position[..3]
                );
            }
            eprintln!("{what}: {seen} vertices, {morphing} morphing, worst difference {worst:e}");
            assert!(morphing > 200, "{what}: only {morphing} vertices morph");
            let tris = h.capture_triangles(&mut scene, &cfg, &camera).unwrap();
            let welded = weld_triangles(&tris);
            assert_eq!(
                welded.positions.len(),
                crack_free_vertices(&corners, &levels, |l| morph_levels(l, MAX)),
                "{what}: welded vertices"
            );
            assert_eq!(open_edges(&welded.triangles), 0, "{what}: cracks");
            h.adaptive = false;
        }
    });
}

/// One frame as the tess driver drew it: per element its triangles in parameter space (the
/// corners' parameters as drawn, blended while geomorphing) with their positions, and every
/// drawn vertex (element, parameter, position).
struct Drawn {
    triangles: Vec<Vec<([DVec2; 3], [Vec3; 3])>>,
    vertices: Vec<(usize, DVec2, Vec3)>,
    levels: Vec<Option<([u32; 3], u32)>>,
}

/// The levels the tess driver draws `l` with for `cfg`.
fn tess_levels(cfg: &DrawConfig, l: &ElementLevels) -> Option<([u32; 3], u32)> {
    if cfg.glides() {
        morph_levels(l, cfg.level)
    } else {
        outer_levels(l, cfg.level)
    }
}

fn draw_frame(h: &mut Headless, scene: &mut Scene, cfg: &DrawConfig, camera: &Camera) -> Drawn {
    let (width, height) = SWEEP_SIZE;
    scene
        .set_levels(
            cfg,
            &LevelView {
                camera: *camera,
                width,
                height,
                pixel_error: 1.0,
                cull: false,
            },
        )
        .unwrap();
    assert!(scene.level_pass(cfg).is_some(), "no level pass");
    h.adaptive = true;
    let cap = h.capture(scene, cfg, camera).unwrap();
    let tris = h.capture_triangles(scene, cfg, camera).unwrap();
    h.adaptive = false;
    let (levels, _) = scene.drawn_levels(cfg);
    let n = levels.len();
    let drawn: Vec<_> = levels.iter().map(|l| tess_levels(cfg, l)).collect();
    let mut at: HashMap<[u32; 3], Vec<(usize, DVec2)>> = HashMap::new();
    let mut vertices = Vec::new();
    let mut seen = HashSet::new();
    for v in cap.vertices.iter().filter(|v| v.position[3] == 1.0) {
        let t = v.id[0] as usize;
        let (outer, inner) = drawn[t].expect("a drawn element");
        let tc = [v.coord[0], v.coord[1], v.coord[2]];
        let b = if cfg.glides() {
            geomorph_weights(
                tc,
                morph_weights(tc, outer, inner),
                outer,
                inner,
                &levels[t],
            )
        } else {
            tess_weights_levels(tc, outer, inner)
        };
        let q = DVec2::new(b[1] as f64, b[2] as f64);
        let key = [0, 1, 2].map(|k| v.position[k].to_bits());
        if seen.insert((t, key)) {
            at.entry(key).or_default().push((t, q));
            vertices.push((t, q, Vec3::from_slice(&v.position[..3])));
        }
    }
    let mut triangles = vec![Vec::new(); n];
    for tri in tris {
        let lists = tri.map(|v| &at[&v.position.map(f32::to_bits)]);
        let (t, _) = *lists[0]
            .iter()
            .find(|(t, _)| lists[1..].iter().all(|l| l.iter().any(|x| x.0 == *t)))
            .expect("a triangle's corners in one element");
        let q = lists.map(|l| l.iter().find(|x| x.0 == t).unwrap().1);
        triangles[t].push((q, tri.map(|v| Vec3::from(v.position))));
    }
    Drawn {
        triangles,
        vertices,
        levels: drawn,
    }
}

/// The drawn mesh of element `t` at parameter `q` (linear over the triangle containing it).
fn drawn_at(d: &Drawn, t: usize, q: DVec2) -> Option<Vec3> {
    for (p, x) in &d.triangles[t] {
        let area = (p[1] - p[0]).perp_dot(p[2] - p[0]);
        if area.abs() < 1e-12 {
            continue;
        }
        let wb = (q - p[0]).perp_dot(p[2] - p[0]) / area;
        let wc = (p[1] - p[0]).perp_dot(q - p[0]) / area;
        let wa = 1.0 - wb - wc;
        if wa >= -1e-7 && wb >= -1e-7 && wc >= -1e-7 {
            let s = x[0].as_dvec3() * wa + x[1].as_dvec3() * wb + x[2].as_dvec3() * wc;
            return Some(s.as_vec3());
        }
    }
    None
}

const SWEEP_SIZE: (u32, u32) = (1280, 720);

/// The popping sweep (docs/adaptivity.md, "Geomorphing") on the tess driver's real pipelines:
/// Spot as `pn` at 1 px, the camera moving 6% closer a frame for 12 frames; each drawn vertex's
/// screen motion less its surface point's, from where the mesh drawn the frame before had its
/// parameter. Returns (worst pop in pixels, vertices compared, level changes).
fn tess_sweep(h: &mut Headless, scene: &mut Scene, geomorph: bool) -> (f32, usize, usize) {
    let (c, r) = scene.bounding_sphere();
    let mut cfg = DrawConfig::new(Driver::Tess, 64).with_surface(Surface::Pn, Displace::None);
    cfg.params = SurfaceParams::for_radius(r);
    cfg.geomorph = geomorph;
    h.prepared_elements(scene, &cfg, Capture::Vertices).unwrap();
    let records = scene.records(cfg.surface).to_vec();
    let dir = Vec3::new(0.6, 0.35, 1.0).normalize();
    let (width, height) = SWEEP_SIZE;
    let size = Vec2::new(width as f32, height as f32);
    let pixel = |vp: &Mat4, p: Vec3| {
        let c = *vp * Vec4::new(p.x, p.y, p.z, 1.0);
        let inside = c.x.abs() <= c.w && c.y.abs() <= c.w && c.z >= 0.0 && c.z <= c.w;
        inside.then(|| (Vec2::new(c.x, c.y) / c.w + 1.0) * 0.5 * size)
    };
    let mut prev: Option<(Drawn, Mat4)> = None;
    let (mut worst, mut compared, mut changes) = (0.0f32, 0usize, 0usize);
    for k in 0..12 {
        let eye = c + dir * (3.0 * r * 0.94f32.powi(k));
        let camera = Camera::looking(eye, c, 45f32.to_radians(), r).unwrap();
        let vp = camera.view_proj(size.x / size.y);
        let now = draw_frame(h, scene, &cfg, &camera);
        if let Some((before, pvp)) = &prev {
            let mirror = scene.mirror(&cfg, 64).unwrap();
            changes += (now.levels.iter().zip(&before.levels))
                .filter(|(a, b)| a != b)
                .count();
            for &(t, q, x1) in &now.vertices {
                let Some(x0) = drawn_at(before, t, q) else {
                    continue;
                };
                let b = [1.0 - q.x - q.y, q.x, q.y].map(|x| x as f32);
                let p = mirror.eval(&cfg.params, t, &records[t], b).position;
                let (Some(s0), Some(s1), Some(p0), Some(p1)) =
                    (pixel(pvp, x0), pixel(&vp, x1), pixel(pvp, p), pixel(&vp, p))
                else {
                    continue;
                };
                let pop = ((s1 - s0) - (p1 - p0)).length();
                worst = worst.max(pop);
                compared += 1;
            }
        }
        prev = Some((now, vp));
    }
    (worst, compared, changes)
}

/// Geomorphing keeps the tessellator from popping: with it every drawn vertex moves on screen
/// at most 0.15 px more than its surface point does between frames, measured against the mesh
/// the GPU drew the frame before (measured 0.118 px, where a coarser edge doubles and a ring-1
/// vertex's parent on the snapped outer ring switches samples, docs/adaptivity.md "What
/// remains"), under the 0.2 px the sweep allows; without, the integer levels' changes (by one
/// level at a time, with the tessellator's own transitions) step by more (0.163 px). The
/// dyadic levels change less often than integer ones, so this comparison alone would not show
/// a morph that does nothing: `tess_geomorph_matches_the_mirror_and_is_watertight` checks every
/// morphing vertex against the mirror (hundreds of them mid-morph).
#[test]
fn tess_geomorphing_removes_popping() {
    with_gpu(64, 36, |h| {
        let mut scene = Scene::with_patterns(
            &h.ctx,
            &h.pool,
            &h.renderer,
            model("spot_control_tri.obj"),
            PatternSet::from_levels(&[64]),
        )
        .unwrap();
        let (on, n_on, changes) = tess_sweep(h, &mut scene, true);
        let (off, n_off, changes_off) = tess_sweep(h, &mut scene, false);
        eprintln!(
            "tess popping: geomorph on {on} px ({n_on} vertices, {changes} level changes), off {off} px ({n_off} vertices, {changes_off} level changes)"
        );
        assert!(changes > 100, "only {changes} level changes");
        assert!(n_on > 100_000 && n_off > 100_000);
        assert!(on <= 0.15, "geomorphing pops by {on} px");
        assert!(
            off > on,
            "without geomorphing only {off} px (with: {on} px): the test sees no popping"
        );
    });
}

/// The tess driver drawing adaptively at random levels (one per unique edge, shared; inner levels
/// at least their edges'): the evaluated vertices (capture) and the tessellator's triangles
/// (transform feedback, what export writes) weld on exact bits into exactly the vertex count of a
/// crack-free tessellation, and the triangles into a closed mesh, for every closed mesh and
/// surface, loop too. Levels equal everywhere draw exactly the uniform triangles.
#[test]
fn tess_adaptive_is_watertight() {
    with_gpu(64, 64, |h| {
        let loop_files = ["icosahedron.obj", "spot_control_tri.obj"];
        for (f, file) in CLOSED.iter().enumerate() {
            let mesh = model(file);
            let max = 9;
            let (mut scene, camera) = scene_at(h, &mesh, &[max]);
            let r = mesh.bounding_radius();
            let mut combos = SURFACES.to_vec();
            if loop_files.contains(file) {
                combos.push((Surface::Loop, Displace::None));
                combos.push((Surface::Loop, Displace::Sine));
            }
            for (c, &combo) in combos.iter().enumerate() {
                let cfg = config(Driver::Tess, max, combo, r);
                let seed = 31 * f as u32 + c as u32 + 1;
                check_tess_adaptive(h, &mut scene, &camera, &cfg, seed, file);
            }
            // Every element at level 4 adaptively: exactly the uniform level-4 triangles.
            if f < 3 {
                let cfg = config(Driver::Tess, 4, (Surface::Pn, Displace::None), r);
                let (mut scene, camera) = scene_at(h, &mesh, &[4]);
                let uniform = h.capture_triangles(&mut scene, &cfg, &camera).unwrap();
                let n = scene.gpu.element_count as usize;
                scene
                    .gpu
                    .upload_levels(&vec![ElementLevels::uniform(4.0); n]);
                h.adaptive = true;
                let adaptive = h.capture_triangles(&mut scene, &cfg, &camera).unwrap();
                h.adaptive = false;
                assert!(
                    adaptive == uniform,
                    "{file}: adaptive at level 4 everywhere differs from uniform level 4"
                );
            }
        }
    });
}

/// Culled elements (inner level 0) draw nothing: with every element culled the image is the
/// background and no triangle is written; with one drawn, exactly its triangles are.
#[test]
fn tess_culled_elements_draw_nothing() {
    with_gpu(64, 64, |h| {
        let mesh = model("spot_control_tri.obj");
        let r = mesh.bounding_radius();
        let (mut scene, camera) = scene_at(h, &mesh, &[6]);
        let cfg = config(Driver::Tess, 6, (Surface::Pn, Displace::None), r);
        let n = scene.gpu.element_count as usize;
        let mut levels = vec![ElementLevels::CULLED; n];
        scene.gpu.upload_levels(&levels);
        h.adaptive = true;
        let image = h.render(&mut scene, &cfg, &camera).unwrap();
        assert_eq!(meshrefine::render::covered_pixels(&image), 0);
        assert!(h
            .capture_triangles(&mut scene, &cfg, &camera)
            .unwrap()
            .is_empty());
        assert!(h
            .capture(&mut scene, &cfg, &camera)
            .unwrap()
            .vertices
            .is_empty());
        levels[5] = ElementLevels::uniform(3.0);
        scene.gpu.upload_levels(&levels);
        let tris = h.capture_triangles(&mut scene, &cfg, &camera).unwrap();
        assert_eq!(tris.len(), tess_triangle_count(3) as usize);
        let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
        assert!(cap.vertices.iter().all(|v| v.id[0] == 5));
        h.adaptive = false;
    });
}
