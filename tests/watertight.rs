//! Refinement is watertight by construction: a point on a shared coarse edge is evaluated from
//! that edge's data alone, in a canonical order, so neighbouring triangles produce bit-identical
//! positions in every driver. Checked by welding the evaluated vertices on exact position bits:
//! on a closed mesh the welded vertex count is exactly what a crack-free refinement has, and the
//! welded pattern mesh is closed (every edge shared by two triangles).
//!
//! Run on the curved surfaces too, and with displacement: on `flat` (and `phong`) an edge point is
//! a sum of two non-zero terms and addition commutes, so those stay watertight even without the
//! canonical order (`flat` is evaluated in stored order for that reason); `pn`'s cubic weight products do not (see the unit test
//! `stored_order_breaks_bit_identity_on_curved_surfaces`), so these tests fail if the canonical
//! order is removed.

mod common;

use common::watertight::{
    assert_closed, bits, check_tess_adaptive, config, scene_at, tess_positions, CLOSED, SURFACES,
};
use common::{model, with_gpu};
use meshrefine::export::{weld, weld_triangles};
use meshrefine::mesh::Mesh;
use meshrefine::pattern::Pattern;
use meshrefine::render::static_vbo::refine_on_cpu;
use meshrefine::render::tess::{tess_triangle_count, tess_vertex_count};
use meshrefine::render::{DrawConfig, Driver, Submit};
use meshrefine::subdiv::{LoopData, LoopFrame};
use meshrefine::surface::{Displace, NormalField, RecordKind, Seams, Surface};
use std::collections::HashSet;

/// Distinct positions of `records` refined on the CPU at level `n`.
fn static_positions(
    cfg: &DrawConfig,
    records: &[meshrefine::surface::ElementRecord],
    mesh: &Mesh,
) -> usize {
    static_positions_with(cfg, records, mesh, None)
}

/// [`static_positions`] with the loop surface's tables and M1.
fn static_positions_with(
    cfg: &DrawConfig,
    records: &[meshrefine::surface::ElementRecord],
    mesh: &Mesh,
    loop_: Option<(&LoopData, &LoopFrame)>,
) -> usize {
    // The scalar tags a scene derives from the mesh's hard edges (stpn).
    let (tags, _) = meshrefine::surface::stpn::derive(mesh);
    let sources = meshrefine::surface::Sources {
        tags: Some(&tags),
        loop_,
        ..Default::default()
    };
    let mirror =
        meshrefine::surface::Mirror::new(cfg.surface, cfg.displace, &cfg.build, &sources).unwrap();
    let (v, _) = refine_on_cpu(cfg, records, &Pattern::uniform(cfg.level), &mirror);
    let distinct: HashSet<[u32; 3]> = v.iter().map(|x| bits(&x[..3])).collect();
    distinct.len()
}

fn edges(mesh: &Mesh) -> usize {
    let mut e = HashSet::new();
    for t in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (t.p[k], t.p[(k + 1) % 3]);
            e.insert((a.min(b), a.max(b)));
        }
    }
    e.len()
}

/// Distinct vertices of a crack-free refinement with `inner` vertices strictly inside each patch.
fn expected(mesh: &Mesh, n: usize, inner: usize) -> usize {
    let v = mesh.stats().vertices;
    v + edges(mesh) * (n - 1) + mesh.triangles.len() * inner
}

#[test]
fn static_driver_is_watertight() {
    for file in CLOSED {
        let mesh = model(file);
        let records = meshrefine::surface::build_records(RecordKind::Corners, &mesh, Seams::Closed);
        let r = mesh.bounding_radius();
        for &combo in SURFACES {
            for n in [2u32, 5, 16] {
                let cfg = config(Driver::Static, n, combo, r);
                let inner = ((n - 1) * (n - 2) / 2) as usize;
                assert_eq!(
                    static_positions(&cfg, &records, &mesh),
                    expected(&mesh, n as usize, inner),
                    "{file} {} + {} static level {n}",
                    combo.0.name(),
                    combo.1.name()
                );
            }
        }
    }
}

#[test]
fn pattern_and_tess_are_watertight() {
    with_gpu(64, 64, |h| {
        for file in CLOSED {
            let mesh = model(file);
            let levels = [3u32, 8];
            let (mut scene, camera) = scene_at(h, &mesh, &levels);
            let r = mesh.bounding_radius();
            for (n, &combo) in levels
                .iter()
                .flat_map(|&n| SURFACES.iter().map(move |c| (n, c)))
            {
                let name = format!("{} + {}", combo.0.name(), combo.1.name());
                for submit in Submit::ALL {
                    let cfg = config(Driver::Pattern(submit), n, combo, r);
                    let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
                    let welded = weld(&cap, &Pattern::uniform(n)).unwrap();
                    let inner = ((n - 1) * (n - 2) / 2) as usize;
                    let what = format!("{file} {name} {} level {n}", cfg.label());
                    assert_eq!(
                        welded.positions.len(),
                        expected(&mesh, n as usize, inner),
                        "{what}"
                    );
                    assert_closed(&welded.triangles, &what);
                }
                let cfg = config(Driver::Tess, n, combo, r);
                let inner = (tess_vertex_count(n) - 3 * n) as usize;
                assert_eq!(
                    tess_positions(h, &mut scene, &cfg, &camera),
                    expected(&mesh, n as usize, inner),
                    "{file} {name} tess level {n}"
                );
                // The tessellator's triangles (transform feedback) weld into a closed mesh too.
                let tris = h.capture_triangles(&mut scene, &cfg, &camera).unwrap();
                assert_eq!(
                    tris.len(),
                    mesh.triangles.len() * tess_triangle_count(n) as usize
                );
                let welded = weld_triangles(&tris);
                assert_eq!(
                    welded.positions.len(),
                    expected(&mesh, n as usize, inner),
                    "{file} {name} tess triangles level {n}"
                );
                assert_closed(
                    &welded.triangles,
                    &format!("{file} {name} tess triangles level {n}"),
                );
            }
        }
    });
}

/// `[pattern, tess]` (configurations at one level) weld crack-free on `mesh`: the pattern's
/// captured vertices into a closed mesh of a crack-free refinement's vertex count, the
/// tessellator's evaluated positions into that count.
fn crack_free_on_pattern_and_tess(
    h: &mut meshrefine::render::Headless,
    scene: &mut meshrefine::render::Scene,
    camera: &meshrefine::render::Camera,
    mesh: &Mesh,
    [pattern, tess]: &[DrawConfig; 2],
    name: &str,
) {
    let n = pattern.level;
    let cap = h.capture(scene, pattern, camera).unwrap();
    let welded = weld(&cap, &Pattern::uniform(n)).unwrap();
    let inner = ((n - 1) * (n - 2) / 2) as usize;
    let want = expected(mesh, n as usize, inner);
    assert_eq!(welded.positions.len(), want, "{name} pattern");
    assert_closed(&welded.triangles, &format!("{name} pattern"));
    let inner = (tess_vertex_count(n) - 3 * n) as usize;
    let want = expected(mesh, n as usize, inner);
    assert_eq!(tess_positions(h, scene, tess, camera), want, "{name} tess");
}

/// Every local surface with every procedural displacement (the combinations `SURFACES` leaves
/// out among them, each its own pipeline) is watertight on the pattern driver and the
/// tessellator, on smooth meshes (`stpn` displaced opens at creases by design:
/// docs/surfaces.md, "Limits"; the height map is welded on its own, it needs texture
/// coordinates).
#[test]
fn every_surface_and_displacement_is_watertight() {
    with_gpu(64, 64, |h| {
        for file in ["spot_control_tri.obj", "torus_16x8.obj"] {
            let mesh = model(file);
            let n = 3u32;
            let (mut scene, camera) = scene_at(h, &mesh, &[n]);
            let r = mesh.bounding_radius();
            for s in Surface::LOCAL {
                for d in [Displace::None, Displace::Sine, Displace::Noise] {
                    let name = format!("{file} {} + {} level {n}", s.name(), d.name());
                    let cfgs = [Driver::Pattern(Submit::Instanced), Driver::Tess]
                        .map(|driver| config(driver, n, (s, d), r));
                    crack_free_on_pattern_and_tess(h, &mut scene, &camera, &mesh, &cfgs, &name);
                }
            }
        }
    });
}

/// `stpn` with tags of its own (tension, sharpness and bias at every vertex, two creases: what a
/// tags file gives) stays watertight on the pattern driver and the tessellator: an edge's
/// coefficients come from its two corners' tags alone, and at a crease both sides move along
/// the same direction.
#[test]
fn stpn_with_its_own_tags_is_watertight() {
    with_gpu(64, 64, |h| {
        let mesh = model("icosahedron_vn.obj");
        let n = 4u32;
        let (mut scene, camera) = scene_at(h, &mesh, &[n]);
        let tags = common::own_tags(&mesh);
        scene.set_tags(&h.ctx, &h.pool, &h.renderer, tags).unwrap();
        let r = mesh.bounding_radius();
        let combo = (Surface::Stpn, Displace::None);
        let cfgs = [Driver::Pattern(Submit::Instanced), Driver::Tess]
            .map(|driver| config(driver, n, combo, r));
        crack_free_on_pattern_and_tess(h, &mut scene, &camera, &mesh, &cfgs, "stpn, own tags");
    });
}

/// Displacement moves along `pn`'s and `stpn`'s normal field: every field keeps every driver
/// watertight (the field on a shared edge depends on the edge's corners alone, in canonical
/// order, like the geometry), on smooth and on split normals. `stpn` is displaced only on
/// meshes without creases: at a crease vertex each side moves along its own sharp normal, so
/// displaced creases open whatever the field (docs/surfaces.md, "Limits").
#[test]
fn every_normal_field_is_watertight_under_displacement() {
    with_gpu(64, 64, |h| {
        for file in [
            "icosahedron.obj",
            "spot_control_tri.obj",
            "cylinder_hard_normals.obj",
            // The field vanishes in the middle of an edge: both sides take the same normal.
            "octahedron_opposite_vn.obj",
        ] {
            let mesh = model(file);
            let records =
                meshrefine::surface::build_records(RecordKind::Corners, &mesh, Seams::Closed);
            let n = 4u32;
            let (mut scene, camera) = scene_at(h, &mesh, &[n]);
            let r = mesh.bounding_radius();
            let creases = meshrefine::surface::stpn::derive(&mesh)
                .0
                .iter()
                .any(|t| t.crease());
            let mut combos = vec![(Surface::Pn, Displace::Noise)];
            if !creases {
                combos.push((Surface::Stpn, Displace::Sine));
            }
            for field in NormalField::ALL {
                for &combo in &combos {
                    let name = format!(
                        "{file} {} ({}) + {}",
                        combo.0.name(),
                        field.name(),
                        combo.1.name()
                    );
                    let with_field = |driver| {
                        let mut cfg = config(driver, n, combo, r);
                        cfg.build.normal_field = field;
                        cfg
                    };
                    let inner = ((n - 1) * (n - 2) / 2) as usize;
                    let want = expected(&mesh, n as usize, inner);
                    let cfg = with_field(Driver::Static);
                    assert_eq!(
                        static_positions(&cfg, &records, &mesh),
                        want,
                        "{name} static"
                    );
                    for submit in Submit::ALL {
                        let cfg = with_field(Driver::Pattern(submit));
                        let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
                        let welded = weld(&cap, &Pattern::uniform(n)).unwrap();
                        let what = format!("{name} {}", cfg.label());
                        assert_eq!(welded.positions.len(), want, "{what}");
                        assert_closed(&welded.triangles, &what);
                    }
                    let cfg = with_field(Driver::Tess);
                    let inner = (tess_vertex_count(n) - 3 * n) as usize;
                    assert_eq!(
                        tess_positions(h, &mut scene, &cfg, &camera),
                        expected(&mesh, n as usize, inner),
                        "{name} tess"
                    );
                }
            }
        }
    });
}

/// With the papers' open seams, PN and Phong crack at split normals: the cylinder, whose rim
/// carries radial and axial normals, welds into more vertices than a crack-free refinement has
/// (this is what `--pn-seams closed` fixes). A cube with face normals does not crack even open:
/// its edges are perpendicular to every normal there, so both surfaces keep them straight.
#[test]
fn open_seams_crack_at_split_normals() {
    for file in ["cylinder_hard_normals.obj"] {
        let mesh = model(file);
        let records = meshrefine::surface::build_records(RecordKind::Corners, &mesh, Seams::Open);
        let r = mesh.bounding_radius();
        for surface in [Surface::Phong, Surface::Pn] {
            let n = 5;
            let mut cfg = config(Driver::Static, n, (surface, Displace::None), r);
            cfg.build.seams = Seams::Open;
            let crack_free = expected(&mesh, n as usize, ((n - 1) * (n - 2) / 2) as usize);
            let got = static_positions(&cfg, &records, &mesh);
            assert!(
                got > crack_free,
                "{file} {} with open seams: {got} distinct positions, not more than the crack-free {crack_free}",
                surface.name()
            );
        }
    }
}

/// The height map is watertight where texture coordinates are continuous: a point on a shared
/// edge reads the map at coordinates interpolated from the edge's ends in canonical order, so
/// both sides displace it alike. (At UV seams, where a position carries several `vt`, the two
/// sides read different places of the map: see docs/surfaces.md.)
#[test]
fn heightmap_on_continuous_coordinates_is_watertight() {
    let file = "grid_uv_8x8.obj";
    let mesh = model(file);
    let r = mesh.bounding_radius();
    let combo = (Surface::Pn, Displace::Heightmap);
    with_gpu(64, 64, |h| {
        let levels = [3u32, 8];
        let (mut scene, camera) = scene_at(h, &mesh, &levels);
        for n in levels {
            let inner = ((n - 1) * (n - 2) / 2) as usize;
            let want = expected(&mesh, n as usize, inner);
            let cfg = config(Driver::Static, n, combo, r);
            let (v, _) = refine_on_cpu(
                &cfg,
                &scene.data.records,
                &Pattern::uniform(n),
                &scene.mirror(&cfg, n).unwrap(),
            );
            let distinct: HashSet<[u32; 3]> = v.iter().map(|x| bits(&x[..3])).collect();
            assert_eq!(distinct.len(), want, "{file} static level {n}");
            for submit in Submit::ALL {
                let cfg = config(Driver::Pattern(submit), n, combo, r);
                let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
                let welded = weld(&cap, &Pattern::uniform(n)).unwrap();
                assert_eq!(
                    welded.positions.len(),
                    want,
                    "{file} {} level {n}",
                    cfg.label()
                );
            }
            let cfg = config(Driver::Tess, n, combo, r);
            let inner = (tess_vertex_count(n) - 3 * n) as usize;
            assert_eq!(
                tess_positions(h, &mut scene, &cfg, &camera),
                expected(&mesh, n as usize, inner),
                "{file} tess level {n}"
            );
        }
        // At random levels per edge (each edge's samples read the map alike from both sides).
        let cfg = config(Driver::Tess, 8, combo, r);
        check_tess_adaptive(h, &mut scene, &camera, &cfg, 7, file);
    });
}

/// Loop's limit surface is watertight by ownership (src/surface/loop.rs): a sample on a
/// shared M1 edge or corner is evaluated by its owner from both sides. Every driver's vertices
/// weld on exact bits into exactly the vertex count of a crack-free refinement of M1, and the
/// welded pattern and tessellator meshes are closed; at levels dividing 32 (lattice rows) and
/// not (interpolated), with displacement too.
#[test]
fn loop_is_watertight_on_every_driver() {
    use meshrefine::subdiv::Boundary;
    let files = [
        "tetrahedron.obj",
        "icosahedron.obj",
        "torus_16x8.obj",
        "bicone16.obj",
        "spot_control_tri.obj",
    ];
    with_gpu(64, 64, |h| {
        for file in files {
            let mesh = model(file);
            let data =
                LoopData::new(&mesh, Boundary::EdgeOnly, Default::default(), |_| {}).unwrap();
            let frame = data.frame(&mesh.positions);
            let m1_edges = data.m1.twin.len() / 2;
            let m1_expected = |n: u32, inner: usize| {
                data.m1.vertex_count + m1_edges * (n as usize - 1) + data.m1.faces.len() * inner
            };
            let levels = [3u32, 8];
            let (mut scene, camera) = scene_at(h, &mesh, &levels);
            let r = mesh.bounding_radius();
            for n in levels {
                for combo in [
                    (Surface::Loop, Displace::None),
                    (Surface::Loop, Displace::Noise),
                ] {
                    let name = format!("{file} loop + {} level {n}", combo.1.name());
                    let inner = ((n - 1) * (n - 2) / 2) as usize;
                    // static: the mirror.
                    let cfg = config(Driver::Static, n, combo, r);
                    let distinct =
                        static_positions_with(&cfg, &data.records, &mesh, Some((&data, &frame)));
                    assert_eq!(distinct, m1_expected(n, inner), "{name} static");
                    for submit in Submit::ALL {
                        let cfg = config(Driver::Pattern(submit), n, combo, r);
                        let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
                        let welded = weld(&cap, &Pattern::uniform(n)).unwrap();
                        let what = format!("{name} {}", cfg.label());
                        assert_eq!(welded.positions.len(), m1_expected(n, inner), "{what}");
                        assert_closed(&welded.triangles, &what);
                    }
                    let cfg = config(Driver::Tess, n, combo, r);
                    let inner = (tess_vertex_count(n) - 3 * n) as usize;
                    assert_eq!(
                        tess_positions(h, &mut scene, &cfg, &camera),
                        m1_expected(n, inner),
                        "{name} tess"
                    );
                    let tris = h.capture_triangles(&mut scene, &cfg, &camera).unwrap();
                    let welded = weld_triangles(&tris);
                    assert_eq!(
                        welded.positions.len(),
                        m1_expected(n, inner),
                        "{name} tess triangles"
                    );
                    assert_closed(&welded.triangles, &format!("{name} tess triangles"));
                }
            }
        }
    });
}

/// An export made in many small capture passes (the tess driver's welded pass by pass) is the
/// same file, byte for byte, as one made in a single pass, on both GPU drivers and several
/// surfaces; the tess driver's streamed weld equals welding the whole capture; each pass is
/// reported once, in order, with the elements it brings the capture to.
#[test]
fn exports_in_many_passes_write_the_same_bytes() {
    use meshrefine::export::to_obj;
    use meshrefine::pattern::vertex_count;
    use std::sync::{Arc, Mutex};
    with_gpu(64, 64, |h| {
        let mesh = model("icosahedron.obj");
        let n = mesh.triangles.len() as u32;
        let (mut scene, camera) = scene_at(h, &mesh, &[7, 8]);
        let r = scene.bounding_sphere().1;
        // Bytes of three elements' capture: tess triangles by transform feedback (an
        // `XfbVertex` a vertex), pattern vertices (64 bytes each).
        let xfb_vertex = std::mem::size_of::<meshrefine::render::XfbVertex>() as u64;
        let three = [
            (
                Driver::Tess,
                7,
                3 * tess_triangle_count(7) as u64 * 3 * xfb_vertex,
            ),
            (
                Driver::Pattern(Submit::Instanced),
                8,
                3 * vertex_count(8) as u64 * 64,
            ),
        ];
        let surfaces = [
            (Surface::Flat, Displace::None),
            (Surface::Pn, Displace::None),
            (Surface::Phong, Displace::Sine),
        ];
        for (driver, level, bytes) in three {
            for surface in surfaces {
                let cfg = config(driver, level, surface, r);
                h.max_capture_bytes = None;
                let one = to_obj(&h.refined_mesh(&mut scene, &cfg, &camera).unwrap(), &[]);
                assert!(one.lines().filter(|l| l.starts_with("f ")).count() > n as usize);
                if driver == Driver::Tess {
                    let whole = h.capture_triangles(&mut scene, &cfg, &camera).unwrap();
                    assert!(
                        to_obj(&weld_triangles(&whole), &[]) == one,
                        "{}",
                        cfg.label()
                    );
                }
                let seen = Arc::new(Mutex::new(Vec::new()));
                let log = seen.clone();
                h.capture_progress = Some(Box::new(move |p| log.lock().unwrap().push(p)));
                h.max_capture_bytes = Some(bytes);
                let many = h.refined_mesh(&mut scene, &cfg, &camera);
                h.capture_progress = None;
                h.max_capture_bytes = None;
                let many = to_obj(&many.unwrap(), &[]);
                assert!(many == one, "{}: passes change the file", cfg.label());
                let seen = seen.lock().unwrap();
                let passes = n.div_ceil(3);
                assert_eq!(seen.len(), passes as usize, "{}", cfg.label());
                for (k, p) in seen.iter().enumerate() {
                    let done = k as u32 + 1;
                    assert_eq!((p.done, p.passes, p.elements), (done, passes, n));
                    assert_eq!(p.elements_done, (3 * done).min(n));
                }
            }
        }
    });
}
