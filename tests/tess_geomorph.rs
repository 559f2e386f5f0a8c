//! Geomorphing on the tess driver (docs/adaptivity.md, "Geomorphing"): the real pipelines
//! drawing at random continuous levels, read back, against the CPU mirror
//! (`render::tess::morph`), and the welded result closed.

mod common;

use common::random_levels::{element_corners, random_levels};
use common::{model, with_gpu};
use glam::Vec3;
use meshrefine::export::weld_triangles;
use meshrefine::lod::levels::ElementLevels;
use meshrefine::pattern::PatternSet;
use meshrefine::render::tess::morph::{geomorph_position, morph_levels};
use meshrefine::render::tess::{tess_vertex_count, tess_weights_levels};
use meshrefine::render::{Camera, Capture, DrawConfig, Driver, Scene};
use meshrefine::surface::{eval_with, Displace, Surface, SurfaceParams};
use std::collections::{HashMap, HashSet};

const MAX: u32 = 16;

/// Distinct vertices of a crack-free geomorphing tessellation: every corner once, each unique
/// edge its own dyadic level's inner samples, each element the inner rings of its inner level.
fn expected_vertices(corners: &[[u32; 3]], levels: &[ElementLevels]) -> usize {
    let mut vertices = HashSet::new();
    let mut edge_samples = HashMap::new();
    let mut inside = 0;
    for (c, l) in corners.iter().zip(levels) {
        let (outer, inner) = morph_levels(l, MAX).unwrap();
        inside += (tess_vertex_count(inner) - 3 * inner) as usize;
        for i in 0..3 {
            vertices.insert(c[i]);
            let (a, b) = (c[(i + 1) % 3], c[(i + 2) % 3]);
            edge_samples.insert((a.min(b), a.max(b)), outer[i] as usize - 1);
        }
    }
    vertices.len() + edge_samples.values().sum::<usize>() + inside
}

/// Welded edges shared by other than two triangles.
fn open_edges(triangles: &[[(u32, u32); 3]]) -> usize {
    let mut count: HashMap<(u32, u32), u32> = HashMap::new();
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k].0, t[(k + 1) % 3].0);
            *count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    count.values().filter(|&&c| c != 2).count()
}

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
            let inputs = scene.inputs(MAX);
            let eps = f32::EPSILON * r;
            // Loop: sums of table-weighted M1 points (M1 made by the GPU's Loop pass).
            let base = if surface == Surface::Loop { 64.0 } else { 16.0 };
            let tol = (base + 4.0) * eps
                + match displace {
                    Displace::Sine => 2e-3 * cfg.params.amplitude.abs() + 8.0 * eps,
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
                let w = tess_weights_levels(tc, outer, inner);
                let element = inputs.element(t);
                let eval = |b: [f32; 3]| {
                    eval_with(surface, displace, &cfg.params, &records[t], b, &element).position
                };
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
                expected_vertices(&corners, &levels),
                "{what}: welded vertices"
            );
            assert_eq!(open_edges(&welded.triangles), 0, "{what}: cracks");
            h.adaptive = false;
        }
    });
}
