//! Each surface's and displacement's bound against dense sampling: undisplaced, halved,
//! displaced, any parameter triangle (Loop's: loop_bounds.rs).

use super::heightmap::{grid_case, uv_grid};
use super::*;

/// Undisplaced local surfaces on spot, on a mesh with hard edges (flagged seams), and on random
/// elements: never below the truth, and within 5x of it on typical elements (median).
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
            field: NormalField::default(),
            displace: Displace::None,
            params: SurfaceParams::default(),
            inputs: Sources {
                tags: Some(&tags),
                ..Default::default()
            },
        };
        let what = surface.name();
        let (_, m) = case.check(&every(&recs, 4), &[1, 2, 3, 5, 8], r, what);
        // Useful, not only safe: docs/adaptivity.md gives phong 1.33, pn and stpn 2.3 to 3.6
        // (a bound several times looser would refine several times too much).
        if surface != Surface::Flat {
            assert!(m <= 5.0, "{what} on spot: median bound / truth {m}");
        }
        let plain = Case {
            inputs: Sources::default(),
            ..case
        };
        let (_, m) = plain.check(&random, &[1, 2, 4, 7], 2.0, what);
        if surface != Surface::Flat {
            assert!(m <= 5.0, "{what} random: median bound / truth {m}");
        }
        // Hard edges: flagged seams, and crease tags for stpn.
        let hard = Case {
            inputs: Sources {
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
    // Phong at alpha 0 is the flat triangle: bounded as flat (zero) where its corners blend
    // seam normals too, and the check agrees.
    let unbent = Case {
        surface: Surface::Phong,
        field: NormalField::default(),
        displace: Displace::None,
        params: SurfaceParams {
            alpha: 0.0,
            ..SurfaceParams::default()
        },
        inputs: Sources::default(),
    };
    unbent.check(&cyl, &[1, 3, 6], 2.0, "phong at alpha 0 on the cylinder");
    let lod = unbent.lod();
    for rec in &cyl {
        let b = lod.element(rec);
        assert_eq!((b.chord.c1, b.chord.c2), (0.0, 0.0), "{b:?}");
    }
    // Not vacuous: at the default alpha the cylinder's corners do blend seam normals.
    let bent = Case {
        params: SurfaceParams::default(),
        ..unbent
    };
    let blended = (cyl.iter())
        .filter(|rec| bent.lod().element(rec).chord.c2.is_infinite())
        .count();
    assert!(blended >= 4, "{blended} blended elements on the cylinder");
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
        let case = Case::plain(
            surface,
            displace,
            SurfaceParams::for_radius(spot.bounding_radius()),
        );
        let r = std::panic::catch_unwind(|| {
            // Ratios of 2 are rare: the largest-curvature elements must show it.
            case.check_lod(
                &case.lod(),
                &recs,
                &[1, 2, 4],
                spot.bounding_radius(),
                "halved",
                0.5,
            )
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
/// grid (two pyramid levels blended; its median element's bound about 8x the truth). Usefulness: `sine` over `flat` and `phong` is within 20x
/// of the truth on the median element. Where the bound multiplies extremes that an element
/// rarely meets together, the median is looser and the tightest element shows that the bound
/// is still approached: `noise` (its curvature bound is its largest anywhere, and a small patch
/// sees a fraction of it: median about 40-80x, tightest about 6-8.5x) and `sine` over `pn`
/// with the paper's normal field (its control normals are far from its values, so the moving
/// direction's derivative bounds are large: median about 23x, tightest about 4.6x). The other
/// normal fields: `displaced_bounds_hold_for_every_normal_field`.
#[test]
fn displaced_bounds_hold() {
    let (spot, recs) = corner_records("spot_control_tri_vn.obj");
    let r = spot.bounding_radius();
    let sub = every(&recs, 6);
    for surface in [Surface::Flat, Surface::Phong, Surface::Pn] {
        for displace in [Displace::Sine, Displace::Noise] {
            let case = Case {
                surface,
                field: NormalField::Paper,
                displace,
                params: SurfaceParams {
                    octaves: 2,
                    ..SurfaceParams::for_radius(r)
                },
                inputs: Sources::default(),
            };
            let what = format!("{} + {}", surface.name(), displace.name());
            let (min, median) = case.check(&sub, &[1, 2, 4, 6], r, &what);
            if displace == Displace::Sine && surface != Surface::Pn {
                assert!(median <= 20.0, "{what}: median bound / truth {median}");
            } else if displace == Displace::Noise {
                assert!(min <= 15.0, "{what}: smallest bound / truth {min}");
                assert!(median <= 150.0, "{what}: median bound / truth {median}");
            } else {
                assert!(min <= 30.0, "{what}: smallest bound / truth {min}");
                assert!(median <= 300.0, "{what}: median bound / truth {median}");
            }
        }
    }
    let (grid, recs, uvs) = uv_grid();
    let map = Heightmap::generated();
    // pn with each normal field: the paper's is constant on a plane with equal normals (its
    // control normals are 2N), Vlachos' has unit control normals, so its unnormalized net
    // varies in length there and its bound is a little looser.
    let cases = [
        (Surface::Flat, NormalField::Paper, 10.0),
        (Surface::Pn, NormalField::Paper, 10.0),
        (Surface::Pn, NormalField::Vlachos, 14.0),
        (Surface::Pn, NormalField::Linear, 10.0),
    ];
    for (surface, normal_field, limit) in cases {
        let mut worst = 0.0f32;
        for (t, rec) in recs.iter().enumerate().step_by(5) {
            let base = grid_case(&grid, &uvs, &map, t);
            let case = Case {
                surface,
                field: normal_field,
                inputs: Sources {
                    lod: 1.5,
                    ..base.inputs
                },
                ..base
            };
            let (_, m) = case.check(
                std::slice::from_ref(rec),
                &[1, 2, 4, 9],
                grid.bounding_radius(),
                "heightmap",
            );
            worst = worst.max(m);
        }
        assert!(
            worst <= limit,
            "heightmap on {} ({}): median bound / truth {worst}",
            surface.name(),
            normal_field.name()
        );
    }
}

/// `sine` close to its centre, where the curvature of `|P|` across the radius, `a f / r_min`,
/// outweighs the radial `a f²`: on the 8x8 grid (z = 0) with the centre 0.3 below it at
/// frequency 4 (f / r_min up to about 30 against f² = 16), every bound holds by dense sampling,
/// flat and as `pn`, and is approached on the tightest element (within 4x flat; `pn`'s moving
/// direction adds its own derivative bounds, as in `displaced_bounds_hold`).
#[test]
fn sine_bounds_hold_close_to_its_centre() {
    let (grid, recs) = corner_records("grid_open_8x8.obj");
    for (surface, limit) in [(Surface::Flat, 4.0), (Surface::Pn, 30.0)] {
        let case = Case::plain(
            surface,
            Displace::Sine,
            SurfaceParams {
                amplitude: 0.2,
                frequency: 4.0,
                origin: glam::Vec3::new(0.1, 0.05, -0.3),
                ..SurfaceParams::default()
            },
        );
        let what = format!("{} + sine near its centre", surface.name());
        let (min, _) = case.check(&recs, &[1, 2, 4, 8], grid.bounding_radius(), &what);
        // Above 1: elements were compared (with none, `check` returns 1).
        assert!(min > 1.0, "{what}: no element's error above rounding");
        assert!(min <= limit, "{what}: smallest bound / truth {min}");
    }
}

/// The displacement direction is `pn`'s and `stpn`'s normal field: the bounds hold with every
/// choice of it, over spot and over a mesh with hard edges (flagged seams, and crease tags whose
/// sharp normals `stpn` interpolates).
#[test]
fn displaced_bounds_hold_for_every_normal_field() {
    let (spot, recs) = corner_records("spot_control_tri_vn.obj");
    let (cyl_mesh, cyl) = corner_records("cylinder_hard_normals.obj");
    let (cyl_tags, _) = crate::surface::stpn::derive(&cyl_mesh);
    let r = spot.bounding_radius();
    for field in NormalField::ALL {
        for surface in [Surface::Pn, Surface::Stpn] {
            for displace in [Displace::Sine, Displace::Noise] {
                let what = format!(
                    "{} ({}) + {}",
                    surface.name(),
                    field.name(),
                    displace.name()
                );
                let case = Case {
                    surface,
                    field,
                    displace,
                    params: SurfaceParams {
                        ..SurfaceParams::for_radius(r)
                    },
                    inputs: Sources::default(),
                };
                let (min, median) = case.check(&every(&recs, 6), &[1, 2, 4, 6], r, &what);
                assert!(min <= 30.0, "{what}: smallest bound / truth {min}");
                assert!(median <= 300.0, "{what}: median bound / truth {median}");
                let hard = Case {
                    params: SurfaceParams::for_radius(cyl_mesh.bounding_radius()),
                    inputs: Sources {
                        tags: Some(&cyl_tags),
                        ..Default::default()
                    },
                    ..case
                };
                hard.check(&cyl, &[1, 3], 2.0, &format!("{what} on the cylinder"));
            }
        }
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
                field: NormalField::default(),
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
                inputs: Sources {
                    uvs: uv.as_ref().filter(|_| on_grid).map(std::slice::from_ref),
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

/// The largest `|D²P[d_k, d_{k+1}]|` sampled on lattice parallelograms of `g` segments per side:
/// `|P(x) − P(x + a) − P(x + b) + P(x + a + b)| / h²` for the steps `a = h d_k`, `b = h d_{k+1}`
/// (`h = 1/g`, stored directions). This is `h⁻²` times the integral of `D²P[a, b]` over the
/// parallelogram, never above its supremum there, and it is the value at the parallelogram's
/// centre exactly where `D²P` is affine (a cubic), so it reaches the corners' values within one
/// step. Returns per pair and the largest `|P|` (for the rounding slack).
pub(super) fn sampled_mixed(case: &Case, rec: &ElementRecord, g: i32) -> ([f32; 3], f32) {
    let at = |i: i32, j: i32| {
        case.at(
            rec,
            [(g - i - j) as f32, i as f32, j as f32].map(|x| x / g as f32),
        )
    };
    let mut p = std::collections::HashMap::new();
    let mut big = 0.0f32;
    for j in 0..=g {
        for i in 0..=g - j {
            let x = at(i, j);
            big = big.max(x.length());
            p.insert((i, j), x);
        }
    }
    // Stored directions as lattice steps in (i, j) = (weight of corner 1, of corner 2).
    let d = [(1, 0), (-1, 1), (0, -1)];
    let mut out = [0.0f32; 3];
    for (k, o) in out.iter_mut().enumerate() {
        let (a, b) = (d[k], d[(k + 1) % 3]);
        for (&(i, j), &x) in &p {
            let q = |s: i32, t: i32| p.get(&(i + s * a.0 + t * b.0, j + s * a.1 + t * b.1));
            if let (Some(xa), Some(xb), Some(xab)) = (q(1, 0), q(0, 1), q(1, 1)) {
                let v = ((x + *xab) - (*xa + *xb)).length() * (g * g) as f32;
                *o = o.max(v);
            }
        }
    }
    (out, big)
}

/// The mixed second-derivative bounds ([`Bounds::mixed`]) against sampling of the real
/// evaluation, per stored pair of directions: never below it on Spot's elements and random ones,
/// undisplaced and displaced, never above polarization's `Σ/2`; and Phong's, whose second
/// derivatives are constant, equal to the sampling (so an underestimate of a thousandth would
/// fail), which also pins the stored order of the pairs.
#[test]
fn mixed_bounds_hold_and_phong_s_are_exact() {
    let (spot, recs) = corner_records("spot_control_tri_vn.obj");
    let random = random_records(24, 11);
    let r = spot.bounding_radius();
    let mut ratios: Vec<(String, f32)> = Vec::new();
    for (surface, displace) in [
        (Surface::Flat, Displace::None),
        (Surface::Phong, Displace::None),
        (Surface::Pn, Displace::None),
        (Surface::Stpn, Displace::None),
        (Surface::Phong, Displace::Sine),
        (Surface::Pn, Displace::Sine),
        (Surface::Pn, Displace::Noise),
        (Surface::Stpn, Displace::Sine),
    ] {
        let what = format!("{} + {}", surface.name(), displace.name());
        for (list, scale, g) in [(every(&recs, 3), r, 24), (random.clone(), 2.0, 16)] {
            let case = Case {
                surface,
                field: NormalField::default(),
                displace,
                params: SurfaceParams::for_radius(scale),
                inputs: Sources::default(),
            };
            let lod = case.lod();
            let mut tight = f32::INFINITY;
            for (ix, rec) in list.iter().enumerate() {
                let b = lod.element(rec);
                let (truth, big) = sampled_mixed(&case, rec, g);
                let slack = 16.0 * f32::EPSILON * big * (g * g) as f32;
                let half = 0.5 * b.second.iter().sum::<f32>();
                for (k, (&t, &bk)) in truth.iter().zip(&b.mixed).enumerate() {
                    assert!(
                        t <= bk + slack,
                        "{what}: element {ix} pair {k}: sampled {t} above the bound {bk}"
                    );
                    assert!(bk <= half, "{what}: {bk} above Σ/2 {half}");
                    if surface == Surface::Phong && displace == Displace::None {
                        let exact = (t - bk).abs() <= 1e-3 * bk + slack;
                        assert!(exact, "phong: element {ix} pair {k}: {t} vs {bk}");
                    }
                    if t > 20.0 * slack {
                        tight = tight.min(bk / t);
                    }
                }
            }
            ratios.push((what.clone(), tight));
        }
    }
    eprintln!("mixed bound / sampled, tightest element: {ratios:?}");
}

/// The moving direction's second derivative: `|N''| <= |n''|/ρ + 2|n'|²/ρ²` for `N = n/|n|`
/// (`bound::moved_second` with a unit height and no height derivatives) against `N''` by
/// finite differences (in f64) of random quadratic `n`, at random points: never above, and
/// within 2% of it somewhere (half of either term would be caught).
#[test]
fn unit_direction_bound_is_tight() {
    let mut s = 3u64;
    let mut rnd = move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let mut tightest = 0.0f64;
    for _ in 0..20000 {
        let c: [[f64; 3]; 3] = std::array::from_fn(|k| {
            let scale = 0.1 + 3.0 * (rnd() + 1.0) / 2.0 / (k + 1) as f64;
            std::array::from_fn(|_| rnd() * scale)
        });
        let n =
            |t: f64| std::array::from_fn::<f64, 3, _>(|i| c[0][i] + c[1][i] * t + c[2][i] * t * t);
        let len = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let unit = |t: f64| {
            let v = n(t);
            v.map(|x| x / len(v))
        };
        let t = rnd();
        let (r, n1, n2) = (
            len(n(t)),
            len(std::array::from_fn(|i| c[1][i] + 2.0 * c[2][i] * t)),
            len(c[2].map(|x| 2.0 * x)),
        );
        if r < 0.05 || n1 / r > 20.0 {
            continue;
        }
        let h = 1e-4;
        let (a, b, m) = (unit(t + h), unit(t - h), unit(t));
        let second = len(std::array::from_fn(|i| {
            (a[i] + b[i] - 2.0 * m[i]) / (h * h)
        }));
        let bound = crate::lod::bound::moved_second(0.0, 0.0, 1.0, n1 as f32, n2 as f32, r as f32);
        assert!(
            second <= bound as f64 * (1.0 + 1e-4) + 1e-3,
            "|N''| {second} above {bound} (|n| {r}, |n'| {n1}, |n''| {n2})"
        );
        tightest = tightest.max(second / bound as f64);
    }
    assert!(
        tightest > 0.98,
        "the bound is at least {}x |N''|",
        1.0 / tightest
    );
}
