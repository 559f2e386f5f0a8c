//! The per-frame levels against the bounds they come from: shared edges, monotony, caps,
//! culling. The pixel error they promise is checked end to end in src/lod/tests/view.rs.

use super::*;
use crate::lod::levels::drawn_level;
use crate::lod::ELEMENT_FACTOR;
use crate::mesh::test_support::load_model;
use crate::surface::{build_records, Displace, RecordKind, Seams, Sources, Surface, SurfaceParams};
use glam::Mat4;

pub(super) fn spot() -> (crate::mesh::Mesh, Vec<ElementRecord>) {
    let (mesh, _) = load_model("spot_control_tri.obj");
    let recs = build_records(RecordKind::Corners, &mesh, Seams::Closed);
    (mesh, recs)
}

pub(super) fn view_at(eye: Vec3, max: u32) -> View {
    View::new(eye, 0.8, 720, 1.0, max)
}

/// Farther away no edge needs more, every level is within [1, max] and drawn levels respect
/// the cap; the inner level is at least every edge's; a far camera draws no more triangles.
#[test]
fn levels_fall_with_distance_and_respect_the_cap() {
    let (mesh, recs) = spot();
    let r = mesh.bounding_radius();
    let params = SurfaceParams::for_radius(r);
    let inputs = Sources::default();
    let lod = Lod::of(Surface::Pn, Displace::Noise, &params, &inputs);
    let lr = lod_records(&lod, &recs);
    let (lo, hi) = mesh.bounds();
    let centre = (lo + hi) * 0.5;
    for rounding in Rounding::ALL {
        let dyadic = rounding.dyadic();
        let view = |d: f32, max: u32| {
            let v = view_at(centre + Vec3::new(0.3, 0.2, 1.0).normalize() * d, max);
            LodView::new(&v, None, false, rounding, 0)
        };
        let at = |d: f32, max: u32| frame_levels(&view(d, max), &lr);
        // The levels before the lift (which follows the neighbours' levels, not the distance
        // alone: src/lod/frame/lift.rs): the same where the view does not lift.
        let first = |d: f32| -> Vec<ElementLevels> {
            let v = view(d, 64);
            lr.iter().map(|r| element_levels(&v, r)).collect()
        };
        let mut last: Option<(Vec<ElementLevels>, Vec<ElementLevels>)> = None;
        for d in [1.5 * r, 3.0 * r, 6.0 * r, 12.0 * r] {
            let (now, before) = (at(d, 64), first(d));
            for (l, b) in now.iter().zip(&before) {
                assert!(l.inner >= 1.0 && l.inner <= 64.0);
                for (e, f) in l.edges.into_iter().zip(b.edges) {
                    assert!((1.0..=64.0).contains(&e));
                    assert!(l.inner >= e);
                    assert!(e >= f);
                }
            }
            if let Some((prev, prev_before)) = &last {
                for (p, n) in prev_before.iter().zip(&before) {
                    for e in 0..3 {
                        assert!(n.edges[e] <= p.edges[e]);
                    }
                }
                let tris = |v: &[ElementLevels]| -> u64 {
                    let h = LevelStats::new(v, dyadic, 64).histogram;
                    h.iter().map(|(&n, &k)| k * n as u64 * n as u64).sum()
                };
                assert!(tris(&now) <= tris(prev), "at {d}");
            }
            last = Some((now, before));
        }
        // A cap of 4: nothing drawn finer, and the close camera hits it.
        let capped = at(1.5 * r, 4);
        let stats = LevelStats::new(&capped, dyadic, 4);
        assert!(stats.histogram.keys().all(|&n| n <= 4));
        assert!(stats.histogram.get(&4).copied().unwrap_or(0) > 10);
        assert_eq!(
            stats.histogram.values().sum::<u64>() + stats.culled,
            recs.len() as u64
        );
    }
}

/// Frustum culling drops the elements whose sphere is outside (those, and only those, of
/// `Frustum::outside`); back-face culling the elements whose cone faces away
/// (`NormalCone::back_facing`); culled elements have inner level 0.
#[test]
fn culling_follows_the_spheres_and_cones() {
    let (mesh, recs) = spot();
    let r = mesh.bounding_radius();
    let params = SurfaceParams::for_radius(r);
    let inputs = Sources::default();
    let lod = Lod::of(Surface::Pn, Displace::None, &params, &inputs);
    let lr = lod_records(&lod, &recs);
    let (lo, hi) = mesh.bounds();
    let centre = (lo + hi) * 0.5;
    let eye = centre + Vec3::new(0.4, 0.25, 1.0).normalize() * (1.6 * r);
    let target = centre + Vec3::new(0.7 * r, 0.2 * r, 0.0);
    let mut proj = Mat4::perspective_rh(0.9, 16.0 / 9.0, 0.01 * r, 10.0 * r);
    proj.y_axis.y = -proj.y_axis.y;
    let frustum = Frustum::from_view_proj(proj * Mat4::look_at_rh(eye, target, Vec3::Y));
    let view = view_at(eye, 64);
    let count = lr.len() as u32;
    let none = frame_levels(
        &LodView::new(&view, None, false, Rounding::Snapped, count),
        &lr,
    );
    assert!(none.iter().all(|l| !l.culled()));
    let f = frame_levels(
        &LodView::new(&view, Some(&frustum), false, Rounding::Snapped, count),
        &lr,
    );
    let fb = frame_levels(
        &LodView::new(&view, Some(&frustum), true, Rounding::Snapped, count),
        &lr,
    );
    let (mut out, mut back) = (0, 0);
    for (i, rec) in recs.iter().enumerate() {
        let b = lod.element(rec);
        let o = frustum.outside(&b.sphere);
        let away = b.cone.is_some_and(|c| c.back_facing(&b.sphere, eye));
        assert_eq!(f[i].culled(), o, "element {i}");
        assert_eq!(fb[i].culled(), o || away, "element {i}");
        if !o {
            assert_eq!(f[i], none[i]);
        }
        out += o as usize;
        back += (away && !o) as usize;
    }
    assert!(out > 10 && back > 10, "{out} outside, {back} back-facing");
    // The culled that face away, inside the view, are told apart (what `--cull off` draws).
    let lv = LodView::new(&view, Some(&frustum), true, Rounding::Snapped, count);
    assert_eq!(culled_facing_away(&lv, &lr, &fb), back as u64);
    let lv = LodView::new(&view, Some(&frustum), false, Rounding::Snapped, count);
    assert_eq!(culled_facing_away(&lv, &lr, &f), 0);
}

/// The levels are at least `View::levels`' (equal on the edges without their share of the
/// transition triangles), and every coarser edge's transition triangles fit at the drawn inner
/// level: with the edges' share, and with the raise alone where the corners fit.
#[test]
fn inner_levels_cover_own_bound_and_transitions() {
    let (mesh, recs) = spot();
    let r = mesh.bounding_radius();
    let params = SurfaceParams::for_radius(r);
    let inputs = Sources::default();
    let lod = Lod::of(Surface::Pn, Displace::Sine, &params, &inputs);
    let full = lod_records(&lod, &recs);
    // Without the edges' share (step 1), the raise (step 2) alone covers the strips.
    let mut bare = full.clone();
    for b in &mut bare {
        for e in &mut b.edges {
            e.needs = [[0.0; 4]; 4];
        }
    }
    let view = view_at(Vec3::new(0.2, 0.3, 2.0 * r), 1 << 12);
    let (mut raised, mut checked) = (0, 0);
    for (rounding, lr) in Rounding::ALL
        .into_iter()
        .flat_map(|k| [(k, &full), (k, &bare)])
    {
        let (step1, dyadic) = (std::ptr::eq(lr, &full), rounding.dyadic());
        let lv = LodView::new(&view, None, false, rounding, 0);
        for (rec, (l, x)) in recs.iter().zip(frame_levels(&lv, lr).iter().zip(lr)) {
            let b = lod.element(rec);
            let edges = [0, 1, 2].map(|e| lod.edge(rec, e));
            let (own_edges, own_inner) = view.levels(&b, &edges);
            // Before the lift, without step 1, an edge's level is its curve's.
            let before = element_levels(&lv, x).edges;
            for ((mine, own), first) in l.edges.iter().zip(own_edges).zip(before) {
                assert!(*mine >= first && first >= own);
                if !step1 {
                    assert_eq!(first, own);
                }
            }
            assert!(l.inner >= own_inner);
            let n = drawn_level(l.inner, dyadic, lv.max_level);
            if l.inner == n as f32 && l.inner > l.edges.iter().fold(own_inner, |a, &e| a.max(e)) {
                raised += 1;
            }
            // Every coarser edge's transition triangles fit at the drawn inner level.
            let tol = view.tolerance(&b.sphere);
            for e in 0..3 {
                let ne = drawn_level(l.edges[e], dyadic, lv.max_level);
                if ne < n {
                    let (a, beta) = (1.0 / ne as f32, 1.0 / n as f32);
                    let (m, bm) = (x.second, x.mixed);
                    let twist = 2.0 * bm[e].max(bm[(e + 2) % 3]);
                    let mb = m[(e + 1) % 3].max(m[(e + 2) % 3]);
                    let base = a * a * m[e];
                    // Moves of up to a sample, or half of one where snapped; beside the
                    // tessellator's first ring a third of a row further (transitions.rs).
                    let s = if rounding == Rounding::TessSnapped {
                        let c = a / 2.0 + 2.0 * beta / 3.0;
                        c * c * m[e] + c * (2.0 * beta / 3.0) * twist + 4.0 / 9.0 * beta * beta * mb
                    } else {
                        let h = if rounding.snapped() { 0.5 } else { 1.0 };
                        h * h * a * a * m[e] + h * a * beta * twist + beta * beta * mb
                    }
                    .max(base);
                    // The corners fit: `M_c <= 1.25 max_k M_k` whatever `B_k` (`2 B_k <= Σ`);
                    // snapped at powers of two, there are none, and the bases fit.
                    let corner = match rounding {
                        Rounding::Snapped | Rounding::TessSnapped => base,
                        _ => 1.25 * a * a * m[0].max(m[1]).max(m[2]),
                    };
                    if step1 || ELEMENT_FACTOR * corner <= tol {
                        assert!(ELEMENT_FACTOR * s <= tol * 1.0001, "{s} vs {tol}");
                        checked += 1;
                    }
                }
            }
        }
    }
    assert!(
        checked > 50 && raised > 50,
        "{checked} transitions, {raised} raised"
    );
    eprintln!("{checked} transitions, {raised} inner levels raised");
}

/// The height map's bounds read each element's own texture coordinates.
#[test]
fn height_map_bounds_read_each_element_s_coordinates() {
    let (mesh, _) = load_model("grid_uv_8x8.obj");
    let data = crate::render::MeshData::new(mesh, RecordKind::Corners, Seams::Closed);
    let uvs = data
        .uvs
        .as_deref()
        .expect("the grid has texture coordinates");
    let map = crate::surface::Heightmap::generated();
    let params = SurfaceParams::for_radius(data.mesh.bounding_radius());
    let inputs = Sources {
        uvs: Some(uvs),
        heightmap: Some(&map),
        ..Default::default()
    };
    let lod = Lod::of(Surface::Pn, Displace::Heightmap, &params, &inputs);
    let lr = lod_records(&lod, &data.records);
    let mut differ = 0;
    for (i, rec) in data.records.iter().enumerate() {
        let own = Lod::of(
            Surface::Pn,
            Displace::Heightmap,
            &params,
            &Sources {
                uvs: Some(std::slice::from_ref(&uvs[i])),
                ..inputs
            },
        )
        .element(rec);
        assert_eq!(lr[i].chord[..2], chord2(own.chord), "element {i}");
        assert!(own.chord.c1 > 0.0, "element {i}: no kink term");
        differ += (lr[i].chord != lr[0].chord) as usize;
    }
    assert!(differ > 0);
}

/// The bounds computed on every core are those of one thread, in order, whatever the chunks;
/// the progress heard ends at every element and edge bounded.
#[test]
fn bounds_on_every_core_are_those_of_one_thread() {
    let mut heard = Vec::new();
    let squares = on_every_core(1000, |i| i * i, &mut |d| heard.push(d));
    assert_eq!(squares, (0..1000).map(|i| i * i).collect::<Vec<_>>());
    assert_eq!(heard.last(), Some(&1000));
    assert!(heard.windows(2).all(|w| w[0] <= w[1]), "{heard:?}");
    let (mesh, recs) = spot();
    let params = SurfaceParams::for_radius(mesh.bounding_radius());
    let inputs = Sources::default();
    let lod = Lod::of(Surface::Pn, Displace::Sine, &params, &inputs);
    let mut last = None;
    let lr = lod_records_reporting(&lod, &recs, |p| last = Some(p));
    // 372 elements, 558 edges.
    assert_eq!(last, Some(Progress::Bounds(930, 930)));
    // Elements one at a time, on this thread.
    for i in (0..recs.len()).step_by(7) {
        let (a, b) = (&lr[i], &lod_records(&lod.for_element(i), &recs[i..=i])[0]);
        assert_eq!(a.sphere, b.sphere);
        assert_eq!(a.chord, b.chord);
        assert_eq!(a.second, b.second);
    }
}

/// Pixel errors up to f32's largest give level 1 everywhere, for every rounding, with or
/// without displacement: the solvers' `c2 · tol` and `4 p d` overflow there, and used to give
/// NaN (a finer level than at a smaller pixel error, and another on the GPU).
#[test]
fn huge_pixel_errors_draw_level_one() {
    let (mesh, recs) = spot();
    let r = mesh.bounding_radius();
    let params = SurfaceParams::for_radius(r);
    for displace in [Displace::None, Displace::Sine] {
        let lod = Lod::of(Surface::Pn, displace, &params, &Sources::default());
        let lr = lod_records(&lod, &recs);
        for pixel_error in [1e30, 1e38, 2e38, f32::MAX] {
            for rounding in Rounding::ALL {
                let eye = Vec3::new(0.3, 0.4, 2.5 * r);
                let view = View::new(eye, 0.8, 720, pixel_error, 64);
                let view = LodView::new(&view, None, false, rounding, lr.len() as u32);
                for (i, l) in frame_levels(&view, &lr).iter().enumerate() {
                    assert!(
                        l.inner == 1.0 && l.edges == [1.0; 3],
                        "{} at {pixel_error} px, {rounding:?}: element {i} at {l:?}",
                        displace.name()
                    );
                }
            }
        }
    }
    // The shortcut agrees with the formula where both apply.
    let chord = Chord { c1: 0.3, c2: 0.7 };
    for tol in [1.0001f32, 1.001, 2.0, 1e9] {
        let root = (chord.c1 + (chord.c1 * chord.c1 + 4.0 * chord.c2 * tol).sqrt()) / (2.0 * tol);
        assert_eq!((root * (1.0 + 1.0 / 65536.0)).max(1.0), 1.0, "{tol}");
        assert_eq!(chord.level_for(tol), 1.0, "{tol}");
    }
}

/// A quadratic surface `P(x) = Q(x)/2`, one symmetric form `[xx, xy, yy]` per coordinate,
/// `x = (u, v)`: its second derivative is the constant form, so its bounds are exact.
type Forms = [[f32; 3]; 3];

/// The lattice directions `d0`, `d1`, `d2` in `(u, v)`.
const DIRS: [[f32; 2]; 3] = [[1.0, 0.0], [-1.0, 1.0], [0.0, -1.0]];

/// `Q(a, b)`, one value per coordinate.
fn form(f: &Forms, a: [f32; 2], b: [f32; 2]) -> Vec3 {
    Vec3::from(
        f.map(|[xx, xy, yy]| {
            a[0] * b[0] * xx + (a[0] * b[1] + a[1] * b[0]) * xy + a[1] * b[1] * yy
        }),
    )
}

/// `forms` followed by `n` random ones (xorshift from `seed`, entries in `[-1, 1]`).
fn with_random_forms(mut forms: Vec<Forms>, seed: u32, n: usize) -> Vec<Forms> {
    let mut seed = seed;
    let mut rand = || {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        seed as f32 / u32::MAX as f32 * 2.0 - 1.0
    };
    forms.extend((0..n).map(|_| [(); 3].map(|_| [rand(), rand(), rand()])));
    forms
}

/// The level pass's record of quadratic `f`, its exact bounds: `M_k = |Q(d_k)|`,
/// `B_k = |Q(d_k, d_{k+1})|`, the lattice's chord `9/40 max_k M_k`, no kinks.
fn form_record(f: &Forms) -> LodRecord {
    let m = DIRS.map(|d| form(f, d, d).length());
    let b = [0, 1, 2].map(|k| form(f, DIRS[k], DIRS[(k + 1) % 3]).length());
    let mut rec = LodRecord::zeroed();
    rec.chord = [0.0, ELEMENT_FACTOR * m[0].max(m[1]).max(m[2]), 0.0, 0.0];
    rec.second = [m[0], m[1], m[2], 0.0];
    rec.mixed = [b[0], b[1], b[2], 0.0];
    rec
}

/// `own_chord`'s `c2` for record `rec` as a driver rounding as `rounding` draws it.
fn own_c2(rec: &LodRecord, rounding: Rounding) -> f32 {
    let view = View::new(Vec3::ZERO, 0.8, 720, 1.0, 64);
    own_chord(&LodView::new(&view, None, false, rounding, 1), rec)[1]
}

/// The largest distance between quadratic `f` and its linear interpolation over the triangle
/// with corners `x` (`(u, v)`), sampled at `s` steps a side.
fn sampled_error(f: &Forms, x: [[f32; 2]; 3], s: u32) -> f32 {
    let p = |x: [f32; 2]| 0.5 * form(f, x, x);
    let mut worst = 0.0f32;
    for a in 0..=s {
        for c in 0..=s - a {
            let w = [(s - a - c) as f32, a as f32, c as f32].map(|w| w / s as f32);
            let y = [0, 1].map(|k| w[0] * x[0][k] + w[1] * x[1][k] + w[2] * x[2][k]);
            let lin = p(x[0]) * w[0] + p(x[1]) * w[1] + p(x[2]) * w[2];
            worst = worst.max((p(y) - lin).length());
        }
    }
    worst
}

/// The tess driver's own chord (`own_chord`: the ring diagonals) bounds every triangle the
/// tessellator may draw, sampled densely on quadratic surfaces, and is needed: on a saddle the
/// lattice's bound alone is exceeded by the tessellator's diagonals. The patterns' own chord
/// stays the lattice's.
#[test]
fn tessellator_rings_meet_their_own_chord() {
    // The saddle: Q(d0) = Q(d2) = 1, Q(d1) = −1 in one coordinate.
    let forms = with_random_forms(vec![[[1.0, 1.5, 1.0], [0.0; 3], [0.0; 3]]], 0x2545_f491, 40);
    for (i, f) in forms.iter().enumerate() {
        let rec = form_record(f);
        let lattice = own_c2(&rec, Rounding::Snapped);
        assert_eq!(lattice, rec.chord[1]);
        assert_eq!(own_c2(&rec, Rounding::SnappedInteger), lattice);
        let tess = own_c2(&rec, Rounding::TessSnapped);
        assert_eq!(own_c2(&rec, Rounding::Integer), tess);
        for n in [5, 6, 8] {
            let mut worst = 0.0f32;
            for diagonal in [false, true] {
                let tris = crate::render::tess::ring_triangles(n, diagonal);
                assert_eq!(
                    tris.len() as u32,
                    crate::render::tess::tess_triangle_count(n)
                );
                for t in tris {
                    let x = t.map(|k| [k[1] as f32 / (3 * n) as f32, k[2] as f32 / (3 * n) as f32]);
                    worst = worst.max(sampled_error(f, x, 24));
                }
            }
            let n2 = (n * n) as f32;
            assert!(
                worst <= tess / n2 * (1.0 + 1e-4),
                "form {i}, level {n}: {worst} > {}",
                tess / n2
            );
            if i == 0 {
                // The saddle: the lattice's bound alone does not hold on the tessellator.
                assert!(
                    worst > lattice / n2 * 1.2,
                    "saddle, level {n}: {worst} <= {}",
                    lattice / n2
                );
            }
        }
    }
}

/// The gliding tess driver's transition triangles (`Rounding::TessSnapped`): the tessellator's
/// triangles at level `n` (either diagonal), its outer ring snapped onto coarser edges' samples
/// (`render::tess::morph::snap_ring`, what the evaluation stage does), sampled densely on a
/// saddle and 40 random quadratic surfaces: every triangle within `9/40` of the largest of the
/// element's own `max(M, R) β²` and, for each coarser edge, its bases' `a² M_e` and the sides'
/// `S_e` (`transitions::tess_side_coefficients`), the bound the level pass solves.
#[test]
fn tess_snapped_transitions_meet_their_bound() {
    use crate::render::tess::morph::snap_ring;
    // A saddle, and surfaces flat along two lattice directions but twisted between them,
    // where the transition sides' twist term is all that bounds a long thin triangle.
    let special = [
        [1.0, 1.5, 1.0],
        [0.0, 1.0, 2.0],
        [2.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    let forms = with_random_forms(
        special.map(|q| [q, [0.0; 3], [0.0; 3]]).to_vec(),
        0x9e37_79b9,
        40,
    );
    let mut checked = 0;
    for f in &forms {
        let rec = form_record(f);
        let (m, b) = (rec.second, rec.mixed);
        let own = own_c2(&rec, Rounding::TessSnapped);
        for n in [4u32, 8, 16] {
            for outer in [[n / 2, n, n / 4], [1, n / 2, n], [n / 4, n / 4, n / 2]] {
                let beta = 1.0 / n as f32;
                // The bound: the inside's, then each coarser edge's (patch edge i is stored
                // edge i + 1, direction d_{i+1}).
                let mut bound = own * beta * beta;
                for (i, &ne) in outer.iter().enumerate() {
                    if ne < n {
                        let e = (i + 1) % 3;
                        let a = 1.0 / ne as f32;
                        let twist = 2.0 * b[e].max(b[(e + 2) % 3]);
                        let mb = m[(e + 1) % 3].max(m[(e + 2) % 3]);
                        let [caa, cab, cbb] = transitions::tess_side_coefficients(m[e], twist, mb);
                        let sides = caa * a * a + cab * a * beta + cbb * beta * beta;
                        bound = bound.max(ELEMENT_FACTOR * (a * a * m[e]).max(sides));
                    }
                }
                let mut worst = 0.0f32;
                for diagonal in [false, true] {
                    for t in crate::render::tess::ring_triangles(n, diagonal) {
                        let w =
                            t.map(|k| snap_ring(k.map(|x| x as f32 / (3 * n) as f32), outer, n));
                        worst = worst.max(sampled_error(f, w.map(|w| [w[1], w[2]]), 12));
                    }
                }
                assert!(
                    worst <= bound * (1.0 + 1e-4),
                    "level {n}, edges {outer:?}: {worst} > {bound} ({f:?})"
                );
                checked += 1;
            }
        }
    }
    assert_eq!(checked, forms.len() * 9);
}

/// A polynomial patch's level (`own_level`, from `N0` the quadratic term's level without
/// solving the cubic): for spot's `pn` and `phong` elements seen from near to far, with every
/// rounding, the level meets the bound it comes from (`own_error` within the tolerance, unless
/// capped at the largest level), and so does the blend of the two levels a gliding element
/// draws between; it never exceeds the general bound's level, and is lower on most elements
/// close up; `pn` with displacement has no polynomial bound and keeps the general one.
#[test]
fn polynomial_levels_meet_their_bound() {
    let (mesh, recs) = spot();
    let r = mesh.bounding_radius();
    let params = SurfaceParams::for_radius(r);
    let (mut checked, mut lower, mut glides) = (0, 0, 0);
    for (surface, displace) in [
        (Surface::Pn, Displace::None),
        (Surface::Phong, Displace::None),
        (Surface::Pn, Displace::Sine),
    ] {
        let lod = Lod::of(surface, displace, &params, &Sources::default());
        let lr = lod_records(&lod, &recs);
        let polynomial = displace == Displace::None;
        for rounding in Rounding::ALL {
            for d in [1.05f32, 1.5, 3.0, 12.0, 80.0] {
                let view = view_at(Vec3::new(0.2, 0.3, d * r), 64);
                let v = LodView::new(&view, None, false, rounding, lr.len() as u32);
                for rec in &lr {
                    assert_eq!(rec.second[3] < HUGE, polynomial);
                    let n = own_level(&v, rec);
                    let general = level(&v, own_chord(&v, rec), rec.sphere);
                    assert!((1.0..=general).contains(&n), "{n} vs {general}");
                    let tol = tolerance(&v, rec.sphere);
                    if n < 64.0 {
                        let err = own_error(&v, rec, n);
                        assert!(err <= tol * (1.0 + 1e-4), "{err} above {tol} at level {n}");
                    }
                    // Gliding: the drawn power of two `p` blends from `p/2` with the factor
                    // that assumes a bound `c2/N²` at both (docs/adaptivity.md, "Geomorphing").
                    let p = drawn_level(n, true, 64);
                    if rounding.dyadic() && (2..64).contains(&p) {
                        let m = crate::pattern::adaptive::morph_factor(n, p);
                        let half = own_error(&v, rec, (p / 2) as f32);
                        let blend = (1.0 - m) * half + m * own_error(&v, rec, p as f32);
                        assert!(blend <= tol * (1.0 + 1e-4), "{blend} above {tol} gliding");
                        glides += 1;
                    }
                    if d <= 3.0 && n < general && general < 64.0 {
                        lower += 1;
                    }
                    checked += 1;
                }
            }
        }
    }
    assert_eq!(checked, 3 * 4 * 5 * recs.len());
    assert!(glides > recs.len(), "{glides} gliding elements");
    assert!(
        lower > 2 * 4 * 3 * recs.len() / 2,
        "{lower} of {checked} lower"
    );
}
