//! The pattern driver drawing adaptively (`Headless::adaptive`, each element at its own levels
//! from the mesh's levels buffer): what its real pipelines evaluated, read back through the
//! capture variant, equals the CPU mirror (`pattern::adaptive::adaptive_element`, snapping
//! included) in every submission mode; culled elements draw nothing; and at random level
//! combinations (levels differing across edges, so boundary vertices are snapped) the welded
//! result of a closed mesh is closed with the vertex count of a crack-free refinement.
//!
//! Levels are random but consistent: each unique edge gets one random real level, shared by the
//! two elements on it; an element's inner level is at least its largest edge's.
//!
//! Tolerances: those of tests/gpu_mirror.rs for the pattern driver (the adaptive stage feeds the
//! surfaces exact dyadic weights, like the uniform pattern): exact without displacement and seams
//! (64 ulp of the radius for loop), 4 ulp of the radius more at split normals, and the
//! displacements' own terms.

mod common;

use common::{model, with_gpu};
use meshrefine::export::weld_adaptive;
use meshrefine::lod::levels::ElementLevels;
use meshrefine::mesh::Mesh;
use meshrefine::pattern::adaptive::{
    adaptive_element, drawn_levels, geomorph_position, IntegerPatterns,
};
use meshrefine::pattern::{vertex_count, PatternSet};
use meshrefine::render::{Camera, Capture, DrawConfig, Driver, Headless, Scene, Submit};
use meshrefine::subdiv::FaceRecord;
use meshrefine::surface::{Displace, Surface, SurfaceParams};
use std::collections::{HashMap, HashSet};

/// xorshift64*: reproducible random numbers without a dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        ((self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 40) as f32) / (1u64 << 24) as f32
    }
}

/// Random consistent levels for elements with global corners `tris` at largest level `max`:
/// each unique edge one level in `[1, max]`, the inner level between the largest edge's and
/// `max`; a fraction `cull` of the elements culled.
fn random_levels(tris: &[[u32; 3]], max: u32, cull: f32, seed: u64) -> Vec<ElementLevels> {
    let mut rng = Rng(seed);
    let mut edge: HashMap<(u32, u32), f32> = HashMap::new();
    let level = |rng: &mut Rng| 1.0 + rng.next() * (max as f32 - 1.0);
    tris.iter()
        .map(|t| {
            let edges: [f32; 3] = std::array::from_fn(|k| {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *edge
                    .entry((a.min(b), a.max(b)))
                    .or_insert_with(|| level(&mut rng))
            });
            let top = edges.iter().copied().fold(1.0, f32::max);
            let inner = top + rng.next() * (max as f32 - top);
            if rng.next() < cull {
                ElementLevels::CULLED
            } else {
                ElementLevels { edges, inner }
            }
        })
        .collect()
}

/// Each element's global corners: the coarse triangle's positions, or the M1 face's vertices.
fn element_corners(scene: &Scene, surface: Surface) -> Vec<[u32; 3]> {
    match &scene.loop_ {
        Some(l) if surface.uses_loop_faces() => l
            .data
            .records
            .iter()
            .map(|r| l.data.m1.faces[FaceRecord::decode(r).face as usize])
            .collect(),
        _ => scene.data.mesh.triangles.iter().map(|t| t.p).collect(),
    }
}

fn scene_at(h: &Headless, mesh: Mesh, max: u32) -> (Scene, Camera, f32) {
    scene_chunked(h, mesh, max, None)
}

/// Records (and levels) bound in chunks of at most `chunk` elements.
fn scene_chunked(h: &Headless, mesh: Mesh, max: u32, chunk: Option<u32>) -> (Scene, Camera, f32) {
    let scene = Scene::with_chunks(
        &h.ctx,
        &h.pool,
        &h.renderer,
        mesh,
        PatternSet::from_levels(&[max]),
        chunk,
    )
    .unwrap();
    let (c, r) = scene.bounding_sphere();
    (scene, Camera::framing(c, r), r)
}

fn config(submit: Submit, max: u32, (s, d): (Surface, Displace), r: f32) -> DrawConfig {
    let mut cfg = DrawConfig::new(Driver::Pattern(submit), max).with_surface(s, d);
    cfg.params = SurfaceParams::for_radius(r);
    cfg
}

/// Prepare `cfg` (building loop's M1 faces), upload random levels for its elements and return
/// them.
fn set_levels(
    h: &mut Headless,
    scene: &mut Scene,
    cfg: &DrawConfig,
    cull: f32,
    seed: u64,
) -> Vec<ElementLevels> {
    h.prepared_elements(scene, cfg, Capture::Vertices).unwrap();
    let tris = element_corners(scene, cfg.surface);
    let levels = random_levels(&tris, cfg.level, cull, seed);
    match &mut scene.loop_ {
        Some(l) if cfg.surface.uses_loop_faces() => l.gpu.upload_levels(&levels),
        _ => scene.gpu.upload_levels(&levels),
    }
    levels
}

/// Capture `cfg` adaptively with random levels and compare every slot with the mirror; returns
/// how many boundary vertices snapping moved.
fn check(
    h: &mut Headless,
    file: &str,
    max: u32,
    combos: &[(Surface, Displace)],
    cull: f32,
) -> usize {
    check_chunked(h, file, max, combos, cull, None, None)
}

fn check_chunked(
    h: &mut Headless,
    file: &str,
    max: u32,
    combos: &[(Surface, Displace)],
    cull: f32,
    chunk: Option<u32>,
    bft_level: Option<u32>,
) -> usize {
    let (mut scene, camera, r) = scene_chunked(h, model(file), max, chunk);
    let mut moved = 0;
    for (c, &combo) in combos.iter().enumerate() {
        for submit in Submit::ALL {
            let mut cfg = config(submit, max, combo, r);
            cfg.build.bft_level = bft_level.unwrap_or(cfg.build.bft_level);
            let levels = set_levels(h, &mut scene, &cfg, cull, 7 + c as u64);
            h.adaptive = true;
            let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
            h.adaptive = false;
            let records = scene.records(cfg.surface);
            let tol = common::pattern_tolerance(&cfg, r, records);
            let ntol = if cfg.displace == Displace::None {
                1e-5
            } else {
                2e-3
            };
            let mirror = scene.mirror(&cfg, max).unwrap();
            // The patterns' own weights (the hierarchy's, or the integer patterns').
            let plain = match cfg.dyadic_levels() {
                true => meshrefine::pattern::adaptive::Hierarchy::new(max).bary,
                false => IntegerPatterns::new(max).bary,
            };
            let elements: Vec<_> = cap.adaptive_elements().collect();
            assert_eq!(elements.len(), records.len());
            let what = format!(
                "{file} {} + {} {}",
                combo.0.name(),
                combo.1.name(),
                cfg.label()
            );
            let mut culled = 0;
            for (t, rec) in records.iter().enumerate() {
                // Packed: the element's inner level's vertices only, in that level's order.
                let (inner, slots) = elements[t];
                let Some(e) = adaptive_element(&levels[t], max, cfg.dyadic_levels()) else {
                    culled += 1;
                    assert_eq!(inner, 0, "{what}: culled element {t} has a level");
                    assert!(
                        slots.is_empty(),
                        "{what}: culled element {t} drew something"
                    );
                    continue;
                };
                assert_eq!(inner, e.levels.inner, "{what}: element {t}'s level");
                assert_eq!(
                    slots.len(),
                    e.vertices.len(),
                    "{what}: element {t}'s vertices"
                );
                for ((&k, &bary), v) in e.vertices.iter().zip(&e.bary).zip(slots) {
                    let at = format!("{what}: element {t} vertex {k} at {bary:?}");
                    assert_eq!(v.position[3], 1.0, "{at} never written");
                    assert_eq!(v.id, [t as u32, k, e.levels.inner, 1], "{at}: slot");
                    assert_eq!(&v.coord[..3], &bary[..], "{at}: weights");
                    moved += (plain[k as usize] != bary) as usize;
                    let want = mirror.eval(&cfg.params, t, rec, bary);
                    for a in 0..3 {
                        let d = (v.position[a] - want.position[a]).abs();
                        assert!(
                            d <= tol,
                            "{at}: position {:?} vs mirror {} (tolerance {tol:e})",
                            &v.position[..3],
                            want.position
                        );
                        assert!(
                            (v.normal[a] - want.normal[a]).abs() <= ntol,
                            "{at}: normal {:?} vs {}",
                            &v.normal[..3],
                            want.normal
                        );
                    }
                }
            }
            if cull > 0.0 {
                assert!(culled > 0, "{what}: no element culled");
            }
        }
    }
    moved
}

#[test]
fn adaptive_pattern_matches_the_mirror() {
    with_gpu(64, 64, |h| {
        let all: Vec<(Surface, Displace)> = Surface::ALL
            .iter()
            .map(|&s| (s, Displace::None))
            .chain([
                (Surface::Pn, Displace::Sine),
                (Surface::Flat, Displace::Noise),
                (Surface::Loop, Displace::Noise),
            ])
            .collect();
        let moved = check(h, "icosahedron_vn.obj", 8, &all, 0.0);
        assert!(moved > 0, "no vertex was snapped");
        // The height map (texture coordinates).
        check(
            h,
            "grid_uv_8x8.obj",
            8,
            &[
                (Surface::Pn, Displace::Heightmap),
                (Surface::Flat, Displace::Heightmap),
            ],
            0.1,
        );
        check(
            h,
            "cylinder_hard_normals.obj",
            4,
            &[
                (Surface::Stpn, Displace::None),
                (Surface::Phong, Displace::Sine),
            ],
            0.0,
        );
        // Spot, with some elements culled.
        let moved = check(h, "spot_control_tri.obj", 16, &all, 0.15);
        assert!(moved > 0, "no vertex was snapped");
    });
}

/// Records and levels in chunks of 7 of icosahedron's 20 elements (one bin per chunk and level
/// for `instanced`), captured in passes of at most 3 finest patterns' vertices (several elements
/// at their own levels; the bins pass runs on each pass's range).
#[test]
fn adaptive_pattern_in_chunks_and_capture_passes() {
    with_gpu(64, 64, |h| {
        h.max_capture_bytes = Some(3 * vertex_count(8) as u64 * 64);
        let combos = [
            (Surface::Pn, Displace::None),
            (Surface::Loop, Displace::None),
        ];
        let moved = check_chunked(h, "icosahedron_vn.obj", 8, &combos, 0.2, Some(7), None);
        assert!(moved > 0, "no vertex was snapped");
        h.max_capture_bytes = None;
    });
}

/// Welded on exact position bits, a closed mesh drawn at random levels is closed and has the
/// vertex count of a crack-free refinement: the mesh's vertices, `N_e - 1` per unique edge and
/// `(N - 1)(N - 2)/2` inside each element. The levels differ across edges (asserted), so without
/// snapping the coarser side's T-junctions would open cracks and this fails.
#[test]
fn adaptive_pattern_is_watertight() {
    const COMBOS: &[(Surface, Displace)] = &[
        (Surface::Flat, Displace::None),
        (Surface::Pn, Displace::None),
        (Surface::Pn, Displace::Noise),
        (Surface::Stpn, Displace::None),
        (Surface::Phong, Displace::Sine),
        (Surface::Loop, Displace::None),
    ];
    with_gpu(64, 64, |h| {
        for file in [
            "tetrahedron.obj",
            "icosahedron.obj",
            "torus_16x8.obj",
            "cylinder_hard_normals.obj",
            "spot_control_tri.obj",
        ] {
            watertight(h, file, 16, COMBOS, None, false);
        }
        // Loop displaced, and the height map where its texture coordinates are continuous
        // (tests/watertight.rs, uniformly).
        let displaced = [
            (Surface::Loop, Displace::Sine),
            (Surface::Loop, Displace::Noise),
        ];
        watertight(h, "icosahedron.obj", 16, &displaced, None, false);
        let heightmap = [
            (Surface::Pn, Displace::Heightmap),
            (Surface::Flat, Displace::Heightmap),
            (Surface::Phong, Displace::Heightmap),
        ];
        watertight(h, "grid_uv_8x8.obj", 16, &heightmap, None, false);
    });
}

/// `loop` with basis function tables of level 2 (4 segments an edge) drawn up to level 16:
/// samples finer than the tables interpolate between rows, snapped edge samples included; it
/// still equals the mirror and stays watertight (an edge point is evaluated by its owner face).
#[test]
fn adaptive_loop_past_its_table_level() {
    with_gpu(64, 64, |h| {
        let combos = [
            (Surface::Loop, Displace::None),
            (Surface::Loop, Displace::Sine),
        ];
        let moved = check_chunked(h, "icosahedron_vn.obj", 16, &combos, 0.1, None, Some(2));
        assert!(moved > 0, "no vertex was snapped");
        watertight(h, "octahedron.obj", 16, &combos[..1], Some(2), false);
    });
}

/// Welded at random levels, `file` is closed (but for its boundary's segments, on an open
/// mesh), consistently oriented and has the crack-free vertex count, for each of `combos`.
fn watertight(
    h: &mut Headless,
    file: &str,
    max: u32,
    combos: &[(Surface, Displace)],
    bft_level: Option<u32>,
    geomorph: bool,
) {
    let (mut scene, camera, r) = scene_at(h, model(file), max);
    for (c, &combo) in combos.iter().enumerate() {
        let submit = Submit::ALL[c % 3];
        let mut cfg = config(submit, max, combo, r);
        cfg.geomorph = geomorph;
        cfg.build.bft_level = bft_level.unwrap_or(cfg.build.bft_level);
        let levels = set_levels(h, &mut scene, &cfg, 0.0, 100 + c as u64);
        let tris = element_corners(&scene, cfg.surface);
        // The crack-free count, and a check that levels differ across some edge.
        let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
        let mut uses: HashMap<(u32, u32), u32> = HashMap::new();
        let mut inner_vertices = 0;
        let mut corners = HashSet::new();
        let mut differs = false;
        for (t, l) in tris.iter().zip(&levels) {
            let d = drawn_levels(l, max, cfg.dyadic_levels()).unwrap();
            inner_vertices += ((d.inner - 1) * (d.inner.max(2) - 2) / 2) as usize;
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                corners.insert(a);
                edges.insert((a.min(b), a.max(b)), d.edges[k]);
                *uses.entry((a.min(b), a.max(b))).or_default() += 1;
                differs |= d.edges[k] < d.inner;
            }
        }
        assert!(
            differs,
            "{file}: every edge drawn at its element's inner level"
        );
        let expected =
            corners.len() + edges.values().map(|&n| n as usize - 1).sum::<usize>() + inner_vertices;
        h.adaptive = true;
        let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
        // `Headless::refined_mesh` welds the same adaptive capture.
        let refined = h.refined_mesh(&mut scene, &cfg, &camera).unwrap();
        h.adaptive = false;
        let welded = weld_adaptive(&cap, max).unwrap();
        assert_eq!(refined.positions, welded.positions);
        assert_eq!(refined.triangles, welded.triangles);
        let what = format!(
            "{file} {} + {} {}",
            combo.0.name(),
            combo.1.name(),
            cfg.label()
        );
        assert_eq!(welded.positions.len(), expected, "{what}: welded vertices");
        let mut count: HashMap<(u32, u32), u32> = HashMap::new();
        for t in &welded.triangles {
            for k in 0..3 {
                let (a, b) = (t[k].0, t[(k + 1) % 3].0);
                *count.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        // On an open mesh, the segments of its boundary edges at their levels have one triangle.
        let boundary: usize = (edges.iter())
            .filter(|(k, _)| uses[k] == 1)
            .map(|(_, &n)| n as usize)
            .sum();
        let open = count.values().filter(|&&c| c != 2).count();
        let single = count.values().filter(|&&c| c == 1).count();
        assert_eq!(
            (open, single),
            (boundary, boundary),
            "{what}: welded edges not shared by exactly two triangles (a crack) besides the boundary's {boundary} segments"
        );
        // Consistently oriented: no snapped triangle flipped.
        let directed: HashSet<(u32, u32)> = welded
            .triangles
            .iter()
            .flat_map(|t| (0..3).map(move |k| (t[k].0, t[(k + 1) % 3].0)))
            .collect();
        assert_eq!(
            directed.len(),
            3 * welded.triangles.len(),
            "{what}: a flipped triangle"
        );
    }
}

/// Geomorphing (`DrawConfig::geomorph`) at random continuous levels: every captured position
/// equals the mirror's (`geomorph_position`: the vertices the finest drawn levels add, between
/// their parents' drawn midpoint and the surface), within the pattern driver's tolerance plus
/// 4 ulp of the radius for the blend; some vertices really morph; and the welded result stays
/// closed with the crack-free vertex count (edge vertices morph with their edge's level, on
/// the same bits from both sides).
#[test]
fn adaptive_geomorph_matches_the_mirror_and_is_watertight() {
    const COMBOS: &[(Surface, Displace)] = &[
        (Surface::Pn, Displace::None),
        (Surface::Phong, Displace::Sine),
        (Surface::Loop, Displace::None),
        (Surface::Stpn, Displace::Noise),
        (Surface::Flat, Displace::Noise),
        (Surface::Loop, Displace::Sine),
    ];
    with_gpu(64, 64, |h| {
        let max = 16;
        let (mut scene, camera, r) = scene_at(h, model("icosahedron_vn.obj"), max);
        for (c, &combo) in COMBOS.iter().enumerate() {
            let mut cfg = config(Submit::ALL[c % 3], max, combo, r);
            cfg.geomorph = true;
            let levels = set_levels(h, &mut scene, &cfg, 0.1, 300 + c as u64);
            h.adaptive = true;
            let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
            h.adaptive = false;
            let records = scene.records(cfg.surface);
            let tol = common::pattern_tolerance(&cfg, r, records) + 4.0 * f32::EPSILON * r;
            let mirror = scene.mirror(&cfg, max).unwrap();
            let what = format!("{} + {} {}", combo.0.name(), combo.1.name(), cfg.label());
            let (mut morphing, mut worst) = (0usize, 0.0f32);
            for ((t, rec), (_, slots)) in records.iter().enumerate().zip(cap.adaptive_elements()) {
                let Some(e) = adaptive_element(&levels[t], max, true) else {
                    continue;
                };
                let eval = |b: [f32; 3]| mirror.eval(&cfg.params, t, rec, b).position;
                let vertices = e.vertices.iter().zip(&e.points).zip(&e.bary).zip(slots);
                for (((&k, &pt), &bary), v) in vertices {
                    let want = geomorph_position(&levels[t], &e.levels, max, pt, &eval);
                    morphing += (want != eval(bary)) as usize;
                    for a in 0..3 {
                        let d = (v.position[a] - want[a]).abs();
                        worst = worst.max(d);
                        assert!(
                            d <= tol,
                            "{what}: element {t} vertex {k}: {:?} vs mirror {want} (tolerance {tol:e})",
                            &v.position[..3]
                        );
                    }
                }
            }
            eprintln!("{what}: {morphing} morphing vertices, worst difference {worst:e}");
            assert!(morphing > 50, "{what}: only {morphing} vertices morph");
        }
        for file in ["icosahedron.obj", "torus_16x8.obj"] {
            watertight(h, file, 16, COMBOS, None, true);
        }
    });
}

/// A largest level that is not a power of two is refused with one sentence.
#[test]
fn adaptive_pattern_needs_a_power_of_two() {
    with_gpu(16, 16, |h| {
        let (mut scene, camera, r) = scene_at(h, model("tetrahedron.obj"), 6);
        h.adaptive = true;
        let cfg = config(Submit::Instanced, 6, (Surface::Flat, Displace::None), r);
        let e = h.render(&mut scene, &cfg, &camera).unwrap_err().to_string();
        assert!(
            e.contains("power of two") && e.contains("--level 4 or 8"),
            "{e}"
        );
    });
}

/// Images through the whole adaptive path (bins pass, indirect draws, wireframe pass): every
/// element at the largest level draws the very image uniform drawing does (the same weights,
/// the same triangles; pn's normal field per fragment), and every element culled draws nothing.
#[test]
fn adaptive_pattern_images() {
    with_gpu(96, 96, |h| {
        h.wireframe = true;
        let (mut scene, camera, r) = scene_chunked(h, model("spot_control_tri.obj"), 8, Some(100));
        for combo in [
            (Surface::Pn, Displace::None),
            (Surface::Loop, Displace::None),
        ] {
            for submit in Submit::ALL {
                let cfg = config(submit, 8, combo, r);
                h.prepared_elements(&mut scene, &cfg, Capture::None)
                    .unwrap();
                let n = scene.elements(cfg.surface).element_count as usize;
                let set = |scene: &mut Scene, l: ElementLevels| match &mut scene.loop_ {
                    Some(lp) if cfg.surface.uses_loop_faces() => lp.gpu.upload_levels(&vec![l; n]),
                    _ => scene.gpu.upload_levels(&vec![l; n]),
                };
                let what = format!("{} {}", combo.0.name(), cfg.label());
                let uniform = h.render(&mut scene, &cfg, &camera).unwrap();
                assert!(
                    meshrefine::render::covered_pixels(&uniform) > 1000,
                    "{what}: nothing drawn"
                );
                set(&mut scene, ElementLevels::uniform(8.0));
                h.adaptive = true;
                let adaptive = h.render(&mut scene, &cfg, &camera).unwrap();
                assert!(
                    adaptive.rgba == uniform.rgba,
                    "{what}: adaptive at level 8 everywhere differs from uniform level 8"
                );
                set(&mut scene, ElementLevels::CULLED);
                let culled = h.render(&mut scene, &cfg, &camera).unwrap();
                assert_eq!(
                    meshrefine::render::covered_pixels(&culled),
                    0,
                    "{what}: culled elements drew"
                );
                h.adaptive = false;
            }
        }
        h.wireframe = false;
    });
}
