//! The transition triangles along an edge drawn coarser than its element's inside: what an
//! edge's level and an element's inner level need so that they too meet the pixel error.
//!
//! # The proof
//! A driver draws an element at inner level `n` (`β = 1/n`) with the vertices of its boundary
//! on the edges' own samples: a vertex on edge `e` at lattice parameter `k/n` moves to a sample
//! of the edge's level `n_e <= n` (`a_e = 1/n_e`). When `n_e = n` nothing moves. How far a
//! vertex moves, and where, depends on the driver ([`Rounding`]):
//! - [`Rounding::Integer`] (the tessellator's integer levels, whose transitions are its own):
//!   less than `a_e` (as a floor in the edge's canonical direction would), anywhere;
//! - [`Rounding::Snapped`] (the pattern driver while it glides, dyadic): onto the nearest
//!   sample, a tie toward the nearer corner, so at most `a_e/2`; and as a coarser edge is at
//!   most half the inner level (`β <= a_e/2`), the vertex beside a corner moves onto that
//!   corner whenever it is not also beside the other one (`n >= 4`; at `n = 2` the midpoint of
//!   an edge drawn at level 1 moves onto the edge's first corner, `a_e/2` away);
//! - [`Rounding::SnappedInteger`] (the pattern driver without geomorphing, and the static
//!   baseline): snapped alike, at most `a_e/2`, but at integer levels a coarser edge may be
//!   finer than half the inner level (`a_e/2 < β < a_e`), and then the vertex beside a corner
//!   moves onto the edge's first sample, `a_e` from the corner: corner triangles as for the
//!   tessellator (below).
//!
//! - [`Rounding::TessSnapped`] (the tessellator while it glides): every side drawn at the inner
//!   level, the outer ring's vertices snapped as [`Rounding::Snapped`]'s (at most `a_e/2`,
//!   the vertices beside a corner onto it), joined by the tessellator to its first ring (below).
//!
//! The drawn triangles touching the edge are then of three kinds. Their sides are bounded, in
//! the element's lattice directions `d_k` (src/lod/mod.rs), from its second-derivative bounds
//! `M_k >= sup |D²P[d_k, d_k]|` ([`Bounds::second`]) and its mixed ones `B_k >= sup
//! |D²P[d_k, d_{k+1}]|` ([`Bounds::mixed`]), by expanding the quadratic form `Q = D²P(y)` at
//! any point: `|Q(x u + z v)| <= x² |Q(u)| + z² |Q(v)| + 2|xz| |Q(u, v)|`
//! ([`Bounds::second_along`]). `B_k` is each surface's own bound of the mixed term where it
//! has one (a Bézier net's mixed second differences, src/lod/net.rs `Net::mixed`), and never
//! more than polarization's `Σ/2`, `Σ = M_0 + M_1 + M_2` (as `d_k + d_{k+1} = −d_{k+2}`,
//! `2 Q(d_k, d_{k+1}) = Q(d_{k+2}) − Q(d_k) − Q(d_{k+1})`), which is all a surface without one
//! (`loop`) gets. Note `Q(d_e, d_{e+2}) = Q(d_{e+2}, d_e)`, bounded by `B_{e+2}`. With `h` the
//! largest move over `a_e` (1, or `1/2` snapped):
//! - bases on the edge: `0` or `a_e d_e` (consecutive lattice points, `β` apart, move onto the
//!   same sample or neighbouring ones): `|Q| <= a_e² M_e`;
//! - sides from a moved vertex to the next row: `α d_e + β d_{e+1}` with
//!   `−h a_e <= α <= h a_e + β` (the lattice side's `0` or `β`, less the move); expanded on
//!   `(d_e, d_{e+1})` when `|α| <= h a_e` (cross term `2|α|β B_e`) and on `(d_e, d_{e+2})`
//!   otherwise (`(α − β) d_e − β d_{e+2}`, `|α − β| <= h a_e`, cross term
//!   `2|α − β|β B_{e+2}`): with the twist `T_e = 2 max(B_e, B_{e+2})`,
//!   `|Q| <= S_e = h² a_e² M_e + h a_e β T_e + β² max(M_{e+1}, M_{e+2})`, extent
//!   `<= h a_e + β` ("Extents", below);
//! - at a corner between edges `e` and `f`, where a vertex beside the corner moves away from
//!   it, to at most `a_e` (not [`Rounding::Snapped`]: there the only triangles with vertices
//!   on two edges are the corner's two lattice triangles, whose vertices beside the corner
//!   either stay or move onto it, leaving lattice sides and sides of the second kind; at
//!   `n = 2`, where every vertex is on the boundary, a midpoint moved onto the far corner
//!   leaves a whole edge, a base, and sides of the second kind with `α = a_e`), sides `y d_e + z d_f` with
//!   `0 <= y <= a_e`, `0 <= z <= a_f`: with `m = min(y, z)`, `r = |y − z|`,
//!   `y d_e + z d_f = −m d_g + r d_j` (`g` the third direction, `j` one of `e`, `f`), so
//!   `|Q| <= m² M_g + r² M_j + 2 m r B_x`, `B_x = max_k B_k`, and with
//!   `m + r <= A = max(a_e, a_f)`: `M_x (m + r)² + m r (2 B_x − 2 M_x)`, largest at `m r = 0`
//!   or `m = r = A/2`, so `|Q| <= A² M_c`, `M_c = max(M_x, M_x/2 + B_x/2)`, `M_x = max_k M_k`.
//!
//! - beside the tessellator's first ring ([`Rounding::TessSnapped`]): ring 1 lies `2β/3` deep
//!   (its vertices at weights `K/(3n)`, src/lod/mod.rs, "The tessellator's inside"), and a side
//!   from the outer ring (`n` segments) to it is `α d_e + (2β/3) d_{e+1}` with `α` between
//!   `−2β/3` and `4β/3` before the move (the strip's parallelograms and corners: the only
//!   sides `tests/tess_rings.rs` finds on the device), `α − δ` after a move `|δ| <= a_e/2`:
//!   expanded on `(d_e, d_{e+1})` for `α <= 2β/3` and on `(d_e, d_{e+2})` beyond, the
//!   coefficient of `d_e` is at most `a_e/2 + 2β/3` either way, so
//!   `|Q| <= (a_e/2 + 2β/3)² M_e + (a_e/2 + 2β/3)(2β/3) T_e + (4/9) β² max(M_{e+1}, M_{e+2})`
//!   (`tess_side_coefficients`), texel extent `<= a_e/2 + 2β <= a_e + β` (`β <= a_e/2`). The
//!   ring's corners, where snapping merged the corner's neighbours into it, leave ring
//!   diagonals (the element's own chord, [`super::own_chord`]) and sides of this kind.
//!
//! With `B_k = Σ/2` these are the bounds written with `Σ` alone; a surface's own mixed bound
//! makes them smaller wherever its twist across the edge is smaller than polarization allows
//! (on a nearly spherical patch of an equilateral element, `|Q(d_e, d_{e+1})|` is about a third
//! of `Σ/2`).
//!
//! # Extents
//! The kink terms (the height map's texel lines, src/lod/mod.rs) and a polynomial patch's cubic
//! term (below) grow with how far a triangle's sides reach: a side `δ` counts at its extent in
//! lattice coordinates, `|δ| = min Σ |c_k|` over the ways of writing `δ = Σ c_k d_k` (as
//! `d_0 + d_1 + d_2 = 0` there are many): the texel lines a side crosses, per family, are at
//! most `s Σ |c_k|` (`s` as in src/lod/mod.rs), and `|D³P[δ, δ, δ]| <= C̄ (Σ |c_k|)³` (`C̄`
//! bounds `D³P` on any three lattice directions), for every such sum, by the triangle
//! inequality and multilinearity. A lattice side has extent
//! `β`, a base `a_e`. A side `α d_e + β d_{e+1}` written so has `|α| + β`, and written as
//! `(α − β) d_e − β d_{e+2}` has `|α − β| + β`: over `−h a_e <= α <= h a_e + β` the smaller is
//! at most `h a_e + β` (`α <= 0` the first, `α >= β` the second; between them the smallest sum,
//! over every way of writing it, is `β`). A corner triangle's sides
//! `y d_e + z d_f = −m d_g + r d_j` have `m + r <= max(a_e, a_f)`. So the triangles along a
//! coarser edge `e` reach at most `max(a_e, h a_e + β)`: where the lattice's boundary is snapped
//! (`h = 1/2`, [`Rounding::Snapped`] and [`Rounding::SnappedInteger`]) `max(a_e, a_e/2 + β)`,
//! which is `a_e` at `β <= a_e/2`; else (`h = 1`) `a_e + β`. Beside the tessellator's first
//! ring the sides are not the lattice's, and they take `a_e + β` (above).
//!
//! A triangle with vertices moved from two coarser edges `e` and `f` (a corner's, at integer
//! levels) reaches at most the coarser edge's `a` (`A = max(a_e, a_f)`: the corner triangle's
//! sides by `m + r <= A`, and the side from its vertex beside the corner to the next row, that
//! vertex moved `a_e − β < β` along its edge, at most `a_e`), which can pass the finer edge's
//! `a_e/2 + β` (inner level 3, edges at 1 and 2: a triangle reaching `2/3` where edge 2's
//! extent is `7/12`). Its bound is then the coarser edge's, which step 1 meets at any inner
//! level: its kink and cubic terms at `A`, and its sides' `|Q|` within the corners' `A² M_c`
//! (where `A > a_e/2 + β`, with `u = a_e/2`: `S_e <= u² M_e + 2uβ B_x + β² mb <= (u + β)² M_c
//! < A² M_c`). At powers of two such triangles stay within both edges' extents.
//!
//! The test `snapped_transition_sides_span_what_their_extent_allows` (src/lod/frame/extent_tests.rs)
//! measures the sides of every triangle the pattern driver draws at integer levels up to 12 and
//! powers of two up to 16, every combination of coarser edges, against these extents (where a
//! triangle has vertices moved from two edges, the coarser edge's `a` at integer levels, both
//! edges' extents at powers of two), and finds them reached.
//!
//! Every drawn triangle's error is then at most `9/40` of its sides' largest `|Q|` plus the kink
//! terms at its sides' extent (the lattice triangle's proof, src/lod/mod.rs, holds for any
//! triangle). Two steps make every one of them meet the element's tolerance `τ`:
//! 1. The edge's level includes, for each of its elements, the level at which the chord
//!    `(x k_1, 9/40 · max(M_c, M_e + λ T_e + λ² max(M_{e+1}, M_{e+2})) + x² k_2)`, with `x a_e`
//!    at least the extent at `β = λ a_e` ([`need_extent`]: `1 + λ`, `1` where the lattice's
//!    boundary is snapped at integer levels, `5/4` for the gliding pattern driver: "Gliding",
//!    below)
//!    (`k` the kink terms; snapped: `max(M_e, M_e/4 + λ/2 T_e + λ² max(M_{e+1}, M_{e+2}))`,
//!    no corners; snapped integer: `max(M_c, M_e/4 + λ/2 T_e + λ² max(M_{e+1}, M_{e+2}))`, as
//!    `M_c >= M_e` covers the bases; beside the tessellator's first ring, `max(M_e, S_e/a_e²)`
//!    with the sides above at `β = λ a_e`, no corners) meets that element's tolerance
//!    ([`strip_need`]). So the
//!    bases and the corners fit in `τ` whatever `n`, and the kink terms at their extent and `S_e`
//!    whenever `β <= λ a_e` (beyond, step 2's quadratics hold both). The dyadic drivers take
//!    `λ = 1/2` (a coarser edge is at most half the inner level, so it rarely needs step 2),
//!    the tessellator's integer levels
//!    `λ = 1` (no raise is needed then; step 2 only serves where a level is capped or a bound
//!    changes between the two), the snapped integer levels `λ = 1/2` too (step 2 raises the
//!    inner level where a coarser edge is finer than half of it and its sides do not fit). On
//!    Spot these choices draw fewer triangles than the others tried (`λ = 1/4`, `λ = 3/4`,
//!    and the other drivers'; for the snapped integer levels, keeping the corners out of the
//!    edge's need and raising the inner level to twice a coarser edge's where they do not fit
//!    drew about a seventh more).
//! 2. The element checks, on the drawn levels ([`LodView::rounding`] says how the driver
//!    rounds and snaps), that `9/40 max(a_e² M_e, S_e) + k_1 E + k_2 E² <= τ`, `E` the extent
//!    (`a_e + β`, or where the lattice's boundary is snapped the larger of `a_e/2 + β` and
//!    `a_e`), for every edge drawn coarser than its inside, and raises its inner level where
//!    not (`S_e` and the kink terms are quadratics in `β`, one for each form of `E`, solved for
//!    it: `strip_level`); raising
//!    it can make another edge coarser than it, so this repeats (at most three times). After
//!    step 1 this is a safety net (rounding at the thresholds); by itself, with step 1's share
//!    dropped, it would still keep the guarantee wherever the bases and corners fit (the tests
//!    run it so, GPU against CPU).
//!
//! Snapping to the nearest sample, a tie toward the nearer corner, is what makes the snapped
//! drivers' transitions cheap: their edges need about the level their elements' insides need
//! along them (`M_e`), where a floor's corners need it across the whole element (`M_c`) and its
//! sides twice the move; and it keeps their sides short ("Extents"). On Spot as `pn` close up
//! at 1 px (the test `pixel_error_holds_end_to_end`) the transitions then cost about a third
//! more triangles than levels that ignore them on the pattern driver, two thirds more beside
//! the tessellator's first ring (whose vertices sit between the lattice's), and 3.7 times as
//! many with the tessellator's own transitions at integer levels.
//!
//! At integer levels, an edge finer than half the inside (`a_e/2 < β < a_e`) is where step 2
//! raises inner levels: the sides' move, up to `a_e/2`, is then as long as a lattice side. No
//! other snapping moves less: the edge fixes its samples, each must be a vertex from both
//! sides, and any monotone map of the `n + 1` lattice points onto the `n_e + 1` samples moves
//! some point about half a sample. Spreading each move over `R` rows (row `r` moving `1 − r/R`
//! of its foot's, only where the edge is finer than half the inside) would bound the sides along
//! the edge by `h = 1 − 1/(2R) − (1 − 1/R) β/a_e` (down to `1/(2R)` at `β = a_e`), but where
//! two edges' rows meet (beside a corner, and on small insides) a vertex moves along both
//! edges, and its sides fall outside both the corners' bound (extent at most `max a_e`) and
//! the strip's (at most `β` across the edge), some triangles even fold over, tapered moves
//! too: spreading needs a bound for a lattice side plus moves along two edges first.
//!
//! On Spot close up as `pn` at integer levels (the benchmark's camera, 0.5 to 4 px), levels
//! that ignore the transitions draw 0.19-0.21x the triangles of the uniform level meeting the
//! bound, step 1 alone 0.25-0.27x, both steps 0.34-0.36x: step 2's raises, at edges finer than
//! half the inside, are most of the cost. Taking `λ` at 5/8, 3/4 or 1 for them (each with its
//! own extent, `a_e/2 + λ a_e`) draws more (0.36-0.38x, 0.37-0.41x, 0.44-0.47x), and `λ` below
//! 1/2 the same (the corners' `M_c`, not the sides, sets those edges). Step 1 without the
//! corners would draw more still (nothing would then bound them, and its edges being coarser,
//! step 2 raises more). Lifting such an edge to the inner level of the element it would raise,
//! where the element across it is already drawn that fine, leaves no transition there: a
//! second pass over the neighbours' levels ([`super::lift`]) draws 0.31-0.33x (with it, `λ`
//! at 5/8 and 3/4 draw 0.32-0.33x and 0.34-0.37x, below 1/2 the same).
//!
//! # Gliding
//! The gliding pattern driver takes step 1's kink and cubic terms at `5/4 a_e`, a quarter past
//! the extent: any `x` at least the extent keeps the bound, and the extent itself would leave
//! its edges coarser than the popping test allows. Where an edge four times coarser than its
//! inside doubles while the inside stays, the vertices of the first row whose parents are
//! snapped onto the edge step along the surface (docs/adaptivity.md, "What remains"); the
//! coarser the edges may stay, the more such steps, and the larger. In the popping sweep
//! (`geomorphing_removes_popping`: at most 0.2 px a frame) the worst step is 0.209 px at
//! `x = 1`, 0.198 at 1.05, 0.186 at 1.1, 0.175 at 1.15 and 0.171 px from 1.25 on (as at 3/2).
//! At integer levels nothing glides, and the extent itself is taken.
//!
//! # Polynomial patches
//! Where the element is a polynomial of degree at most 3 (its cubic term `T` finite,
//! [`Bounds::cubic`]), a triangle of its domain whose sides span at most `H` in lattice
//! coordinates is within `(1/6) · max |Q(side)| + T H³`: the identity of src/lod/mod.rs, "A
//! polynomial patch", holds for any triangle, and there `w_i = Σ_{j≠i} λ_j e_ij` has lattice
//! coordinates summing to at most `(1 − λ_i) H`. So every bound above holds with `9/40`
//! replaced by `1/6` ([`POLYNOMIAL_SHARE`] of it) plus `T H³`, `H` the sides' extent as for the
//! kink terms (which such a patch has none of; "Extents"). Step 1's share, at `β <= λ a_e`,
//! adds `T x³ a_e³` ([`need_extent_cubed`]), turned into a level as the element's own
//! cubic term is (`T x³ / N0` beside the quadratic term, twice that where the driver
//! glides: `super::edge_need_level`); step 2 adds `T E³`, solved to within
//! rounding by Newton's steps (`cubic_level`), as step 1's share, met at `β = λ a_e`, has it
//! met there: a conservative estimate would raise inner levels that need no raise, and
//! gliding levels would jump. Each level is the smaller of the general bound's and this
//! one's.
//!
//! Interior lattice triangles meet `τ` at the element's own level. Where a level is capped at
//! the maximum, or a bound is infinite, nothing is promised (as for the levels themselves).
#![forbid(unsafe_code)]

use super::{tolerance, LodRecord, LodView, Rounding, HUGE};
use crate::lod::levels::drawn_level;
use crate::lod::{Bounds, Chord, ELEMENT_FACTOR, LEVEL_ONE_MARGIN};

/// The chord an edge's level must meet at element `b`'s tolerance for the transition
/// triangles along stored edge `e` (module notes, step 1), for a driver that rounds and snaps
/// as `rounding` says; zero where the element has no finite bound (nothing is promised there).
pub fn strip_need(b: &Bounds, e: usize, rounding: Rounding) -> Chord {
    let (m, mixed) = (b.second, b.mixed);
    let finite = m.iter().chain(&mixed).all(|x| x.is_finite())
        && b.kink.c1.is_finite()
        && b.kink.c2.is_finite()
        && b.chord.c2.is_finite();
    if !finite {
        return Chord::ZERO;
    }
    let twist = twist(&mixed, e);
    let mb = m[(e + 1) % 3].max(m[(e + 2) % 3]);
    // The transition sides' bound at β = λ a: λ = 1/2 (a dyadic driver's coarser edge is at
    // most half the inner level; the snapped integer levels leave the rest to step 2), λ = 1
    // (the tessellator's integer levels: a coarser edge may be just below the inner level).
    let lambda = if rounding == Rounding::Integer {
        1.0
    } else {
        0.5
    };
    let mx = m[0].max(m[1]).max(m[2]);
    let bx = mixed[0].max(mixed[1]).max(mixed[2]);
    let mc = mx.max(0.5 * mx + 0.5 * bx);
    // The sides' S_e at β = λ a, over a².
    let sides = if rounding == Rounding::TessSnapped {
        let [caa, cab, cbb] = tess_side_coefficients(m[e], twist, mb);
        caa + cab * lambda + cbb * lambda * lambda
    } else {
        // After a move of at most `h` samples: half of one snapped, a whole one else.
        let h = if rounding.snapped() { 0.5 } else { 1.0 };
        h * h * m[e] + h * lambda * twist + lambda * lambda * mb
    };
    let q = match rounding {
        // No corner triangles: the bases' `M_e` or the sides'.
        Rounding::Snapped | Rounding::TessSnapped => m[e].max(sides),
        // Corner triangles (`M_c >= M_e` covers the bases).
        Rounding::SnappedInteger | Rounding::Integer => mc.max(sides),
    };
    // The sides' extent at β = λ a, over a (the kink terms').
    let x = need_extent(rounding);
    Chord {
        c1: x * b.kink.c1,
        c2: ELEMENT_FACTOR * q + x * x * b.kink.c2,
    }
}

/// The extent, over `a_e`, at which [`strip_need`] takes the transition triangles' kink and
/// cubic terms, at the `β <= λ a_e` it allows for (module notes, "Extents"): their largest
/// extent, `1` where the lattice's boundary is snapped at integer levels (`max(a_e, a_e/2 + β)`
/// at `λ = 1/2`), `1 + λ` beside the tessellator's rings (`a_e + β`: `2` for its integer levels,
/// `3/2` beside its first ring); and `5/4` for the gliding pattern driver, a quarter above its
/// extent, so that its edges stay close enough to their insides' levels for the snapped
/// boundary's switches to glide (module notes, "Gliding").
pub fn need_extent(rounding: Rounding) -> f32 {
    match rounding {
        Rounding::SnappedInteger => 1.0,
        Rounding::Snapped => 1.25,
        Rounding::TessSnapped => 1.5,
        Rounding::Integer => 2.0,
    }
}

/// What a polynomial patch's quadratic term is of the general bound's: `(1/6) / (9/40) =
/// 20/27` (module notes, "Polynomial patches"). Mirror: `LOD_POLYNOMIAL_SHARE`.
pub const POLYNOMIAL_SHARE: f32 = 20.0 / 27.0;

/// The cube of [`need_extent`] (module notes, "Polynomial patches"). Mirror: in
/// `edge_need_level`, glsl/lod/levels.comp.
pub fn need_extent_cubed(rounding: Rounding) -> f32 {
    need_extent(rounding).powi(3)
}

/// The transition sides' bound beside the tessellator's first ring ([`Rounding::TessSnapped`],
/// module notes), `S_e = c_aa a² + c_ab a β + c_bb β²` along an edge drawn at `a = 1/n_e` beside
/// an inside at `β = 1/n`, as `[c_aa, c_ab, c_bb] = [M_e/4, 2/3 M_e + T_e/3, 4/9 (M_e + T_e +
/// mb)]`, from the edge direction's `M_e`, the twist `T_e` across it and `mb`, the larger of
/// `M_{e+1}` and `M_{e+2}`. Mirror: `tess_side_coefficients` in glsl/lod/levels.comp.
pub(crate) fn tess_side_coefficients(me: f32, twist: f32, mb: f32) -> [f32; 3] {
    [
        0.25 * me,
        (2.0 / 3.0) * me + twist / 3.0,
        (4.0 / 9.0) * (me + twist + mb),
    ]
}

/// `T_e = 2 max(B_e, B_{e+2})`: what bounds the cross term of a transition side along stored
/// edge `e` (module notes), per unit `a_e β`. Mirror: `twist` in glsl/lod/levels.comp.
fn twist(mixed: &[f32], e: usize) -> f32 {
    2.0 * mixed[e].max(mixed[(e + 2) % 3])
}

/// The smallest level `1/β` at which `p β² + q β + c <= tol`, or `max` where none is (`c >=
/// tol`); 1 where any is. Mirror: `quadratic_level` in glsl/lod/levels.comp.
fn quadratic_level(p: f32, q: f32, c: f32, tol: f32, max: f32) -> f32 {
    if c >= tol {
        return max;
    }
    // Level 1 with room to spare (`p β² + q β + c <= (p + q + c) β²` for β >= 1, so the root is
    // past `sqrt(LEVEL_ONE_MARGIN)`), said before `4 p d` can overflow (`Chord::level_for`).
    if (p + q + c) * LEVEL_ONE_MARGIN <= tol {
        return 1.0;
    }
    let d = tol - c;
    // β = (−q + sqrt(q² + 4pd)) / 2p, in the form without cancellation.
    let den = q + (q * q + 4.0 * p * d).sqrt();
    if den <= 0.0 {
        return 1.0;
    }
    let beta = 2.0 * d / den;
    ((1.0 + 1.0 / 65536.0) / beta).clamp(1.0, max)
}

/// Step 2's bound of the transition triangles along stored edge `e` of element `r`, drawn at
/// `a = 1/n_e` beside an inside at `β` (module notes), as quadratics `[p, q, c]` in `β`
/// (`p β² + q β + c`), each with the extent `e0 + e1 β` of its triangles' sides (module notes,
/// "Extents"): the sides' (the kink terms at that extent, the sides' `S_e` after a move of at
/// most `h a`; beside the tessellator's first ring, its own coefficients) and the bases' (none
/// where the sides' `S_e` holds them: the tessellator's integer levels), each at `a + β`, or
/// where the lattice's boundary is snapped at `a/2 + β` and at `a` (the extent is the larger);
/// and where the element is a polynomial patch (no kinks) its cubic term `t3` (else `None`).
struct Strip {
    kinds: [([f32; 3], [f32; 2]); 4],
    count: usize,
    a: f32,
    t3: Option<f32>,
}

impl Strip {
    fn new(v: &LodView, r: &LodRecord, e: usize, a: f32) -> Self {
        let m = r.second;
        let (k1, k2) = (r.chord[2], r.chord[3]);
        let t = twist(&r.mixed, e);
        let mb = m[(e + 1) % 3].max(m[(e + 2) % 3]);
        let rounding = v.rounding();
        let (sides, reach) = if rounding == Rounding::TessSnapped {
            let [caa, cab, cbb] = tess_side_coefficients(m[e], t, mb);
            ([cbb, cab * a, caa * a * a], a)
        } else {
            let h = if rounding.snapped() { 0.5 } else { 1.0 };
            let reach = if rounding.tessellator() { a } else { 0.5 * a };
            ([mb, h * a * t, h * h * a * a * m[e]], reach)
        };
        // The bases' a² M_e is S_e's own first term where vertices move anywhere in a sample.
        let bases = rounding.snapped().then_some([0.0, 0.0, a * a * m[e]]);
        // The kink terms at extent `e0 + e1 β`.
        let kink =
            |[e0, e1]: [f32; 2]| [k2 * e1 * e1, (k1 + 2.0 * k2 * e0) * e1, (k1 + k2 * e0) * e0];
        let extents = if reach < a { 2 } else { 1 };
        let mut kinds = [([0.0; 3], [0.0; 2]); 4];
        let mut count = 0;
        for ext in [[reach, 1.0], [a, 0.0]].into_iter().take(extents) {
            for quad in std::iter::once(sides).chain(bases) {
                let k = kink(ext);
                kinds[count] = ([0, 1, 2].map(|i| ELEMENT_FACTOR * quad[i] + k[i]), ext);
                count += 1;
            }
        }
        let t3 = (m[3] < HUGE && k1 == 0.0 && k2 == 0.0).then_some(m[3]);
        Strip {
            kinds,
            count,
            a,
            t3,
        }
    }

    /// The smallest inner level at which the triangles meet tolerance `tol`, or the maximum
    /// level `max` where none does. A polynomial patch's own bound (20/27 of the quadratic
    /// terms, plus the cubic term) is solved only where the general one needs more than
    /// `enough` (the level the caller compares with): whether the answer is above `enough`
    /// does not change.
    fn level(&self, tol: f32, max: f32, enough: f32) -> f32 {
        // A quadratic's level, and where it needs more than `enough` the polynomial bound's.
        let solve = |&([p, q, c], ext): &([f32; 3], [f32; 2])| {
            let general = quadratic_level(p, q, c, tol, max);
            match self.t3.filter(|_| general > enough) {
                Some(t3) => {
                    let share = POLYNOMIAL_SHARE;
                    let cubic =
                        cubic_level([share * p, share * q, share * c], t3, ext, self.a, tol, max);
                    general.min(cubic)
                }
                None => general,
            }
        };
        self.kinds[..self.count]
            .iter()
            .map(solve)
            .fold(1.0, f32::max)
    }

    /// Whether the triangles meet `tol` at inner level `n`: each bound evaluated at `β = (1 +
    /// 2⁻¹⁶)/n`, the margin [`quadratic_level`] solves with, so that where [`Strip::level`]
    /// finds a level at most `n` this finds them met (up to rounding), without a square root
    /// or Newton's steps; and where it finds them met, they are, by the bound itself. A
    /// polynomial patch's bound is evaluated where the general one is not met.
    fn fits(&self, n: f32, tol: f32) -> bool {
        let b = (1.0 + 1.0 / 65536.0) / n;
        // Strictly below, as the solver asks (`c >= tol` is never met: a tolerance of zero,
        // where a sphere holds the eye, takes the largest level whatever the bound).
        let meets = |&([p, q, c], [e0, e1]): &([f32; 3], [f32; 2])| {
            let quad = (p * b + q) * b + c;
            let s = e0 + e1 * b;
            quad < tol
                || self
                    .t3
                    .is_some_and(|t3| POLYNOMIAL_SHARE * quad + t3 * s * s * s < tol)
        };
        self.kinds[..self.count].iter().all(meets)
    }
}

/// The smallest inner level at which the transition triangles along stored edge `e`, drawn at
/// `a = 1/n_e`, meet tolerance `tol` (module notes, step 2), or the maximum level where none
/// does ([`Strip::level`], `enough` as there). Mirror: `strip_new` then `strip_level` in
/// glsl/lod/levels.comp.
fn strip_level(v: &LodView, r: &LodRecord, e: usize, a: f32, tol: f32, enough: f32) -> f32 {
    Strip::new(v, r, e, a).level(tol, v.max_level as f32, enough)
}

/// The smallest level `1/β` at which a polynomial patch's transition triangles along an edge
/// drawn coarser than the inside (`β < a`), quadratic term `p β² + q β + c` and cubic term
/// `t (e0 + e1 β)³` (their sides' extent at most `e0 + e1 β`, `e1` 0 or 1), meet `tol` (module
/// notes, "Polynomial patches"): `1/a` (the edge's own level) where `β = a` fits, the maximum
/// where `β = 0` does not. Else the whole bound `f(β)` is convex and rising on `[0, a]`, so
/// Newton's steps from the quadratic term's own solution (at most `a`), which lies at or beyond
/// the root `β*`, stay at or beyond it ([`CUBIC_STEPS`] of them, within rounding of it); with
/// `b` the last, `t (e0 + e1 β)³ <= t (e0 + e1 b)(e0 + e1 β)²` for every `β <= b`, a quadratic
/// again, whose solution is at most `β*` (there the quadratic is at least `f(β*) = tol`) and so
/// at most `b`. Mirror: `cubic_level` in glsl/lod/levels.comp.
fn cubic_level([p, q, c]: [f32; 3], t: f32, [e0, e1]: [f32; 2], a: f32, tol: f32, max: f32) -> f32 {
    let bound = |b: f32| {
        let s = e0 + e1 * b;
        (p * b + q) * b + c + t * s * s * s
    };
    if bound(0.0) >= tol {
        return max;
    }
    if bound(a) <= tol {
        return (1.0 / a).clamp(1.0, max);
    }
    let mut b = (1.0 / quadratic_level(p, q, c, tol, max)).min(a);
    for _ in 0..CUBIC_STEPS {
        let s = e0 + e1 * b;
        let slope = 2.0 * p * b + q + 3.0 * t * e1 * s * s;
        if slope <= 0.0 {
            break;
        }
        b -= (bound(b) - tol) / slope;
    }
    let ts = t * (e0 + e1 * b.clamp(0.0, a));
    quadratic_level(
        p + ts * e1 * e1,
        q + 2.0 * ts * e0 * e1,
        c + ts * e0 * e0,
        tol,
        max,
    )
}

/// Newton's steps of [`cubic_level`].
const CUBIC_STEPS: u32 = 4;

/// Whether element `r`, drawn at the largest level with its edges at `edges` (continuous, as
/// `v` chose them), leaves the transition triangles along a coarser edge short of its
/// tolerance: [`raise_for_transitions`] would go past the largest level.
pub fn transitions_beyond(v: &LodView, r: &LodRecord, edges: &[f32; 3]) -> bool {
    let (dyadic, max) = (v.dyadic(), v.max_level);
    let tol = tolerance(v, r.sphere);
    let free = LodView {
        max_level: super::UNCAPPED,
        ..*v
    };
    edges.iter().enumerate().any(|(e, &l)| {
        let ne = drawn_level(l, dyadic, max);
        ne < max && strip_level(&free, r, e, 1.0 / ne as f32, tol, max as f32) > max as f32
    })
}

/// The inner level raised until every transition triangle meets the element's tolerance
/// (module notes, step 2): unchanged where no edge is drawn coarser than the inside or the
/// triangles already fit, else the drawn level that fits (an exact integer); and the edges
/// (bit `e`) whose triangles do not fit at the level it starts from (what the lift reads:
/// [`super::lift`]). Mirror: `raise_for_transitions` in glsl/lod/levels.comp.
pub fn raise_for_transitions(
    v: &LodView,
    r: &LodRecord,
    edges: &[f32; 3],
    inner: f32,
) -> (f32, u32) {
    let (dyadic, max) = (v.dyadic(), v.max_level);
    if r.chord[1] >= HUGE || r.chord[0] >= HUGE {
        return (inner, 0);
    }
    let tol = tolerance(v, r.sphere);
    let drawn_edges = edges.map(|l| drawn_level(l, dyadic, max));
    let mut n = drawn_level(inner, dyadic, max);
    let mut raised = false;
    let mut failing = 0;
    for it in 0..4 {
        if n >= max {
            break;
        }
        let mut need = 0.0f32;
        for (e, &ne) in drawn_edges.iter().enumerate() {
            if ne < n {
                // Solved only where the bound at `n` is not met.
                let strip = Strip::new(v, r, e, 1.0 / ne as f32);
                if !strip.fits(n as f32, tol) {
                    need = need.max(strip.level(tol, max as f32, n as f32));
                    if it == 0 {
                        failing |= 1 << e;
                    }
                }
            }
        }
        if need <= n as f32 {
            break;
        }
        n = drawn_level(need, dyadic, max);
        raised = true;
    }
    (if raised { n as f32 } else { inner }, failing)
}

#[cfg(test)]
mod tests {
    use super::quadratic_level;

    /// The solver without the level-1 shortcut, as it was.
    fn solved(p: f32, q: f32, c: f32, tol: f32, max: f32) -> f32 {
        if c >= tol {
            return max;
        }
        let d = tol - c;
        let den = q + (q * q + 4.0 * p * d).sqrt();
        if den <= 0.0 {
            return 1.0;
        }
        ((1.0 + 1.0 / 65536.0) / (2.0 * d / den)).clamp(1.0, max)
    }

    /// Level 1 for tolerances up to infinity (the solver's `4 p d` overflows there), and the
    /// solver's own level wherever both apply, near the shortcut's threshold too.
    #[test]
    fn the_level_one_shortcut_agrees_with_the_solver() {
        let coefficients = [
            (0.5f32, 0.25f32, 0.125f32),
            (3.0, 0.0, 0.01),
            (0.0, 2.0, 0.0),
            (1e-3, 1e-2, 1e-4),
        ];
        for &(p, q, c) in &coefficients {
            for tol in [1e38, f32::MAX, f32::INFINITY] {
                assert_eq!(
                    quadratic_level(p, q, c, tol, 64.0),
                    1.0,
                    "{p} {q} {c} at {tol}"
                );
            }
            let one = p + q + c;
            let mut checked = 0;
            for k in 0..2000 {
                // From just below level 1's bound to a few times past it.
                let tol = one * (0.999 + k as f32 * 1e-3);
                if tol.is_finite() && (p + q + c) * crate::lod::LEVEL_ONE_MARGIN <= tol {
                    assert_eq!(
                        quadratic_level(p, q, c, tol, 64.0),
                        solved(p, q, c, tol, 64.0)
                    );
                    checked += 1;
                }
            }
            assert!(checked > 1000);
        }
    }
}
