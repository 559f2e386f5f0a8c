//! The loop surface at dyadic levels is the limit surface: the vertices the pattern driver's
//! pipelines evaluate at level N = 2^k (k <= 5, lattice rows of the tables) equal the limit
//! positions of M^(1 + k) (the CPU reference, itself checked against OpenSubdiv by
//! scripts/check-loop-osd.sh) within 1e-5 of the bounding-box diagonal: closed meshes (valences
//! 3 to 16, and a sphere with valence-40 poles), open meshes with both boundary rules, and a
//! vertex of valence 24 (beyond the 2010 paper's tables, which stop at 18). Validation on.

mod common;

use common::{model, with_gpu};
use meshrefine::pattern::{Pattern, PatternSet};
use meshrefine::render::{Camera, DrawConfig, Driver, Scene, Submit};
use meshrefine::subdiv::bft::children_in_lattice;
use meshrefine::subdiv::{subdivide_to_limit, Boundary};
use meshrefine::surface::{BuildOptions, Displace, Surface, SurfaceParams};

/// `mesh` uploaded with the patterns of `levels`, and a camera framing it; and its radius.
fn scene(
    h: &meshrefine::render::Headless,
    mesh: meshrefine::mesh::Mesh,
    levels: &[u32],
) -> (Scene, Camera, f32) {
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

#[test]
fn dyadic_levels_are_the_limit_surface() {
    let all = vec![1u32, 2, 4, 8, 32];
    let mut cases: Vec<(String, meshrefine::mesh::Mesh, Boundary, Vec<u32>, u32)> = [
        ("spot_control_tri.obj", Boundary::EdgeOnly),
        ("bicone16.obj", Boundary::EdgeOnly),
        ("fan24_open.obj", Boundary::EdgeOnly),
        ("halfdisc17_open.obj", Boundary::EdgeOnly),
        ("grid_open_8x8.obj", Boundary::EdgeAndCorner),
        ("spot_open.obj", Boundary::EdgeOnly),
    ]
    .into_iter()
    .map(|(f, b)| (f.to_string(), model(f), b, all.clone(), 5))
    .collect();
    // A coarser table (--bft-level 3): its lattice is level 8.
    cases.push((
        "spot_control_tri.obj, table level 3".into(),
        model("spot_control_tri.obj"),
        Boundary::EdgeOnly,
        vec![1, 2, 4, 8],
        3,
    ));
    // Two valence-40 poles: configuration meshes pruned level by level (src/subdiv/bft/table.rs); the
    // reference at level 32 (M^6) would be 1.6 M faces, so up to 8 here.
    cases.push((
        "sphere, valence-40 poles".into(),
        meshrefine::mesh::generate::sphere_mesh(40, 6),
        Boundary::EdgeOnly,
        vec![1, 2, 4, 8],
        5,
    ));
    with_gpu(64, 64, |h| {
        for (file, mesh, boundary, levels, bft_level) in cases {
            let levels = &levels[..];
            let (mut scene, camera, r) = scene(h, mesh.clone(), levels);
            let (lo, hi) = mesh.bounds();
            let diag = (hi - lo).length() as f64;
            for &n in levels {
                let k = n.trailing_zeros();
                let mut cfg = DrawConfig::new(Driver::Pattern(Submit::Instanced), n)
                    .with_surface(Surface::Loop, Displace::None);
                cfg.params = SurfaceParams::for_radius(r);
                cfg.build = BuildOptions {
                    boundary,
                    bft_level,
                    ..BuildOptions::default()
                };
                let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
                let reference = subdivide_to_limit(&mesh, 1 + k, boundary).unwrap();
                let pattern = Pattern::uniform(n);
                let pv = pattern.bary.len();
                // Pattern vertex (i, j) of M1 face f is the vertex of M^(1+k) that face f's
                // sub-faces (4f + child, k times) have at lattice (i, j) in units of 1/n.
                let faces = scene.records(Surface::Loop).len();
                let mut worst: f64 = 0.0;
                let mut lattice = std::collections::HashMap::new();
                for f in 0..faces {
                    let mut tracked = vec![(f, [[0, 0], [n, 0], [0, n]])];
                    for _ in 0..k {
                        tracked = children_in_lattice(&tracked);
                    }
                    lattice.clear();
                    for (face, coords) in &tracked {
                        for (c, &v) in coords.iter().zip(&reference.faces[*face]) {
                            lattice.insert((c[0], c[1]), v);
                        }
                    }
                    for (idx, (i, j)) in pattern.lattice().enumerate() {
                        let got = &cap.vertices[f * pv + idx].position;
                        let want = reference.positions[lattice[&(i, j)] as usize];
                        let d = ((got[0] as f64 - want.x).powi(2)
                            + (got[1] as f64 - want.y).powi(2)
                            + (got[2] as f64 - want.z).powi(2))
                        .sqrt();
                        worst = worst.max(d / diag);
                    }
                }
                eprintln!(
                    "{file} {boundary:?} level {n}: max distance {worst:.2e} of the diagonal"
                );
                assert!(
                    worst <= 1e-5,
                    "{file} {boundary:?} level {n}: {worst:e} of the diagonal from M^(1+{k})'s limit"
                );
            }
        }
    });
}

/// An animated coarse mesh drawn with loop uploads M0's positions alone (16 bytes a vertex,
/// whatever the level), and what the pipelines then evaluate follows the new M0: equal to the
/// mirror on the moved mesh (the GPU's M0 -> M1 and normals passes ran again).
#[test]
fn animated_loop_uploads_m0_only() {
    with_gpu(64, 64, |h| {
        let base = model("spot_control_tri.obj");
        let levels = [4u32, 16];
        let (mut scene, camera, r) = scene(h, base.clone(), &levels);
        let cfg = |n| {
            DrawConfig::new(Driver::Pattern(Submit::Instanced), n)
                .with_surface(Surface::Loop, Displace::None)
        };
        h.draw(&mut scene, &cfg(4), &camera).unwrap();
        let m0_bytes = base.positions.len() as u64 * 16;
        for n in levels {
            assert_eq!(scene.upload_bytes(&cfg(n)), m0_bytes, "level {n}");
        }
        for frame in 1..3 {
            let moved = base.animated(frame as f32 * 0.7, 0.05 * r);
            scene.update_mesh(moved);
            let cap = h.capture(&mut scene, &cfg(4), &camera).unwrap();
            let mirror = scene.mirror(&cfg(4), 4).unwrap();
            let pattern = Pattern::uniform(4);
            let pv = pattern.bary.len();
            for (t, rec) in scene.records(Surface::Loop).iter().enumerate() {
                for (k, &b) in pattern.bary.iter().enumerate() {
                    let want = mirror.eval(&cfg(4).params, t, rec, b);
                    let got = &cap.vertices[t * pv + k].position;
                    let d = (glam::Vec3::new(got[0], got[1], got[2]) - want.position).length();
                    assert!(
                        d <= 64.0 * f32::EPSILON * r,
                        "frame {frame} face {t}: {d:e}"
                    );
                }
            }
        }
    });
}
