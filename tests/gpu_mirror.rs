//! The vertices the real drawing pipelines evaluated (read back through their capture variants)
//! equal the CPU mirror, for every surface x displacement x GPU driver x submission mode, several
//! meshes and levels.
//!
//! Tolerances (per position component, `r` the mesh's bounding radius, `a` the amplitude):
//! - `pattern`, no displacement: exact (0 ulp) for every surface. The pattern stores the same
//!   barycentric floats the mirror uses, the surfaces are evaluated with `precise` (no FMA) in the
//!   mirror's operation order, with `dot3` instead of `dot`, multiplications by 1/3 and 1/6
//!   instead of divisions, and Vulkan rounds fp32 add and multiply correctly.
//! - at split normals with closed seams (the default), 4 ulp of r more for the curved surfaces and
//!   displacement: their geometry normals are stored octahedral and decoded with `normalize`,
//!   whose GPU inversesqrt is not correctly rounded (measured: 1 ulp).
//! - `tess`: 4 ulp of r (flat) or 16 ulp of r (curved surfaces), the mirror evaluated at the
//!   captured gl_TessCoord: edge samples are snapped to k/N on the GPU, and Vulkan's division is
//!   exact only to 2.5 ulp, which the cubic PN patch amplifies.
//! - `sine`: 2e-3·|a| more: GPU sin/cos/sqrt are not correctly rounded (Vulkan allows 2^-11
//!   absolute error for sin on [-π, π]).
//! - `noise`: 1e-5·|a| more: floor, fade and the lerps are exact operations, but the noise's
//!   input is the (already rounded) surface point times the frequency.
//! - normals: 1e-5 per component without displacement (GPU inversesqrt is not exact); 2e-3 with
//!   (sin, cos, cross products and a second normalization).

mod common;

use common::random_levels::{element_corners, random_levels};
use common::{model, with_gpu};
use meshrefine::lod::levels::drawn_level;
use meshrefine::mesh::Mesh;
use meshrefine::pattern::{lattice_index, Pattern, PatternSet};
use meshrefine::render::tess::{
    outer_levels, tess_vertex_count, tess_vertex_count_levels, tess_weights, tess_weights_levels,
};
use meshrefine::render::{Camera, DrawConfig, Driver, Headless, Scene, Submit};
use meshrefine::subdiv::Boundary;
use meshrefine::surface::{
    BuildOptions, CornerRecord, Displace, ElementRecord, NormalField, Surface, SurfaceParams,
    SMOOTH_CORNER,
};

use std::collections::{HashMap, HashSet};

fn scene_with(h: &Headless, mesh: Mesh, levels: &[u32]) -> (Scene, Camera, f32) {
    scene_chunked(h, mesh, levels, None)
}

/// A scene whose records are bound in chunks of at most `chunk` elements.
fn scene_chunked(
    h: &Headless,
    mesh: Mesh,
    levels: &[u32],
    chunk: Option<u32>,
) -> (Scene, Camera, f32) {
    let scene = Scene::with_chunks(
        &h.ctx,
        &h.pool,
        &h.renderer,
        mesh,
        PatternSet::from_levels(levels),
        chunk,
    )
    .unwrap();
    let (c, r) = scene.bounding_sphere();
    (scene, Camera::framing(c, r), r)
}

/// Whether some corner of `records` has a geometry normal of its own (split normals).
fn seamed(records: &[ElementRecord]) -> bool {
    records
        .iter()
        .any(|r| (0..3).any(|i| CornerRecord::decode(r).p[i][3] != SMOOTH_CORNER))
}

/// Position tolerance of a combination on `driver` for a mesh of radius `r`.
fn position_tolerance(cfg: &DrawConfig, r: f32, seamed: bool) -> f32 {
    let eps = f32::EPSILON * r;
    let base = match (cfg.driver, cfg.surface) {
        // Sums of up to 30 table-weighted M1 points (M1 itself made by the GPU's Loop pass);
        // the GPU may fuse multiply-adds the mirror rounds twice.
        (_, Surface::Loop) => 64.0 * eps,
        (Driver::Pattern(_), _) => 0.0,
        (_, Surface::Flat) => 4.0 * eps,
        _ => 16.0 * eps,
    };
    let uses_normals =
        !matches!(cfg.surface, Surface::Flat | Surface::Loop) || cfg.displace != Displace::None;
    let base = base
        + if seamed && uses_normals {
            4.0 * eps
        } else {
            0.0
        };
    let a = cfg.params.amplitude.abs();
    base + match cfg.displace {
        Displace::None => 0.0,
        Displace::Sine => 2e-3 * a + 8.0 * eps,
        Displace::Noise => 1e-5 * a + 8.0 * eps,
        // Bilinear and trilinear filtering are exact operations on the same texels; the error
        // is that of the (already rounded) texture coordinates times the map's slope.
        Displace::Heightmap => 1e-4 * a + 8.0 * eps,
    }
}

/// Assert a captured vertex equals the mirror's point within the tolerances (per component);
/// returns the largest position difference.
fn compare(
    got: &meshrefine::render::CapturedVertex,
    want: &meshrefine::surface::SurfacePoint,
    tol: f32,
    ntol: f32,
    what: &str,
) -> f32 {
    let mut worst = 0.0f32;
    for a in 0..3 {
        let d = (got.position[a] - want.position[a]).abs();
        worst = worst.max(d);
        assert!(
            d <= tol,
            "{what}: position {:?} differs from the mirror {} (tolerance {tol:e})",
            &got.position[..3],
            want.position
        );
        assert!(
            (got.normal[a] - want.normal[a]).abs() <= ntol,
            "{what}: normal {:?} vs {}",
            &got.normal[..3],
            want.normal
        );
    }
    worst
}

fn normal_tolerance(cfg: &DrawConfig) -> f32 {
    if cfg.displace == Displace::None {
        1e-5
    } else {
        2e-3
    }
}

/// Which combinations a check runs: `false` the flat surface alone, `true` every surface x
/// displacement, or [`Loop`] the loop surface alone with a boundary rule and every displacement
/// it takes.
#[derive(Clone, Copy)]
enum Which {
    Flat,
    All,
    /// The loop surface with a boundary rule and a table level.
    Loop(Boundary, u32),
    /// `pn` and `stpn` with a normal field, without and with displacement (which moves along it).
    Field(NormalField),
    /// `stpn` with tags of its own, as a tags file gives them (not derived from the mesh: every
    /// vertex a tension, sharpness and bias, two opposite vertices creases), without and with
    /// displacement.
    OwnTags,
}

impl From<bool> for Which {
    fn from(all: bool) -> Self {
        if all {
            Which::All
        } else {
            Which::Flat
        }
    }
}

/// The scene of `file` (records in chunks of `chunk`), its camera, the parameters `which` runs
/// with, and the mesh's radius.
fn setup(
    h: &Headless,
    file: &str,
    levels: &[u32],
    which: Which,
    chunk: Option<u32>,
) -> (Scene, Camera, SurfaceParams, BuildOptions, f32) {
    let (scene, camera, r) = scene_chunked(h, model(file), levels, chunk);
    let (boundary, bft_level) = match which {
        Which::Loop(b, l) => (b, l),
        _ => (Boundary::EdgeOnly, 5),
    };
    let build = BuildOptions {
        boundary,
        bft_level,
        ..BuildOptions::default()
    };
    let normal_field = match which {
        Which::Field(f) => f,
        _ => NormalField::default(),
    };
    let build = BuildOptions {
        normal_field,
        ..build
    };
    let params = SurfaceParams::for_radius(r);
    let mut scene = scene;
    if let Which::OwnTags = which {
        scene
            .set_tags(
                &h.ctx,
                &h.pool,
                &h.renderer,
                common::own_tags(&scene.data.mesh),
            )
            .unwrap();
    }
    (scene, camera, params, build, r)
}

/// Every surface x displacement of `which` (the height map only on meshes with texture
/// coordinates).
fn combinations(which: Which, uvs: bool) -> Vec<(Surface, Displace)> {
    match which {
        Which::Flat => return vec![(Surface::Flat, Displace::None)],
        Which::Loop(..) => {
            return vec![
                (Surface::Loop, Displace::None),
                (Surface::Loop, Displace::Sine),
                (Surface::Loop, Displace::Noise),
            ]
        }
        Which::Field(_) => {
            return [Surface::Pn, Surface::Stpn]
                .iter()
                .flat_map(|&s| {
                    [Displace::None, Displace::Sine, Displace::Noise].map(move |d| (s, d))
                })
                .collect()
        }
        Which::OwnTags => {
            return [Displace::None, Displace::Sine, Displace::Noise]
                .map(|d| (Surface::Stpn, d))
                .to_vec()
        }
        Which::All => {}
    }
    Surface::ALL
        .iter()
        .flat_map(|&s| Displace::ALL.iter().map(move |&d| (s, d)))
        // The height map reads texture coordinates (loop has none).
        .filter(|&(s, d)| d != Displace::Heightmap || (uvs && s != Surface::Loop))
        .collect()
}

fn check_pattern(file: &str, h: &mut Headless, levels: &[u32], all: impl Into<Which>) {
    check_pattern_chunked(file, h, levels, all, None)
}

fn check_pattern_chunked(
    file: &str,
    h: &mut Headless,
    levels: &[u32],
    all: impl Into<Which>,
    chunk: Option<u32>,
) {
    let all = all.into();
    let (mut scene, camera, params, build, r) = setup(h, file, levels, all, chunk);
    for &level in levels {
        let pattern = Pattern::uniform(level);
        let pv = pattern.bary.len();
        for (surface, displace) in combinations(all, scene.data.uvs.is_some()) {
            for submit in Submit::ALL {
                let mut cfg =
                    DrawConfig::new(Driver::Pattern(submit), level).with_surface(surface, displace);
                cfg.params = params;
                cfg.build = build;
                let tol = position_tolerance(&cfg, r, seamed(&scene.data.records));
                let ntol = normal_tolerance(&cfg);
                let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
                let hm = scene.mirror(&cfg, level).unwrap();
                let records = scene.records(surface);
                assert_eq!(cap.vertices.len(), records.len() * pv);
                let mut worst = 0.0f32;
                for (t, rec) in records.iter().enumerate() {
                    for (k, (i, j)) in pattern.lattice().enumerate() {
                        assert_eq!(lattice_index(level, i, j) as usize, k);
                        let got = &cap.vertices[t * pv + k];
                        let what = format!(
                            "{file} {} ({}) + {} {} L{level}: triangle {t} vertex ({i},{j})",
                            surface.name(),
                            build.normal_field.name(),
                            displace.name(),
                            cfg.label()
                        );
                        assert_eq!(got.position[3], 1.0, "{what} never written");
                        assert_eq!(
                            got.id,
                            [t as u32, k as u32, 0, 0],
                            "{what}: wrong capture slot"
                        );
                        let want = hm.eval(&params, t, rec, pattern.bary[k]);
                        worst = worst.max(compare(got, &want, tol, ntol, &what));
                    }
                }
                if submit == Submit::Instanced {
                    eprintln!(
                        "{file} {} + {} pattern L{level}: max position error {worst:e} (tolerance {tol:e})",
                        surface.name(),
                        displace.name()
                    );
                }
            }
        }
    }
}

fn check_tess(file: &str, h: &mut Headless, levels: &[u32], all: impl Into<Which>) {
    check_tess_chunked(file, h, levels, all, None)
}

fn check_tess_chunked(
    file: &str,
    h: &mut Headless,
    levels: &[u32],
    all: impl Into<Which>,
    chunk: Option<u32>,
) {
    let all = all.into();
    let (mut scene, camera, params, build, r) = setup(h, file, levels, all, chunk);
    for &level in levels {
        for (surface, displace) in combinations(all, scene.data.uvs.is_some()) {
            let mut cfg = DrawConfig::new(Driver::Tess, level).with_surface(surface, displace);
            cfg.params = params;
            cfg.build = build;
            let tol = position_tolerance(&cfg, r, seamed(&scene.data.records));
            let ntol = normal_tolerance(&cfg);
            let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
            let hm = scene.mirror(&cfg, level).unwrap();
            let mut coords: HashMap<u32, HashSet<[u32; 3]>> = HashMap::new();
            let mut worst = 0.0f32;
            let what = format!(
                "{file} {} ({}) + {} tess L{level}",
                surface.name(),
                build.normal_field.name(),
                displace.name()
            );
            for v in &cap.vertices {
                let t = v.id[0] as usize;
                assert_eq!(v.id[1], u32::MAX);
                assert_eq!(v.position[3], 1.0);
                let tc = [v.coord[0], v.coord[1], v.coord[2]];
                coords
                    .entry(v.id[0])
                    .or_default()
                    .insert(tc.map(f32::to_bits));
                let want = hm.eval(
                    &params,
                    t,
                    &scene.records(surface)[t],
                    tess_weights(tc, level),
                );
                let at = format!("{what}: triangle {t} at {tc:?}");
                worst = worst.max(compare(v, &want, tol, ntol, &at));
            }
            // Every patch was tessellated into exactly the expected set of distinct samples.
            assert_eq!(
                coords.len(),
                scene.records(surface).len(),
                "{what}: patches missing"
            );
            for (t, set) in &coords {
                assert_eq!(
                    set.len() as u32,
                    tess_vertex_count(level),
                    "{what}: triangle {t}"
                );
            }
            eprintln!(
                "{what}: {} evaluations, max position error {worst:e} (tolerance {tol:e})",
                cap.vertices.len()
            );
        }
    }
}

/// The tess driver drawing adaptively (each element at its random levels, `max` the largest)
/// evaluates what the mirror does at the captured gl_TessCoord snapped with each edge's own
/// level; each patch has exactly the tessellator's samples for its levels, each stored edge its
/// own level's samples (so gl_TessLevelOuter[i] is stored edge i + 1), and culled elements draw
/// nothing.
fn check_tess_adaptive(file: &str, h: &mut Headless, max: u32, all: impl Into<Which>, seed: u32) {
    let all = all.into();
    let (mut scene, camera, params, build, r) = setup(h, file, &[max], all, None);
    h.adaptive = true;
    for (surface, displace) in combinations(all, scene.data.uvs.is_some()) {
        let mut cfg = DrawConfig::new(Driver::Tess, max).with_surface(surface, displace);
        cfg.params = params;
        cfg.build = build;
        // Loop's M1 faces exist once prepared.
        h.prepared_elements(&mut scene, &cfg, meshrefine::render::Capture::Vertices)
            .unwrap();
        let levels = random_levels(&element_corners(&scene, surface), max, 0.2, seed);
        scene.elements_mut(surface).upload_levels(&levels);
        let tol = position_tolerance(&cfg, r, seamed(&scene.data.records));
        let ntol = normal_tolerance(&cfg);
        let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
        let hm = scene.mirror(&cfg, max).unwrap();
        let what = format!(
            "{file} {} + {} tess adaptive up to {max}",
            surface.name(),
            displace.name()
        );
        let mut coords: HashMap<u32, HashSet<[u32; 3]>> = HashMap::new();
        let mut worst = 0.0f32;
        for v in &cap.vertices {
            let t = v.id[0] as usize;
            assert_eq!(v.position[3], 1.0);
            let Some((outer, inner)) = outer_levels(&levels[t], max) else {
                panic!("{what}: culled triangle {t} was drawn");
            };
            let tc = [v.coord[0], v.coord[1], v.coord[2]];
            coords
                .entry(v.id[0])
                .or_default()
                .insert(tc.map(f32::to_bits));
            let want = hm.eval(
                &params,
                t,
                &scene.records(surface)[t],
                tess_weights_levels(tc, outer, inner),
            );
            let at = format!("{what}: triangle {t} at {tc:?}");
            worst = worst.max(compare(v, &want, tol, ntol, &at));
        }
        let drawn = levels.iter().filter(|l| !l.culled()).count();
        assert!(
            drawn > 0 && drawn < levels.len(),
            "{what}: none or all culled"
        );
        assert_eq!(coords.len(), drawn, "{what}: patches missing");
        for (&t, set) in &coords {
            let l = &levels[t as usize];
            let (outer, inner) = outer_levels(l, max).unwrap();
            assert_eq!(
                set.len() as u32,
                tess_vertex_count_levels(outer, inner),
                "{what}: triangle {t}"
            );
            // The samples with gl_TessCoord[i] == 0 lie on stored edge i + 1 (corners i + 1 and
            // i + 2): as many as that edge's level has, whatever the inner level.
            let half = 0.5 / inner as f32;
            for i in 0..3 {
                let on_edge = set.iter().filter(|c| f32::from_bits(c[i]) < half).count() as u32;
                let stored = drawn_level(l.edges[(i + 1) % 3], false, max);
                assert_eq!(
                    on_edge,
                    stored + 1,
                    "{what}: triangle {t}, stored edge {}",
                    (i + 1) % 3
                );
            }
        }
        eprintln!(
            "{what}: {} evaluations, {drawn} of {} drawn, max position error {worst:e} (tolerance {tol:e})",
            cap.vertices.len(),
            levels.len()
        );
    }
    h.adaptive = false;
}

/// Every surface (loop too) and displacement on the tess driver drawing adaptively, against
/// the mirror: random consistent levels, some elements culled.
#[test]
fn tess_adaptive_matches_mirror() {
    with_gpu(64, 64, |h| {
        check_tess_adaptive("icosahedron_vn.obj", h, 9, true, 7);
        check_tess_adaptive("grid_uv_8x8.obj", h, 6, true, 11);
        check_tess_adaptive("spot_control_tri.obj", h, 16, false, 13);
        // Past lavapipe's patches per draw at the largest level: the draws are split for it.
        check_tess_adaptive("spot_tri.obj", h, 3, false, 17);
        check_tess_adaptive(
            "spot_control_tri.obj",
            h,
            7,
            Which::Loop(Boundary::EdgeOnly, 5),
            19,
        );
        check_tess_adaptive(
            "fan24_open.obj",
            h,
            12,
            Which::Loop(Boundary::EdgeOnly, 5),
            23,
        );
    });
}

#[test]
fn pattern_matches_mirror_exactly() {
    with_gpu(64, 64, |h| {
        check_pattern("tetrahedron.obj", h, &[1, 2, 7, 64], false);
        check_pattern("icosahedron_vn.obj", h, &[1, 5, 16], false);
        check_pattern("grid_open_8x8.obj", h, &[3, 8], false);
        check_pattern("cylinder_hard_normals.obj", h, &[4], false);
        check_pattern("spot_control_tri.obj", h, &[6], false);
    });
}

#[test]
fn tess_matches_mirror() {
    with_gpu(64, 64, |h| {
        // Level 64 on lavapipe exercises the split draws (20 patches per draw).
        check_tess("tetrahedron.obj", h, &[1, 2, 7, 64], false);
        check_tess("icosahedron_vn.obj", h, &[3, 16], false);
        check_tess("grid_open_8x8.obj", h, &[5], false);
        check_tess("spot_control_tri.obj", h, &[6], false);
        // 5,856 patches: past lavapipe's 1,365 patches per draw, where its gl_PrimitiveID
        // starts over (src/render/tess.rs).
        check_tess("spot_tri.obj", h, &[2], false);
    });
}

/// Every surface x displacement x submission mode on the pattern driver.
#[test]
fn every_surface_and_displacement_on_pattern() {
    with_gpu(64, 64, |h| {
        check_pattern("icosahedron_vn.obj", h, &[5], true);
        check_pattern("cylinder_hard_normals.obj", h, &[4], true);
        check_pattern("grid_uv_8x8.obj", h, &[3, 16], true);
    });
}

/// A normal field that vanishes (at the middle of an edge whose corners' normals point opposite
/// ways) takes the same corner's normal on the GPU as in the mirror, and stays finite under
/// every displacement and submission (the tessellator's evaluation is the same code: this
/// mesh's tess exports are checked in tests/watertight.rs and tests/cli.rs, `vanishing_normal_fields_export_unit_normals`).
#[test]
fn vanishing_normal_fields_match_the_mirror() {
    with_gpu(64, 64, |h| {
        check_pattern("octahedron_opposite_vn.obj", h, &[2], true);
    });
}

/// Every surface x displacement on the tess driver.
#[test]
fn every_surface_and_displacement_on_tess() {
    with_gpu(64, 64, |h| {
        check_tess("icosahedron_vn.obj", h, &[5], true);
        check_tess("grid_uv_8x8.obj", h, &[3], true);
    });
}

/// `pn`'s and `stpn`'s normal fields (the NORMAL_FIELD specialization constant), without and
/// with displacement along them, on both GPU drivers and every submission mode: smooth normals
/// (icosahedron), split normals with closed seams and crease tags (the cylinder), a control cage.
/// With `Displace::None` the captured normal is the field itself.
#[test]
fn every_normal_field_on_pattern_and_tess() {
    with_gpu(64, 64, |h| {
        for field in NormalField::ALL {
            let f = Which::Field(field);
            check_pattern("icosahedron_vn.obj", h, &[5], f);
            check_pattern("cylinder_hard_normals.obj", h, &[4], f);
            check_tess("icosahedron_vn.obj", h, &[4], f);
            check_tess("spot_control_tri.obj", h, &[3], f);
        }
    });
}

/// `stpn` with tags of its own (what a tags file gives: tension, sharpness and bias at every
/// vertex, crease directions) on both GPU drivers and every submission mode, against the
/// mirror reading the same tags.
#[test]
fn stpn_with_its_own_tags_matches_the_mirror() {
    with_gpu(64, 64, |h| {
        check_pattern("icosahedron_vn.obj", h, &[4], Which::OwnTags);
        check_tess("icosahedron_vn.obj", h, &[4], Which::OwnTags);
        // The tags are in effect: with neutral ones stpn is pn, with these it is not.
        let (scene, _, params, build, r) =
            setup(h, "icosahedron_vn.obj", &[4], Which::OwnTags, None);
        let mirror = |s: Surface| {
            let mut cfg = DrawConfig::new(Driver::Tess, 4).with_surface(s, Displace::None);
            (cfg.params, cfg.build) = (params, build);
            scene.mirror(&cfg, 4).unwrap()
        };
        let (stpn, pn) = (mirror(Surface::Stpn), mirror(Surface::Pn));
        let records = scene.records(Surface::Stpn);
        let apart = (records.iter().enumerate())
            .map(|(t, rec)| {
                let at = [0.2, 0.3, 0.5];
                let a = stpn.eval(&params, t, rec, at).position;
                let b = pn.eval(&params, t, scene.records(Surface::Pn).get(t).unwrap(), at);
                a.distance(b.position)
            })
            .fold(0.0f32, f32::max);
        assert!(apart > 1e-2 * r, "own tags leave stpn as pn: {apart}");
    });
}

/// The loop surface (the GPU's M0 -> M1 and normals passes, then the tables through the owners)
/// against the mirror, on both GPU drivers and every submission mode: a closed mesh (valences 3
/// to 10), an open fan with a valence-24 vertex, an open half disc with a boundary vertex of 18
/// edges, an open grid with pinned corners; pattern levels
/// dividing 32 (exact lattice rows) and not (interpolated), tess below and above 32. Chunked
/// records too (an owner may be in another chunk).
#[test]
fn loop_matches_mirror_on_every_driver() {
    with_gpu(64, 64, |h| {
        let l = Which::Loop(Boundary::EdgeOnly, 5);
        check_pattern("spot_control_tri.obj", h, &[1, 4, 7], l);
        check_tess("spot_control_tri.obj", h, &[4, 7], l);
        check_pattern("fan24_open.obj", h, &[8, 32], l);
        check_tess("fan24_open.obj", h, &[5, 64], l);
        // A boundary vertex of 18 edges: its faces' tables dropped the columns they do not weigh.
        check_pattern("halfdisc17_open.obj", h, &[32], l);
        let corners = Which::Loop(Boundary::EdgeAndCorner, 5);
        check_pattern("grid_open_8x8.obj", h, &[3, 16], corners);
        check_tess("grid_open_8x8.obj", h, &[6], corners);
        check_pattern_chunked("tetrahedron.obj", h, &[4], l, Some(5));
        // Another table level: level 8 is its lattice, 5 and 12 are not.
        let coarse = Which::Loop(Boundary::EdgeOnly, 3);
        check_pattern("spot_control_tri.obj", h, &[8, 5, 12], coarse);
        check_tess("spot_control_tri.obj", h, &[6], coarse);
    });
}

/// Records bound in chunks (a storage-buffer descriptor spans at most maxStorageBufferRange
/// bytes, so large meshes are drawn chunk by chunk) and captures made in passes (a capture buffer
/// likewise): with chunks of 7 of icosahedron's 20 elements and capture passes of 3 elements,
/// every driver and submission mode still evaluates exactly what the mirror does, in the right
/// slots, and the images are the same as unchunked.
#[test]
fn chunked_records_and_capture_passes_match_the_mirror() {
    with_gpu(64, 64, |h| {
        h.max_capture_bytes = Some(3 * 21 * 64); // 3 elements of a level-5 pattern
        check_pattern_chunked("icosahedron_vn.obj", h, &[5], false, Some(7));
        h.max_capture_bytes = Some(3 * 2 * 19 * 64); // 3 elements of level-4 tess capture
        check_tess_chunked("icosahedron_vn.obj", h, &[4], false, Some(7));
        h.max_capture_bytes = None;
        let (mut whole, camera, _) = scene_with(h, model("icosahedron_vn.obj"), &[5]);
        let (mut chunked, _, _) = scene_chunked(h, model("icosahedron_vn.obj"), &[5], Some(7));
        assert_eq!(chunked.gpu.sets.len(), 3);
        for driver in Driver::VARIANTS {
            let cfg = DrawConfig::new(driver, 5).with_surface(Surface::Pn, Displace::None);
            let a = h.render(&mut whole, &cfg, &camera).unwrap();
            let b = h.render(&mut chunked, &cfg, &camera).unwrap();
            assert!(a.rgba == b.rgba, "{}: chunked image differs", cfg.label());
        }
    });
}

/// The tess driver's transform feedback (what `export` reads) carries each vertex's element,
/// among all the scene's, and the sample the surface was evaluated at: with records bound in
/// chunks of 7 of icosahedron's 20 elements and capture passes of 3 elements, every captured
/// vertex is the mirror's point at its element and sample, the three corners of a triangle
/// share their element, elements come in order with every tessellated triangle, and the samples
/// are exactly the capture variant's, snapped (`tess_weights`).
#[test]
fn tess_transform_feedback_carries_element_and_sample() {
    use meshrefine::render::tess::tess_triangle_count;
    use meshrefine::render::XfbVertex;
    with_gpu(64, 64, |h| {
        let level = 4;
        let (mut scene, camera, r) =
            scene_chunked(h, model("icosahedron_vn.obj"), &[level], Some(7));
        assert_eq!(scene.gpu.sets.len(), 3);
        let cfg = DrawConfig::new(Driver::Tess, level).with_surface(Surface::Pn, Displace::None);
        let per_element = tess_triangle_count(level) as usize;
        h.max_capture_bytes = Some((3 * per_element * 3 * std::mem::size_of::<XfbVertex>()) as u64);
        let tris = h.capture_triangles(&mut scene, &cfg, &camera).unwrap();
        h.max_capture_bytes = None;
        let n = scene.records(cfg.surface).len();
        assert_eq!(tris.len(), n * per_element);
        let hm = scene.mirror(&cfg, level).unwrap();
        let tol = position_tolerance(&cfg, r, seamed(&scene.data.records));
        let ntol = normal_tolerance(&cfg);
        let mut xfb: HashSet<(u32, [u32; 3])> = HashSet::new();
        for (k, tri) in tris.iter().enumerate() {
            let e = (k / per_element) as u32;
            for v in tri {
                assert_eq!(v.element, e, "triangle {k}");
                let want = hm.eval(
                    &cfg.params,
                    e as usize,
                    &scene.records(cfg.surface)[e as usize],
                    v.bary,
                );
                let got = meshrefine::render::CapturedVertex {
                    position: [v.position[0], v.position[1], v.position[2], 1.0],
                    normal: [v.normal[0], v.normal[1], v.normal[2], 0.0],
                    coord: [v.bary[0], v.bary[1], v.bary[2], 0.0],
                    id: [e, u32::MAX, 0, 0],
                };
                compare(
                    &got,
                    &want,
                    tol,
                    ntol,
                    &format!("element {e} at {:?}", v.bary),
                );
                xfb.insert((e, v.bary.map(f32::to_bits)));
            }
        }
        let cap = h.capture(&mut scene, &cfg, &camera).unwrap();
        let captured: HashSet<(u32, [u32; 3])> = cap
            .vertices
            .iter()
            .map(|v| {
                let tc = [v.coord[0], v.coord[1], v.coord[2]];
                (v.id[0], tess_weights(tc, level).map(f32::to_bits))
            })
            .collect();
        assert!(
            xfb == captured,
            "transform feedback's samples are not the capture's"
        );
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
            let cfg = DrawConfig::new(Driver::Pattern(submit), 1);
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
            .capture(&mut scene, &DrawConfig::new(Driver::Tess, 1), &camera)
            .unwrap();
        for v in &cap.vertices {
            let corner = [[0usize, 1, 2], [3, 2, 1]][v.id[0] as usize]
                [v.coord.iter().position(|&c| c == 1.0).unwrap()];
            assert_eq!(&v.position[..3], &positions[corner].to_array()[..]);
        }
    });
}
