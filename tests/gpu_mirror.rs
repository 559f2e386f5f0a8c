//! The vertices the real drawing pipelines evaluated (read back through their capture variants)
//! equal the CPU mirror, for every GPU driver and submission mode, several meshes and levels.
//!
//! Tolerances:
//! - `pattern` positions: exact (0 ulp). The pattern stores the same barycentric floats the
//!   mirror uses, the flat surface is evaluated with `precise` (no FMA) in the same operation
//!   order, and Vulkan rounds fp32 add/multiply correctly.
//! - `tess` positions: 4 ulp of the mesh's bounding radius, the mirror evaluated at the captured
//!   gl_TessCoord. Edge samples are snapped to k/N on the GPU, and Vulkan's division is exact
//!   only to 2.5 ulp.
//! - normals (both): 1e-5 per component after normalization (GPU inversesqrt is not exact).

mod common;

use common::{model, with_gpu};
use meshrefine::mesh::Mesh;
use meshrefine::pattern::{lattice_index, Pattern, PatternSet};
use meshrefine::render::tess::tess_vertex_count;
use meshrefine::render::{Camera, DrawConfig, Driver, Headless, Scene, Submit};
use meshrefine::surface::{eval, tess_weights, Surface};
use std::collections::{HashMap, HashSet};

fn scene_with(h: &Headless, mesh: Mesh, levels: &[u32]) -> (Scene, Camera, f32) {
    let scene = Scene::with_patterns(
        &h.ctx,
        &h.pool,
        &h.renderer,
        mesh,
        PatternSet::from_levels(levels),
    )
    .unwrap();
    let (c, r) = scene.bounding_sphere();
    (scene, Camera::framing(c, r), r)
}

fn check_pattern(file: &str, h: &mut Headless, levels: &[u32]) {
    let (mut scene, camera, _) = scene_with(h, model(file), levels);
    for &level in levels {
        let pattern = Pattern::uniform(level);
        let pv = pattern.bary.len();
        for submit in Submit::ALL {
            let cfg = DrawConfig::new(Driver::Pattern, submit, level);
            let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
            assert_eq!(cap.vertices.len(), scene.data.records.len() * pv);
            for (t, rec) in scene.data.records.iter().enumerate() {
                for (k, (i, j)) in pattern.lattice().enumerate() {
                    assert_eq!(lattice_index(level, i, j) as usize, k);
                    let got = &cap.vertices[t * pv + k];
                    let what = format!(
                        "{file} {} L{level}: triangle {t} vertex ({i},{j})",
                        cfg.label()
                    );
                    assert_eq!(got.position[3], 1.0, "{what} never written");
                    assert_eq!(
                        got.id,
                        [t as u32, k as u32, 0, 0],
                        "{what}: wrong capture slot"
                    );
                    let want = eval(Surface::Flat, rec, pattern.bary[k]);
                    assert_eq!(
                        &got.position[..3],
                        &want.position.to_array()[..],
                        "{what}: position differs from the mirror"
                    );
                    for a in 0..3 {
                        assert!(
                            (got.normal[a] - want.normal[a]).abs() <= 1e-5,
                            "{what}: normal {:?} vs {:?}",
                            &got.normal[..3],
                            want.normal
                        );
                    }
                }
            }
        }
    }
}

fn check_tess(file: &str, h: &mut Headless, levels: &[u32]) {
    let (mut scene, camera, r) = scene_with(h, model(file), levels);
    let tol = 4.0 * f32::EPSILON * r;
    for &level in levels {
        let cfg = DrawConfig::new(Driver::Tess, Submit::Instanced, level);
        let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
        let mut coords: HashMap<u32, HashSet<[u32; 3]>> = HashMap::new();
        let mut worst = 0.0f32;
        for v in &cap.vertices {
            let t = v.id[0] as usize;
            assert_eq!(v.id[1], u32::MAX);
            assert_eq!(v.position[3], 1.0);
            let tc = [v.coord[0], v.coord[1], v.coord[2]];
            coords
                .entry(v.id[0])
                .or_default()
                .insert(tc.map(f32::to_bits));
            let want = eval(
                Surface::Flat,
                &scene.data.records[t],
                tess_weights(tc, level),
            );
            for a in 0..3 {
                let d = (v.position[a] - want.position[a]).abs();
                worst = worst.max(d);
                assert!(d <= tol, "{file} tess L{level}: triangle {t} at {tc:?}: {:?} vs mirror {:?} (tolerance {tol})", &v.position[..3], want.position);
                assert!(
                    (v.normal[a] - want.normal[a]).abs() <= 1e-5,
                    "{file} tess L{level}: normal at {tc:?}"
                );
            }
        }
        // Every patch was tessellated into exactly the expected set of distinct samples.
        assert_eq!(
            coords.len(),
            scene.data.records.len(),
            "{file} tess L{level}: patches missing"
        );
        for (t, set) in &coords {
            assert_eq!(
                set.len() as u32,
                tess_vertex_count(level),
                "{file} tess L{level}: triangle {t}"
            );
        }
        eprintln!(
            "{file} tess level {level}: {} evaluations, max position error {worst:e}",
            cap.vertices.len()
        );
    }
}

#[test]
fn pattern_matches_mirror_exactly() {
    with_gpu(64, 64, |h| {
        check_pattern("tetrahedron.obj", h, &[1, 2, 7, 64]);
        check_pattern("icosahedron_vn.obj", h, &[1, 5, 16]);
        check_pattern("grid_open_8x8.obj", h, &[3, 8]);
        check_pattern("cylinder_hard_normals.obj", h, &[4]);
        check_pattern("spot_control_tri.obj", h, &[6]);
    });
}

#[test]
fn tess_matches_mirror() {
    with_gpu(64, 64, |h| {
        // Level 64 on lavapipe exercises the split draws (20 patches per draw).
        check_tess("tetrahedron.obj", h, &[1, 2, 7, 64]);
        check_tess("icosahedron_vn.obj", h, &[3, 16]);
        check_tess("grid_open_8x8.obj", h, &[5]);
        check_tess("spot_control_tri.obj", h, &[6]);
    });
}

#[test]
fn record_fields_reach_every_submission_path() {
    // Sentinels: the corners of a pattern evaluate to exactly the record's positions and
    // (normalized) normals, and the capture slot is chosen by the record's triangle index, so a
    // record field landing at a wrong offset in push constants, the uniform block or the storage
    // buffer shows up here.
    use glam::Vec3;
    let positions = vec![
        Vec3::new(1.5, -2.25, 3.125),
        Vec3::new(-7.0, 0.5, 0.0625),
        Vec3::new(0.25, 9.0, -4.5),
        Vec3::new(3.0, 3.0, 3.0),
    ];
    let normals = vec![Vec3::X, Vec3::Y, Vec3::Z, Vec3::new(0.0, 0.6, 0.8)];
    let (mesh, _) = Mesh::from_parts(
        "sentinel",
        positions.clone(),
        Some(normals.clone()),
        vec![[0, 1, 2], [3, 2, 1]],
    )
    .unwrap();
    with_gpu(32, 32, |h| {
        let (mut scene, camera, _) = scene_with(h, mesh, &[1]);
        for submit in Submit::ALL {
            let cfg = DrawConfig::new(Driver::Pattern, submit, 1);
            let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
            // Level 1: vertices (0,0) -> corner 0, (1,0) -> corner 1, (0,1) -> corner 2.
            for (t, tri) in [[0usize, 1, 2], [3, 2, 1]].iter().enumerate() {
                for (k, &corner) in tri.iter().enumerate() {
                    let v = &cap.vertices[t * 3 + k];
                    assert_eq!(
                        &v.position[..3],
                        &positions[corner].to_array()[..],
                        "{} triangle {t} corner {k}",
                        cfg.label()
                    );
                    let n = Vec3::from_slice(&v.normal[..3]);
                    assert!(
                        (n - normals[corner].normalize()).length() < 1e-6,
                        "{} normal {n:?}",
                        cfg.label()
                    );
                }
            }
        }
        let cap = h
            .capture(
                &mut scene,
                &DrawConfig::new(Driver::Tess, Submit::Instanced, 1),
                &camera,
            )
            .unwrap();
        for v in &cap.vertices {
            let corner = [[0usize, 1, 2], [3, 2, 1]][v.id[0] as usize]
                [v.coord.iter().position(|&c| c == 1.0).unwrap()];
            assert_eq!(&v.position[..3], &positions[corner].to_array()[..]);
        }
    });
}
