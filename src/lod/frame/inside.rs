//! An element's own chord error as its driver draws its inside, the lattice's or the
//! tessellator's rings', and the level it needs (the proofs are in src/lod/mod.rs, "A lattice
//! triangle", "A polynomial patch" and "The tessellator's inside").

use super::{level_at, tolerance, LodRecord, LodView, HUGE};
use crate::lod::bound::second_along;
use crate::lod::Chord;
use crate::lod::{ELEMENT_FACTOR, QUADRATIC_FACTOR, RING_DIAGONAL, TESS_CUBIC};

/// Element `r`'s own chord bound `(c1, c2)` as `v`'s driver draws its inside: the lattice
/// triangles' (`LodRecord::chord`) for the pattern and static drivers; for the tessellator,
/// whose rings' triangles have sides `(2/3)(d_a − d_b)/N` besides the lattice's
/// ([`RING_DIAGONAL`]), `c2` takes the largest of those sides' second-derivative bounds
/// where it exceeds the directions' own, and the height map's kink terms count at those sides'
/// texel extent (up to 4/3 of a lattice side's in each family of texel lines). Mirror:
/// `own_chord` in glsl/lod/levels.comp.
pub fn own_chord(v: &LodView, r: &LodRecord) -> [f32; 2] {
    let [c1, c2] = [r.chord[0], r.chord[1]];
    if !v.rounding().tessellator() || c1 >= HUGE || c2 >= HUGE {
        return [c1, c2];
    }
    let mx = largest_second(r);
    if mx >= HUGE {
        return [c1, c2];
    }
    let ring = ring_second(r);
    // The kink terms (`chord[2..]`, per unit segment) at the diagonals' texel extent, 4/3 of a
    // lattice side's: `c1` takes a third more of `k1`, `c2` 7/9 more of `k2`.
    let (k1, k2) = (r.chord[2], r.chord[3]);
    [
        c1 + k1 / 3.0,
        c2 + ELEMENT_FACTOR * (ring - mx).max(0.0) + (7.0 / 9.0) * k2,
    ]
}

/// The largest of element `r`'s directional bounds `M_k`.
fn largest_second(r: &LodRecord) -> f32 {
    r.second[0].max(r.second[1]).max(r.second[2])
}

/// The largest second-derivative bound of the tessellator's ring diagonals
/// `(2/3)(d_a − d_b)` ([`RING_DIAGONAL`]) on element `r`.
fn ring_second(r: &LodRecord) -> f32 {
    let m = [r.second[0], r.second[1], r.second[2]];
    let b = [r.mixed[0], r.mixed[1], r.mixed[2]];
    RING_SIDES
        .iter()
        .map(|&e| second_along(m, b, e))
        .fold(0.0f32, f32::max)
        * RING_DIAGONAL
}

/// The continuous level element `r`'s inside needs as `v`'s driver draws it: that of
/// [`own_chord`], or, for a polynomial patch (a finite cubic term in `second[3]`), the smaller
/// level of its tighter bound `Q / N² + T / N³`, with `Q = max_k M_k / 6` and `T` the cubic
/// term (for the tessellator `Q = max(max_k M_k, R) / 6` over its ring diagonals too and `T`
/// times [`TESS_CUBIC`]): the level `N1` of `Q + T / N0`, `N0` the level of `Q` alone, or of
/// `Q + 2T / N0` where the driver glides (`glide_factor`; proof in src/lod/mod.rs, "A
/// polynomial patch"). Mirror: `own_level_above` in glsl/lod/levels.comp (with the largest
/// of the element's edges' levels).
pub fn own_level(v: &LodView, r: &LodRecord) -> f32 {
    own_level_above(v, r, 0.0)
}

/// The larger of `floor` and [`own_level`], the polynomial patch's level not computed where
/// the general bound's is at most `floor` (it cannot matter there): what the level pass takes
/// with the largest of the element's edges' levels. Mirror: `own_level_above` in
/// glsl/lod/levels.comp.
pub fn own_level_above(v: &LodView, r: &LodRecord, floor: f32) -> f32 {
    let tol = tolerance(v, r.sphere);
    let general = level_at(v, own_chord(v, r), tol);
    if general <= floor {
        return floor;
    }
    let Some([q, t]) = polynomial(v, r) else {
        return general;
    };
    let n0 = level_at(v, [0.0, q], tol);
    let n1 = level_at(v, [0.0, q + glide_factor(v) * t / n0], tol);
    floor.max(general.min(n1))
}

/// How many times `T / N0` a polynomial patch's level takes beside its quadratic term: 1, the
/// bound at the level itself; 2 where the driver glides (dyadic levels), so that the bound also
/// holds, in the form `c2 / N²` geomorphing's factor assumes, at half the level, which a gliding
/// element blends from (src/lod/mod.rs, "A polynomial patch"). Mirror: in `own_level_above`
/// and `edge_need_level`, glsl/lod/levels.comp.
pub(super) fn glide_factor(v: &LodView) -> f32 {
    if v.dyadic() {
        2.0
    } else {
        1.0
    }
}

/// A polynomial patch's `(Q, T)` as `v`'s driver draws its inside ([`own_level`]); `None`
/// where it has none.
fn polynomial(v: &LodView, r: &LodRecord) -> Option<[f32; 2]> {
    let (mx, t) = (largest_second(r), r.second[3]);
    if t >= HUGE || mx >= HUGE {
        return None;
    }
    let (q, t) = if v.rounding().tessellator() {
        (mx.max(ring_second(r)), t * TESS_CUBIC)
    } else {
        (mx, t)
    };
    Some([QUADRATIC_FACTOR * q, t])
}

/// The chord error bound of element `r`'s inside at level `n` as `v`'s driver draws it, what
/// [`own_level`] meets: the smaller of [`own_chord`]'s and the polynomial patch's.
pub fn own_error(v: &LodView, r: &LodRecord, n: f32) -> f32 {
    let [c1, c2] = own_chord(v, r);
    let general = Chord { c1, c2 }.error(n);
    match polynomial(v, r) {
        Some([q, t]) => general.min((q + t / n) / (n * n)),
        None => general,
    }
}

/// The tessellator's ring diagonals `d_a − d_b` as `(du, dv)`, before [`RING_DIAGONAL`]'s
/// scale: `d0 − d2`, `d0 − d1`, `d1 − d2`.
const RING_SIDES: [[f32; 2]; 3] = [[1.0, 1.0], [2.0, -1.0], [-1.0, 2.0]];
