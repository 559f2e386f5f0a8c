//! The polynomial patch's bound (src/lod/mod.rs, "A polynomial patch") against dense sampling:
//! lattice triangles and the tessellator's.

use super::*;

/// The polynomial patch's bound (`Bounds::cubic`: `max_k M_k / (6N²) + 4 C̄ / (81 N³)`) on
/// spot's `pn` and `phong` elements: within the truth sampled densely on the lattice (the check
/// of `local_surface_bounds_hold_and_are_useful` uses it), tighter than the general
/// `9/40 · max_k M_k / N²` from level 4 on (about 0.8 of it on the median element), and for
/// Phong's quadratic the quadratic term alone (no cubic term), 20/27 of the general bound. (The
/// samples stay within the quadratic term alone for `pn` too: the cubic term is the proof's, a
/// few percent of the bound from level 8 on.)
#[test]
fn polynomial_patch_bounds_hold_and_are_tighter() {
    let (spot, recs) = corner_records("spot_control_tri_vn.obj");
    let r = spot.bounding_radius();
    for surface in [Surface::Pn, Surface::Phong] {
        let case = Case::plain(surface, Displace::None, SurfaceParams::default());
        let lod = case.lod();
        let (mut gains, mut beyond_quadratic) = (Vec::new(), 0);
        for rec in every(&recs, 3) {
            let b = lod.element(&rec);
            assert!(b.cubic.is_finite(), "{}: {b:?}", surface.name());
            if surface == Surface::Phong {
                assert_eq!(b.cubic, 0.0);
            }
            let mx = b.second.iter().fold(0.0f32, |a, &x| a.max(x));
            for n in [1u32, 2, 3, 4, 8] {
                let (inner, _) = case.true_error(&rec, n);
                let nf = n as f32;
                let bound = b.element_error(nf);
                assert!(
                    inner <= bound + 64.0 * f32::EPSILON * r,
                    "{}: level {n}: {inner} above {bound} ({b:?})",
                    surface.name()
                );
                if inner > mx / 6.0 / (nf * nf) * (1.0 + 1e-3) + 64.0 * f32::EPSILON * r {
                    beyond_quadratic += 1;
                }
                if n >= 4 {
                    gains.push(bound / b.chord.error(nf));
                }
            }
        }
        gains.sort_by(f32::total_cmp);
        let median = gains[gains.len() / 2];
        eprintln!(
            "{}: the polynomial bound is {median} of the general one (median, levels 4 and 8); \
             {beyond_quadratic} samples beyond the quadratic term alone",
            surface.name()
        );
        if surface == Surface::Phong {
            assert!((median - 20.0 / 27.0).abs() < 1e-3, "{median}");
            assert_eq!(beyond_quadratic, 0);
        } else {
            assert!(median < 0.85, "{median}");
        }
    }
}

/// The tessellator's triangles at integer levels (either diagonal) on spot's `pn` elements,
/// sampled densely: within the inside bound the level pass meets for the tess driver
/// (`lod::frame::own_error`: the polynomial patch's, with the ring diagonals' `R` and `(4/3)³`
/// times the cubic term, where it is below the general one), which is below the general bound
/// somewhere.
#[test]
fn polynomial_patch_bounds_hold_on_the_tessellators_triangles() {
    use crate::lod::frame::{lod_records, own_chord, own_error, LodView, Rounding};
    let (spot, recs) = corner_records("spot_control_tri_vn.obj");
    let r = spot.bounding_radius();
    let case = Case::plain(Surface::Pn, Displace::None, SurfaceParams::default());
    let records = lod_records(&case.lod(), &recs);
    let view = crate::lod::View::new(Vec3::ZERO, 0.8, 720, 1.0, 64);
    let tess = LodView::new(&view, None, false, Rounding::Integer, 1);
    let (mut checked, mut tighter) = (0, 0);
    for (rec, lr) in recs.iter().zip(&records).step_by(6) {
        for n in [2u32, 3, 4, 6] {
            let nf = n as f32;
            let bound = own_error(&tess, lr, nf);
            let [c1, c2] = own_chord(&tess, lr);
            if bound < (crate::lod::Chord { c1, c2 }).error(nf) {
                tighter += 1;
            }
            let mut worst = 0.0f32;
            for diagonal in [false, true] {
                for t in crate::render::tess::ring_triangles(n, diagonal) {
                    let b = t.map(|k| k.map(|x| x as f32 / (3 * n) as f32));
                    worst = worst.max(case.triangle_error(rec, b));
                }
            }
            assert!(
                worst <= bound + 64.0 * f32::EPSILON * r,
                "level {n}: {worst} above {bound}"
            );
            checked += 1;
        }
    }
    assert!(
        checked > 200 && tighter > checked / 2,
        "{checked} {tighter}"
    );
}
