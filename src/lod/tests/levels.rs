//! Shared edges' bits, the continuous level, and the spheres around displaced patches.

use super::*;

/// Two elements that share an edge compute its bounds (and so its level) to the same bits.
#[test]
fn shared_edges_get_identical_bits() {
    let (spot, recs) = corner_records("spot_control_tri_vn.obj");
    let (tags, _) = crate::surface::stpn::derive(&spot);
    let params = SurfaceParams::for_radius(spot.bounding_radius());
    let view = View::new(Vec3::new(0.3, 0.2, 2.5), 0.8, 1080, 1.0, 64);
    let bits = |b: &Bounds| {
        [
            b.chord.c1.to_bits(),
            b.chord.c2.to_bits(),
            b.sphere.radius.to_bits(),
            b.sphere.centre.x.to_bits(),
            b.sphere.centre.y.to_bits(),
            b.sphere.centre.z.to_bits(),
            view.level(&b.chord, &b.sphere).to_bits(),
        ]
    };
    let mut sides: std::collections::HashMap<(u32, u32), Vec<(usize, usize)>> = Default::default();
    for (t, tri) in spot.triangles.iter().enumerate() {
        for e in 0..3 {
            let (a, b) = (tri.p[e], tri.p[(e + 1) % 3]);
            sides.entry((a.min(b), a.max(b))).or_default().push((t, e));
        }
    }
    let mut compared = 0;
    for surface in [Surface::Flat, Surface::Phong, Surface::Pn, Surface::Stpn] {
        for displace in [Displace::None, Displace::Sine, Displace::Noise] {
            let inputs = Sources {
                tags: Some(&tags),
                ..Default::default()
            };
            let lod = Lod::of(surface, displace, &params, &inputs);
            for s in sides.values().filter(|s| s.len() == 2) {
                let a = lod.edge(&recs[s[0].0], s[0].1);
                let b = lod.edge(&recs[s[1].0], s[1].1);
                assert_eq!(
                    bits(&a),
                    bits(&b),
                    "{} + {}",
                    surface.name(),
                    displace.name()
                );
                compared += 1;
            }
        }
    }
    assert!(compared > 1000);
    // Hard edges: seams and crease corners (whose sharp normal depends on the side).
    let (cyl, cyl_recs) = corner_records("cylinder_hard_normals.obj");
    let (cyl_tags, _) = crate::surface::stpn::derive(&cyl);
    let inputs = Sources {
        tags: Some(&cyl_tags),
        ..Default::default()
    };
    let mut sides: std::collections::HashMap<(u32, u32), Vec<(usize, usize)>> = Default::default();
    for (t, tri) in cyl.triangles.iter().enumerate() {
        for e in 0..3 {
            let (a, b) = (tri.p[e], tri.p[(e + 1) % 3]);
            sides.entry((a.min(b), a.max(b))).or_default().push((t, e));
        }
    }
    for surface in [Surface::Phong, Surface::Pn, Surface::Stpn] {
        for displace in [Displace::None, Displace::Sine] {
            let lod = Lod::of(surface, displace, &params, &inputs);
            for s in sides.values().filter(|s| s.len() == 2) {
                let a = lod.edge(&cyl_recs[s[0].0], s[0].1);
                let b = lod.edge(&cyl_recs[s[1].0], s[1].1);
                assert_eq!(
                    bits(&a),
                    bits(&b),
                    "cylinder {} + {}",
                    surface.name(),
                    displace.name()
                );
            }
        }
    }
    // Loop: M1's edges, through their owners.
    let (mesh, _) = load_model("spot_control_tri.obj");
    let data = LoopData::new(&mesh, Boundary::EdgeOnly, Lattice::new(3), |_| {}).unwrap();
    let frame = data.frame(&mesh.positions);
    let inputs = Sources {
        loop_: Some((&data, &frame)),
        ..Default::default()
    };
    let lod = Lod::of(Surface::Loop, Displace::None, &params, &inputs);
    let mut sides: std::collections::HashMap<(u32, u32), Vec<(usize, usize)>> = Default::default();
    for (f, face) in data.m1.faces.iter().enumerate() {
        for e in 0..3 {
            let (a, b) = (face[e], face[(e + 1) % 3]);
            sides.entry((a.min(b), a.max(b))).or_default().push((f, e));
        }
    }
    for s in sides.values().filter(|s| s.len() == 2) {
        let a = lod.edge(&data.records[s[0].0], s[0].1);
        let b = lod.edge(&data.records[s[1].0], s[1].1);
        assert_eq!(bits(&a), bits(&b), "loop");
    }
}

/// The continuous level is the root of the bound: its ceiling meets the tolerance and the
/// integer below does not; an eye inside the sphere gets the maximum level.
#[test]
fn levels_are_the_smallest_that_meet_the_error() {
    let view = View::new(Vec3::ZERO, 0.9, 1000, 0.5, 300);
    let sphere = Sphere {
        centre: Vec3::new(0.0, 0.0, -10.0),
        radius: 1.0,
    };
    let tol = view.tolerance(&sphere);
    assert!((tol - 0.5 * 9.0 / view.k).abs() < 1e-6 * tol);
    for (c1, c2) in [
        (0.0, 0.3),
        (0.01, 0.0),
        (0.004, 0.2),
        (0.0, 1e-4),
        (0.0, 0.0),
    ] {
        let chord = Chord { c1, c2 };
        let l = view.level(&chord, &sphere);
        let n = integer_level(l);
        assert!(l >= 1.0 && (n as f32) >= l && (n as f32) < l + 1.0);
        assert!(chord.error(n as f32) <= tol, "{c1} {c2}: level {n}");
        if n > 1 {
            assert!(
                chord.error((n - 1) as f32) > tol,
                "{c1} {c2}: {n} is not the smallest"
            );
        }
    }
    let inside = Sphere {
        centre: Vec3::new(0.0, 0.0, -0.5),
        radius: 1.0,
    };
    assert_eq!(view.level(&Chord { c1: 0.0, c2: 1e-9 }, &inside), 300.0);
    assert_eq!(
        view.level(
            &Chord {
                c1: 0.0,
                c2: f32::INFINITY
            },
            &sphere
        ),
        300.0
    );
    assert_eq!(dyadic(5), 8);
    assert_eq!(dyadic(8), 8);
}

/// Every sampled point of every surface and displacement is inside its element's sphere, and
/// every point of an edge inside the edge's (what frustum culling and the levels' distances
/// rely on): Spot as each surface (`stpn` with its derived tags, `loop` from its tables)
/// undisplaced, with sine and with noise, and the terrain with the height map at its own
/// texture coordinates.
#[test]
fn spheres_contain_the_displaced_patch() {
    let (spot, recs) = corner_records("spot_control_tri_vn.obj");
    let params = SurfaceParams {
        octaves: 3,
        ..SurfaceParams::for_radius(spot.bounding_radius())
    };
    let (tags, _) = crate::surface::stpn::derive(&spot);
    let (plain, _) = load_model("spot_control_tri.obj");
    let data = LoopData::new(&plain, Boundary::EdgeOnly, Lattice::default(), |_| {}).unwrap();
    let frame = data.frame(&plain.positions);
    let (loop_recs, spot_recs) = (every(&data.records, 4), every(&recs, 3));
    for surface in Surface::ALL {
        for displace in [Displace::None, Displace::Sine, Displace::Noise] {
            let case = Case {
                surface,
                field: NormalField::default(),
                displace,
                params,
                inputs: Sources {
                    tags: Some(&tags),
                    loop_: Some((&data, &frame)),
                    ..Default::default()
                },
            };
            let records = match surface {
                Surface::Loop => &loop_recs,
                _ => &spot_recs,
            };
            check_spheres(&case, records);
        }
    }
    let (terrain, terrain_recs, uvs) = super::heightmap::textured("terrain_16x16.obj");
    let map = Heightmap::generated();
    for surface in [Surface::Flat, Surface::Phong, Surface::Pn] {
        let case = Case {
            surface,
            field: NormalField::default(),
            displace: Displace::Heightmap,
            params: SurfaceParams {
                amplitude: 0.05 * terrain.bounding_radius(),
                bias: 0.5,
                ..Default::default()
            },
            inputs: Sources {
                uvs: Some(&uvs),
                heightmap: Some(&map),
                lod: 1.0,
                ..Default::default()
            },
        };
        for t in (0..terrain_recs.len()).step_by(5) {
            check_spheres(&case.element(t), std::slice::from_ref(&terrain_recs[t]));
        }
    }
}

/// Every lattice point of level 9 of each of `records` lies in its element's sphere, and each
/// on an edge in that edge's sphere.
fn check_spheres(case: &Case, records: &[ElementRecord]) {
    let lod = case.lod();
    let what = || format!("{} + {}", case.surface.name(), case.displace.name());
    for rec in records {
        let s = lod.element(rec).sphere;
        let edges = [0, 1, 2].map(|e| lod.edge(rec, e).sphere);
        for (i, j) in crate::pattern::Pattern::uniform(9).lattice() {
            let b = lattice_bary(9, i, j);
            let p = case.at(rec, b);
            assert!((p - s.centre).length() <= s.radius, "{}", what());
            for e in 0..3 {
                if b[(e + 2) % 3] == 0.0 {
                    let d = (p - edges[e].centre).length();
                    assert!(d <= edges[e].radius, "{}: edge sphere", what());
                }
            }
        }
    }
}
