//! What the watertightness checks share (tests/watertight.rs, tests/tess_adaptive.rs): the
//! closed meshes and surfaces they weld, a scene framing a mesh, and welding on exact bits.

use super::random_levels::{crack_free_vertices, element_corners, open_edges, random_levels};
use meshrefine::export::weld_triangles;
use meshrefine::mesh::Mesh;
use meshrefine::pattern::PatternSet;
use meshrefine::render::tess::{outer_levels, tess_triangle_count_levels};
use meshrefine::render::{Camera, Capture, DrawConfig, Driver, Headless, Scene};
use meshrefine::surface::{Displace, Surface, SurfaceParams};
use std::collections::HashSet;

/// Surface x displacement combinations checked on every driver.
pub const SURFACES: &[(Surface, Displace)] = &[
    (Surface::Flat, Displace::None),
    (Surface::Phong, Displace::Sine),
    (Surface::Pn, Displace::None),
    (Surface::Pn, Displace::Noise),
    // Tags derived from the hard edges: the cylinder's rims become creases, closed.
    (Surface::Stpn, Displace::None),
];

pub fn config(driver: Driver, n: u32, (s, d): (Surface, Displace), r: f32) -> DrawConfig {
    let mut cfg = DrawConfig::new(driver, n).with_surface(s, d);
    cfg.params = SurfaceParams::for_radius(r);
    cfg
}
pub const CLOSED: &[&str] = &[
    "tetrahedron.obj",
    "octahedron.obj",
    "icosahedron.obj",
    "cube_tri.obj",
    "torus_16x8.obj",
    "bicone16.obj",
    "uvsphere12.obj",
    "spot_control_tri.obj",
    // Split normals (several `vn` at a position): watertight with closed seams (the default).
    "cylinder_hard_normals.obj",
    "cube_face_normals.obj",
];

/// `mesh` uploaded with patterns of `levels`, and a camera framing it.
pub fn scene_at(h: &Headless, mesh: &Mesh, levels: &[u32]) -> (Scene, Camera) {
    let scene = Scene::with_patterns(
        &h.ctx,
        &h.pool,
        &h.renderer,
        mesh.clone(),
        PatternSet::from_levels(levels),
    )
    .unwrap();
    let (c, r) = scene.bounding_sphere();
    (scene, Camera::framing(c, r))
}

/// Distinct positions the tess driver's capture variant evaluated for `cfg`.
pub fn tess_positions(
    h: &mut Headless,
    scene: &mut Scene,
    cfg: &DrawConfig,
    camera: &Camera,
) -> usize {
    let cap = h.capture(scene, cfg, camera).unwrap();
    let distinct: HashSet<[u32; 3]> = cap
        .vertices
        .iter()
        .map(|v| bits(&v.position[..3]))
        .collect();
    distinct.len()
}

pub fn bits(p: &[f32]) -> [u32; 3] {
    [p[0], p[1], p[2]].map(|x| if x == 0.0 { 0 } else { x.to_bits() })
}

pub fn assert_closed(triangles: &[[(u32, u32); 3]], what: &str) {
    let open = open_edges(triangles);
    assert_eq!(
        open, 0,
        "{what}: {open} welded edges are not shared by exactly two triangles (a crack)"
    );
}

/// `cfg` (tess, largest level `cfg.level`) drawn adaptively at random levels from `seed` (one
/// per unique edge, shared; inner levels at least their edges'): the evaluated vertices and the
/// transform-feedback triangles weld on exact bits into exactly the vertex count of a
/// crack-free tessellation, and the triangles into a closed mesh where `file`'s is closed.
pub fn check_tess_adaptive(
    h: &mut Headless,
    scene: &mut Scene,
    camera: &Camera,
    cfg: &DrawConfig,
    seed: u32,
    file: &str,
) {
    let (surface, max) = (cfg.surface, cfg.level);
    let what = format!(
        "{file} {} + {} tess adaptive",
        surface.name(),
        cfg.displace.name()
    );
    h.prepared_elements(scene, cfg, Capture::None).unwrap();
    let corners = element_corners(scene, surface);
    let levels = random_levels(&corners, max, 0.0, seed);
    scene.elements_mut(surface).upload_levels(&levels);
    h.adaptive = true;
    let want = crack_free_vertices(&corners, &levels, |l| outer_levels(l, max));
    assert_eq!(tess_positions(h, scene, cfg, camera), want, "{what}");
    let tris = h.capture_triangles(scene, cfg, camera).unwrap();
    let count: u32 = levels
        .iter()
        .map(|l| {
            let (outer, inner) = outer_levels(l, max).unwrap();
            tess_triangle_count_levels(outer, inner)
        })
        .sum();
    assert_eq!(tris.len(), count as usize, "{what}: triangles");
    let welded = weld_triangles(&tris);
    assert_eq!(welded.positions.len(), want, "{what}: triangles welded");
    if CLOSED.contains(&file) {
        assert_closed(&welded.triangles, &format!("{what} triangles"));
    }
    h.adaptive = false;
}
