//! The bounds against the surfaces themselves: dense sampling of the real evaluation
//! (`surface::eval_with`, what every driver mirrors) on real meshes and random elements.

use super::*;
use crate::mesh::test_support::load_model;
use crate::mesh::Mesh;
use crate::pattern::weight;
use crate::subdiv::bft::Lattice;
use crate::subdiv::Boundary;
use crate::surface::loop_::LoopData;
use crate::surface::{
    build_records, eval_with, CornerRecord, Displace, ElementRecord, Heightmap, Inputs, RecordKind,
    Seams, Surface, SurfaceParams,
};
use glam::{Mat4, Vec3, Vec4};

/// Interior sample grid per lattice triangle (points `a/R, b/R, c/R`).
const R: u32 = 6;
/// Samples per segment along an edge.
const RE: u32 = 16;

fn lattice_bary(n: u32, i: u32, j: u32) -> [f32; 3] {
    [weight(n - i - j, n), weight(i, n), weight(j, n)]
}

fn mix(b: [[f32; 3]; 3], l: [f32; 3]) -> [f32; 3] {
    [0, 1, 2].map(|c| b[0][c] * l[0] + b[1][c] * l[1] + b[2][c] * l[2])
}

/// The lattice triangles of level `n` as lattice coordinates.
fn lattice_triangles(n: u32) -> Vec<[(u32, u32); 3]> {
    let mut out = Vec::new();
    for j in 0..n {
        for i in 0..n - j {
            out.push([(i, j), (i + 1, j), (i, j + 1)]);
            if i + j + 1 < n {
                out.push([(i + 1, j), (i + 1, j + 1), (i, j + 1)]);
            }
        }
    }
    out
}

struct Case<'a> {
    surface: Surface,
    displace: Displace,
    params: SurfaceParams,
    inputs: Inputs<'a>,
}

impl Case<'_> {
    fn at(&self, rec: &ElementRecord, b: [f32; 3]) -> Vec3 {
        eval_with(
            self.surface,
            self.displace,
            &self.params,
            rec,
            b,
            &self.inputs,
        )
        .position
    }

    fn lod(&self) -> Lod<'_> {
        Lod::new(self.surface, self.displace, &self.params, &self.inputs)
    }

    /// The true largest distance between the surface and its interpolation at level `n`, over
    /// the element (dense samples of every lattice triangle) and along each stored edge.
    fn true_error(&self, rec: &ElementRecord, n: u32) -> (f32, [f32; 3]) {
        let mut inner = 0.0f32;
        for t in lattice_triangles(n) {
            let b = t.map(|(i, j)| lattice_bary(n, i, j));
            let p = b.map(|b| self.at(rec, b));
            for c in 0..=R {
                for a in 0..=R - c {
                    let l = [(R - a - c) as f32, a as f32, c as f32].map(|x| x / R as f32);
                    let lin = p[0] * l[0] + p[1] * l[1] + p[2] * l[2];
                    inner = inner.max((self.at(rec, mix(b, l)) - lin).length());
                }
            }
        }
        let mut edges = [0.0f32; 3];
        for (e, out) in edges.iter_mut().enumerate() {
            let on = |t: f32| {
                let mut b = [0.0f32; 3];
                b[e] = 1.0 - t;
                b[(e + 1) % 3] = t;
                b
            };
            for k in 0..n {
                let (b0, b1) = (on(k as f32 / n as f32), on((k + 1) as f32 / n as f32));
                let (p0, p1) = (self.at(rec, b0), self.at(rec, b1));
                for s in 1..RE {
                    let f = s as f32 / RE as f32;
                    let b = [0, 1, 2].map(|c| b0[c] * (1.0 - f) + b1[c] * f);
                    *out = out.max((self.at(rec, b) - (p0 * (1.0 - f) + p1 * f)).length());
                }
            }
        }
        (inner, edges)
    }

    /// Checks every bound of `records` at `levels` against sampling; returns the smallest and
    /// the median ratio bound / truth over the elements whose true error is above rounding.
    fn check(
        &self,
        records: &[ElementRecord],
        levels: &[u32],
        scale: f32,
        what: &str,
    ) -> (f32, f32) {
        self.check_with(records, levels, scale, what, 1.0)
    }

    /// [`Case::check`] with every bound multiplied by `shrink` (below 1: a bound made too
    /// small, which the check must catch).
    fn check_with(
        &self,
        records: &[ElementRecord],
        levels: &[u32],
        scale: f32,
        what: &str,
        shrink: f32,
    ) -> (f32, f32) {
        let lod = self.lod();
        let slack = 64.0 * f32::EPSILON * scale;
        let mut ratios = Vec::new();
        for (ix, rec) in records.iter().enumerate() {
            let b = lod.element(rec);
            let eb = [0, 1, 2].map(|e| lod.edge(rec, e));
            for &n in levels {
                let (inner, edges) = self.true_error(rec, n);
                let bound = b.chord.error(n as f32) * shrink;
                assert!(
                    inner <= bound + slack,
                    "{what}: element {ix} at level {n}: true chord error {inner} above the bound {bound}"
                );
                for e in 0..3 {
                    let eb = eb[e].chord.error(n as f32) * shrink;
                    assert!(
                        edges[e] <= eb + slack,
                        "{what}: element {ix} edge {e} at level {n}: true {} above the bound {eb}",
                        edges[e]
                    );
                }
                if inner > 1e3 * slack && bound.is_finite() {
                    ratios.push(bound / inner);
                }
            }
        }
        ratios.sort_by(f32::total_cmp);
        let min = ratios.first().copied().unwrap_or(1.0);
        let median = ratios.get(ratios.len() / 2).copied().unwrap_or(1.0);
        eprintln!("{what}: bound / truth smallest {min}, median {median}");
        (min, median)
    }
}

fn corner_records(file: &str) -> (Mesh, Vec<ElementRecord>) {
    let (mesh, _) = load_model(file);
    let recs = build_records(RecordKind::Corners, &mesh, Seams::Closed);
    (mesh, recs)
}

/// Random triangles of size about 1 with normals up to ~45° off the face normal.
fn random_records(count: usize, seed: u64) -> Vec<ElementRecord> {
    let mut s = seed;
    let mut rnd = move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 33) as f32 / (1u64 << 31) as f32) * 2.0 - 1.0
    };
    (0..count)
        .map(|i| {
            let p = [0; 3].map(|_| Vec3::new(rnd(), rnd(), rnd()));
            let f = (p[1] - p[0]).cross(p[2] - p[0]).normalize();
            let n = [0; 3].map(|_| (f + Vec3::new(rnd(), rnd(), rnd()) * 0.55).normalize());
            let i = i as u32 * 3;
            CornerRecord::new(p, n, [i + 2, i, i + 1]).encode()
        })
        .collect()
}

fn every(v: &[ElementRecord], step: usize) -> Vec<ElementRecord> {
    v.iter().step_by(step).copied().collect()
}

/// Undisplaced local surfaces on spot, on a mesh with hard edges (flagged seams), and on random
/// elements: never below the truth, and within 20x of it on typical elements.
#[test]
fn local_surface_bounds_hold_and_are_useful() {
    let (spot, recs) = corner_records("spot_control_tri_vn.obj");
    let (cyl_mesh, cyl) = corner_records("cylinder_hard_normals.obj");
    let (cyl_tags, _) = crate::surface::stpn::derive(&cyl_mesh);
    assert!(cyl_tags.iter().filter(|t| t.crease()).count() > 10);
    let random = random_records(40, 7);
    let r = spot.bounding_radius();
    let (tags, _) = crate::surface::stpn::derive(&spot);
    for surface in [Surface::Flat, Surface::Phong, Surface::Pn, Surface::Stpn] {
        let case = Case {
            surface,
            displace: Displace::None,
            params: SurfaceParams::default(),
            inputs: Inputs {
                tags: Some(&tags),
                ..Default::default()
            },
        };
        let what = surface.name();
        let (_, m) = case.check(&every(&recs, 4), &[1, 2, 3, 5, 8], r, what);
        if surface != Surface::Flat {
            assert!(m <= 20.0, "{what} on spot: median bound / truth {m}");
        }
        let plain = Case {
            inputs: Inputs::default(),
            ..case
        };
        let (_, m) = plain.check(&random, &[1, 2, 4, 7], 2.0, what);
        if surface != Surface::Flat {
            assert!(m <= 20.0, "{what} random: median bound / truth {m}");
        }
        // Hard edges: flagged seams, and crease tags for stpn.
        let hard = Case {
            inputs: Inputs {
                tags: Some(&cyl_tags),
                ..Default::default()
            },
            ..plain
        };
        hard.check(&cyl, &[1, 3, 6], 2.0, what);
        if surface != Surface::Flat {
            let displaced = Case {
                displace: Displace::Sine,
                params: SurfaceParams::for_radius(cyl_mesh.bounding_radius()),
                ..hard
            };
            displaced.check(&cyl, &[1, 3], 2.0, &format!("{what} + sine"));
        }
    }
}

/// A bound made 2x too small is caught: the check has the power to see an underestimate
/// (the edges' bounds are the tightest: Phong's is exact). Not so for `noise`, whose bound is
/// at least about 5x the truth on every element of spot.
#[test]
fn halved_bounds_are_caught() {
    let (spot, recs) = corner_records("spot_control_tri_vn.obj");
    for (surface, displace) in [
        (Surface::Phong, Displace::None),
        (Surface::Pn, Displace::None),
        (Surface::Flat, Displace::Sine),
    ] {
        let case = Case {
            surface,
            displace,
            params: SurfaceParams::for_radius(spot.bounding_radius()),
            inputs: Inputs::default(),
        };
        let r = std::panic::catch_unwind(|| {
            // Ratios of 2 are rare: the largest-curvature elements must show it.
            case.check_with(&recs, &[1, 2, 4], spot.bounding_radius(), "halved", 0.5)
        });
        assert!(
            r.is_err(),
            "{} + {}: half the bound went unnoticed",
            surface.name(),
            displace.name()
        );
    }
}

/// Displacement over every local surface: sine and noise on spot, the height map on a textured
/// grid (two pyramid levels blended). Usefulness: `sine` over `flat` and `phong` is within 20x
/// of the truth on the median element. Where the bound multiplies extremes that an element
/// rarely meets together, the median is looser and the tightest element shows that the bound
/// is still approached: `noise` (its curvature bound is its largest anywhere, and a small patch
/// sees a fraction of it: median about 100-300x, tightest about 15-25x) and `sine` over `pn`
/// (PN's quadratic normal field has control normals far from its values, so the moving
/// direction's derivative bounds are large: median about 50x, tightest about 7x).
#[test]
fn displaced_bounds_hold() {
    let (spot, recs) = corner_records("spot_control_tri_vn.obj");
    let r = spot.bounding_radius();
    let sub = every(&recs, 6);
    for surface in [Surface::Flat, Surface::Phong, Surface::Pn] {
        for displace in [Displace::Sine, Displace::Noise] {
            let case = Case {
                surface,
                displace,
                params: SurfaceParams {
                    octaves: 2,
                    ..SurfaceParams::for_radius(r)
                },
                inputs: Inputs::default(),
            };
            let what = format!("{} + {}", surface.name(), displace.name());
            let (min, median) = case.check(&sub, &[1, 2, 4, 6], r, &what);
            if displace == Displace::Sine && surface != Surface::Pn {
                assert!(median <= 20.0, "{what}: median bound / truth {median}");
            } else {
                assert!(min <= 30.0, "{what}: smallest bound / truth {min}");
                assert!(median <= 300.0, "{what}: median bound / truth {median}");
            }
        }
    }
    let (grid, _) = load_model("grid_uv_8x8.obj");
    let map = Heightmap::generated();
    let recs = build_records(RecordKind::Corners, &grid, Seams::Closed);
    for surface in [Surface::Flat, Surface::Pn] {
        let mut worst = 0.0f32;
        for (t, rec) in grid.triangles.iter().zip(&recs).step_by(5) {
            let uv = t.t.unwrap().map(|i| grid.texcoords[i as usize].to_array());
            let case = Case {
                surface,
                displace: Displace::Heightmap,
                params: SurfaceParams {
                    amplitude: 0.1 * grid.bounding_radius(),
                    bias: 0.5,
                    ..Default::default()
                },
                inputs: Inputs {
                    uv: Some(&uv),
                    heightmap: Some(&map),
                    lod: 1.5,
                    ..Default::default()
                },
            };
            let (_, m) = case.check(
                std::slice::from_ref(rec),
                &[1, 2, 4, 9],
                grid.bounding_radius(),
                "heightmap",
            );
            worst = worst.max(m);
        }
        assert!(worst <= 20.0, "heightmap: median bound / truth {worst}");
    }
}

/// Any triangle of the parameter domain (the transition triangles between an element's inner
/// level and its edges'): its chord error is within [`Bounds::triangle_error`].
#[test]
fn triangle_errors_hold_for_any_triangle() {
    let (spot, recs) = corner_records("spot_control_tri_vn.obj");
    let (grid, _) = load_model("grid_uv_8x8.obj");
    let grid_recs = build_records(RecordKind::Corners, &grid, Seams::Closed);
    let map = Heightmap::generated();
    let r = spot.bounding_radius();
    let mut s = 99u64;
    let mut rnd = move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 33) as f32 / (1u64 << 31) as f32
    };
    let mut checked = 0;
    for (surface, displace) in [
        (Surface::Phong, Displace::None),
        (Surface::Pn, Displace::None),
        (Surface::Flat, Displace::Sine),
        (Surface::Pn, Displace::Heightmap),
    ] {
        let on_grid = displace == Displace::Heightmap;
        let list = if on_grid { &grid_recs } else { &recs };
        for (ix, rec) in list.iter().enumerate().step_by(9) {
            let uv = grid.triangles[ix.min(grid.triangles.len() - 1)]
                .t
                .map(|t| t.map(|i| grid.texcoords[i as usize].to_array()));
            let case = Case {
                surface,
                displace,
                params: if on_grid {
                    SurfaceParams {
                        amplitude: 0.1 * grid.bounding_radius(),
                        bias: 0.5,
                        ..Default::default()
                    }
                } else {
                    SurfaceParams::for_radius(r)
                },
                inputs: Inputs {
                    uv: uv.as_ref().filter(|_| on_grid),
                    heightmap: Some(&map),
                    lod: 0.5,
                    ..Default::default()
                },
            };
            let b = case.lod().element(rec);
            for _ in 0..6 {
                let size = 0.02 + 0.5 * rnd();
                let c = [rnd(), rnd()];
                let tri =
                    [0; 3].map(|_| [c[0] + size * (rnd() - 0.5), c[1] + size * (rnd() - 0.5)]);
                if tri
                    .iter()
                    .any(|p| p[0] < 0.0 || p[1] < 0.0 || p[0] + p[1] > 1.0)
                {
                    continue;
                }
                let bary = |p: [f32; 2]| [1.0 - p[0] - p[1], p[0], p[1]];
                let pts = tri.map(|p| case.at(rec, bary(p)));
                let mut truth = 0.0f32;
                for k in 0..=R {
                    for a in 0..=R - k {
                        let l = [(R - a - k) as f32, a as f32, k as f32].map(|x| x / R as f32);
                        let p =
                            [0, 1].map(|d| tri[0][d] * l[0] + tri[1][d] * l[1] + tri[2][d] * l[2]);
                        let lin = pts[0] * l[0] + pts[1] * l[1] + pts[2] * l[2];
                        truth = truth.max((case.at(rec, bary(p)) - lin).length());
                    }
                }
                let bound = b.triangle_error(tri);
                assert!(
                    truth <= bound + 64.0 * f32::EPSILON * r,
                    "{} + {}: triangle {tri:?}: true {truth} above {bound}",
                    surface.name(),
                    displace.name()
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 100, "{checked}");
}

/// Loop: spot's M1 faces, at dyadic and other levels, with extraordinary vertices of valence 3
/// to 10.
#[test]
fn loop_bounds_hold() {
    let (mesh, _) = load_model("spot_control_tri.obj");
    let data = LoopData::new(&mesh, Boundary::EdgeOnly, Lattice::default(), |_| {}).unwrap();
    let frame = data.frame(&mesh.positions);
    let case = Case {
        surface: Surface::Loop,
        displace: Displace::None,
        params: SurfaceParams::default(),
        inputs: Inputs {
            loop_: Some((&data, &frame)),
            ..Default::default()
        },
    };
    let (_, m) = case.check(
        &every(&data.records, 23),
        &[1, 2, 3, 4, 8],
        mesh.bounding_radius(),
        "loop",
    );
    assert!(m <= 20.0, "loop: median bound / truth {m}");
}

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
            let inputs = Inputs {
                tags: Some(&tags),
                ..Default::default()
            };
            let lod = Lod::new(surface, displace, &params, &inputs);
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
    let inputs = Inputs {
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
            let lod = Lod::new(surface, displace, &params, &inputs);
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
    let inputs = Inputs {
        loop_: Some((&data, &frame)),
        ..Default::default()
    };
    let lod = Lod::new(Surface::Loop, Displace::None, &params, &inputs);
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

/// Every sampled point of every surface and displacement is inside its element's sphere.
#[test]
fn spheres_contain_the_displaced_patch() {
    let (spot, recs) = corner_records("spot_control_tri_vn.obj");
    let params = SurfaceParams {
        octaves: 3,
        ..SurfaceParams::for_radius(spot.bounding_radius())
    };
    for surface in [Surface::Phong, Surface::Pn, Surface::Stpn] {
        for displace in [Displace::None, Displace::Sine, Displace::Noise] {
            let case = Case {
                surface,
                displace,
                params,
                inputs: Inputs::default(),
            };
            let lod = case.lod();
            for rec in recs.iter().step_by(3) {
                let s = lod.element(rec).sphere;
                let edges = [0, 1, 2].map(|e| lod.edge(rec, e).sphere);
                for (i, j) in crate::pattern::Pattern::uniform(9).lattice() {
                    let b = lattice_bary(9, i, j);
                    let p = case.at(rec, b);
                    assert!((p - s.centre).length() <= s.radius, "{}", surface.name());
                    for e in 0..3 {
                        if b[(e + 2) % 3] == 0.0 {
                            let d = (p - edges[e].centre).length();
                            assert!(d <= edges[e].radius, "edge sphere");
                        }
                    }
                }
            }
        }
    }
}

/// A camera close to spot, looking past part of it.
fn close_camera(spot: &Mesh) -> (Vec3, Mat4, f32, f32) {
    let (lo, hi) = spot.bounds();
    let centre = (lo + hi) * 0.5;
    let r = spot.bounding_radius();
    let eye = centre + Vec3::new(0.4, 0.25, 1.0).normalize() * (1.6 * r);
    let target = centre + Vec3::new(0.7 * r, 0.2 * r, 0.0);
    let fov = 50f32.to_radians();
    let aspect = 16.0 / 9.0;
    let mut proj = Mat4::perspective_rh(fov, aspect, 0.01 * r, 10.0 * r);
    proj.y_axis.y = -proj.y_axis.y;
    (
        eye,
        proj * Mat4::look_at_rh(eye, target, Vec3::Y),
        fov,
        aspect,
    )
}

fn clip_inside(vp: Mat4, p: Vec3) -> bool {
    let c = vp * Vec4::new(p.x, p.y, p.z, 1.0);
    c.x.abs() <= c.w && c.y.abs() <= c.w && c.z >= 0.0 && c.z <= c.w
}

#[test]
fn frustum_and_back_face_culling_are_conservative() {
    let (spot, recs) = corner_records("spot_control_tri_vn.obj");
    let (eye, vp, _, _) = close_camera(&spot);
    let frustum = Frustum::from_view_proj(vp);
    for surface in [Surface::Flat, Surface::Phong, Surface::Pn] {
        let case = Case {
            surface,
            displace: Displace::None,
            params: SurfaceParams::default(),
            inputs: Inputs::default(),
        };
        let lod = case.lod();
        let (mut outside, mut back) = (0, 0);
        for rec in &recs {
            let b = lod.element(rec);
            let out = frustum.outside(&b.sphere);
            let away = b.cone.is_some_and(|c| c.back_facing(&b.sphere, eye));
            outside += out as usize;
            back += away as usize;
            if !(out || away) {
                continue;
            }
            let n = 8;
            for t in lattice_triangles(n) {
                let p = t.map(|(i, j)| case.at(rec, lattice_bary(n, i, j)));
                let normal = (p[1] - p[0]).cross(p[2] - p[0]);
                for q in p {
                    if out {
                        assert!(
                            !clip_inside(vp, q),
                            "{}: a culled point is visible",
                            surface.name()
                        );
                    }
                    if away {
                        assert!(
                            (q - eye).dot(normal) > 0.0,
                            "{}: culled a front face",
                            surface.name()
                        );
                    }
                }
            }
            if away {
                for (i, j) in crate::pattern::Pattern::uniform(12).lattice() {
                    let sp = eval_with(
                        surface,
                        Displace::None,
                        &case.params,
                        rec,
                        lattice_bary(12, i, j),
                        &case.inputs,
                    );
                    assert!((sp.position - eye).dot(sp.dpdu.cross(sp.dpdv)) > 0.0);
                }
            }
        }
        assert!(
            outside > 10,
            "{}: only {outside} elements outside",
            surface.name()
        );
        assert!(
            back > 10,
            "{}: only {back} back-facing elements",
            surface.name()
        );
    }
}

/// The camera of the end-to-end check, and how its pixels are counted.
struct Screen {
    eye: Vec3,
    vp: Mat4,
    view: View,
    frustum: Frustum,
    axis: Vec3,
    size: glam::Vec2,
}

impl Screen {
    fn new(spot: &Mesh, px: f32) -> Self {
        let (eye, vp, fov, aspect) = close_camera(spot);
        let size = glam::Vec2::new(1920.0, 1080.0);
        assert!((size.x / size.y - aspect).abs() < 1e-3);
        let far = vp.inverse() * Vec4::new(0.0, 0.0, 1.0, 1.0);
        Self {
            eye,
            vp,
            view: View::new(eye, fov, size.y as u32, px, 64),
            frustum: Frustum::from_view_proj(vp),
            axis: ((far.truncate() / far.w) - eye).normalize(),
            size,
        }
    }

    fn pixel(&self, p: Vec3) -> glam::Vec2 {
        let c = self.vp * Vec4::new(p.x, p.y, p.z, 1.0);
        (glam::Vec2::new(c.x, c.y) / c.w + 1.0) * 0.5 * self.size
    }

    /// Asserts that surface point `s`, drawn at `lin`, is within the pixel error (when
    /// visible); returns its metric pixels.
    fn check(&self, s: Vec3, lin: Vec3, what: &dyn Fn() -> String) -> f32 {
        if !clip_inside(self.vp, s) {
            return 0.0;
        }
        let px = self.view.pixel_error;
        let metric = self.view.pixels((s - lin).length(), s);
        assert!(metric <= px * 1.0001, "{}: {metric} px (metric)", what());
        let cos = (s - self.eye).normalize().dot(self.axis);
        let screen = (self.pixel(s) - self.pixel(lin)).length();
        assert!(
            screen * cos * cos <= px * 1.02,
            "{}: {screen} px on screen at cos {cos}",
            what()
        );
        metric
    }
}

/// Levels for every element in view, then dense samples of each element at its inner level and
/// of each edge at its own level; returns (elements checked, elements capped, worst metric px).
fn end_to_end(case: &Case, records: &[ElementRecord], screen: &Screen) -> (usize, usize, f32) {
    let lod = case.lod();
    let view = &screen.view;
    let (mut drawn, mut capped, mut worst) = (0usize, 0usize, 0.0f32);
    for rec in records {
        let b = lod.element(rec);
        if screen.frustum.outside(&b.sphere) {
            continue;
        }
        let edges = [0, 1, 2].map(|e| lod.edge(rec, e));
        let (edge_levels, inner) = view.levels(&b, &edges);
        let n = integer_level(inner);
        if n >= view.max_level && b.chord.error(n as f32) > view.tolerance(&b.sphere) {
            // Capped: the bound needs more than the maximum level here.
            capped += 1;
            continue;
        }
        drawn += 1;
        let what = || {
            format!(
                "{} + {} at level {n}",
                case.surface.name(),
                case.displace.name()
            )
        };
        for t in lattice_triangles(n) {
            let bb = t.map(|(i, j)| lattice_bary(n, i, j));
            let p = bb.map(|x| case.at(rec, x));
            for c in 0..=4u32 {
                for a in 0..=4 - c {
                    let l = [(4 - a - c) as f32, a as f32, c as f32].map(|x| x / 4.0);
                    let lin = p[0] * l[0] + p[1] * l[1] + p[2] * l[2];
                    worst = worst.max(screen.check(case.at(rec, mix(bb, l)), lin, &what));
                }
            }
        }
        for (e, &level) in edge_levels.iter().enumerate() {
            let m = integer_level(level);
            let on = |t: f32| {
                let mut b = [0.0f32; 3];
                b[e] = 1.0 - t;
                b[(e + 1) % 3] = t;
                b
            };
            let what = || format!("{} edge at level {m}", case.surface.name());
            for k in 0..m {
                let (p0, p1) = (
                    case.at(rec, on(k as f32 / m as f32)),
                    case.at(rec, on((k + 1) as f32 / m as f32)),
                );
                for s in 1..8 {
                    let f = (k as f32 + s as f32 / 8.0) / m as f32;
                    let lin = p0 + (p1 - p0) * (s as f32 / 8.0);
                    worst = worst.max(screen.check(case.at(rec, on(f)), lin, &what));
                }
            }
        }
    }
    (drawn, capped, worst)
}

/// The metric end to end: levels for a real mesh and camera, then every visible sample of every
/// element drawn at its inner level, and of every edge drawn at its own level, is within the
/// pixel error of the drawn mesh, in the metric's own pixels (`d·K/|p − eye|`) and on screen
/// through the real projection (where a deviation at angle φ off the view axis shows up to
/// `1/cos²φ` larger than the metric counts). The worst sample must come within a small factor
/// of the bound, so the check is not vacuous.
#[test]
fn pixel_error_holds_end_to_end() {
    let (spot, recs) = corner_records("spot_control_tri_vn.obj");
    let (tags, _) = crate::surface::stpn::derive(&spot);
    let screen = Screen::new(&spot, 1.0);
    let r = spot.bounding_radius();
    let (plain, _) = load_model("spot_control_tri.obj");
    assert_eq!(plain.positions, spot.positions);
    let data = LoopData::new(&plain, Boundary::EdgeOnly, Lattice::default(), |_| {}).unwrap();
    let frame = data.frame(&plain.positions);
    for (surface, displace) in [
        (Surface::Pn, Displace::None),
        (Surface::Stpn, Displace::None),
        (Surface::Phong, Displace::Noise),
        (Surface::Flat, Displace::Sine),
        (Surface::Loop, Displace::None),
    ] {
        let case = Case {
            surface,
            displace,
            params: SurfaceParams {
                amplitude: 0.01 * r,
                // Noise cells four times the size of the sine's waves.
                frequency: if displace == Displace::Noise {
                    6.0 / r
                } else {
                    24.0 / r
                },
                ..SurfaceParams::for_radius(r)
            },
            inputs: Inputs {
                tags: Some(&tags),
                loop_: Some((&data, &frame)),
                ..Default::default()
            },
        };
        let records = if surface == Surface::Loop {
            every(&data.records, 3)
        } else {
            recs.clone()
        };
        let (drawn, capped, worst) = end_to_end(&case, &records, &screen);
        let what = format!("{} + {}", surface.name(), displace.name());
        eprintln!("{what}: {drawn} elements checked, {capped} capped, worst {worst} px");
        assert!(drawn > 50, "{what}: only {drawn} elements in view");
        assert!(
            capped * 20 <= drawn,
            "{what}: {capped} of {drawn} elements capped"
        );
        assert!(worst > 1.0 / 20.0, "{what}: worst {worst} px");
    }
}

/// The noise constants cover the scan of every corner-gradient choice, with at most 10% room.
#[test]
fn noise_constants_cover_the_scan() {
    use super::displace::{noise_scan, NOISE_GRAD, NOISE_HESS, NOISE_MAX};
    let (v, g, d, o) = noise_scan(64);
    assert!(NOISE_MAX >= v && NOISE_MAX <= 1.1 * v, "value {v}");
    let g = g * 3f32.sqrt();
    assert!(NOISE_GRAD >= g && NOISE_GRAD <= 1.1 * g, "gradient {g}");
    let h = d + 2.0 * o;
    assert!(NOISE_HESS >= h && NOISE_HESS <= 1.1 * h, "hessian {h}");
    // The scan finds what sampling the real noise finds (its largest gradient component is
    // reached), so it is the noise's, not another function's.
    let mut worst = 0.0f32;
    for i in 0..20000 {
        let p = Vec3::new(
            i as f32 * 0.0137,
            i as f32 * 0.0291 + 0.3,
            i as f32 * 0.0077 + 0.6,
        );
        let (n, grad) = crate::surface::noise::noise_grad(p);
        assert!(n.abs() <= v && grad.abs().max_element() <= g);
        worst = worst.max(grad.abs().max_element());
    }
    assert!(worst > 0.5 * g / 3f32.sqrt(), "{worst}");
}
