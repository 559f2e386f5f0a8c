//! Level of detail with a guaranteed screen-space error: proven chord-error bounds per surface,
//! the screen-space metric that turns them into refinement levels, per edge and per element, and
//! the conservative bounds (spheres, normal cones) that culling uses. Plain math on the CPU, all
//! in `f32`. `glsl/include/lod.glsl` mirrors it function for function for `flat`, `phong` and
//! `pn` with sine and noise displacement: bounds, spheres, normal cones, levels and culling
//! tests (glsl/lod/bounds.comp runs it per element, tests/lod_mirror.rs compares the two). Where
//! this module returns infinity (no finite bound) the mirror returns 3e38.
//!
//! # Levels
//! A level is what a pattern's level is in this codebase (src/pattern): `N` segments per edge,
//! the element's `(u, v)` domain cut into `N²` lattice triangles whose edges are parallel to the
//! three directions `d0 = corner 0 → 1`, `d1 = corner 1 → 2`, `d2 = corner 2 → 0` (barycentric
//! steps of `1/N`). A dyadic driver (samples at `k / 2^l`) uses `N = 2^l`: the bounds below
//! decrease with `N`, so any `N' >= N` meets what `N` meets ([`dyadic`]).
//!
//! # The chord error
//! The drawn mesh at level `N` is the piecewise-linear interpolation `I_N P` of the surface `P`
//! at the lattice points. Every bound here has the form ([`Chord`])
//! `|P(x) − I_N P(x)| <= c1 / N + c2 / N²` for every `x` of the element (world units), where `c1`
//! is zero except for the height map, whose bilinear texels put kinks in the surface.
//!
//! *One dimension.* For `g: [0, 1] → R³` and its chord `L`,
//! `g(t) − L(t) = −∫ G(t, τ) g''(τ) dτ` with `G >= 0`, `∫ G dτ = t(1 − t)/2` and `G <= t(1−t)`;
//! so `|g − L| <= t(1 − t)/2 · sup|g''| <= sup|g''| / 8`. When `g'` only has bounded variation
//! (kinks), `|g − L| <= ∫ G |dg'|`: a jump `J` at `τ` weighs `G(t, τ) <= t(1 − t)`, and jumps
//! at most `J` at evenly spaced points, `L` per unit `τ`, weigh together at most
//! `J (t(1 − t) + L ∫ G dτ) = J t(1 − t) (1 + L/2)` (`G(t, ·)` rises to its peak at `τ = t` and
//! falls: each point but the two around the peak is outweighed by the integral over the
//! spacing beside it, the lower of those two by the spacing between them, the higher by the
//! peak), so the jumps count once at the peak weight and the rest at the mean weight, half of it
//! ([`KINK_FACTOR`]). On an edge of `N` segments: `error <= M_e / (8 N²)`, `M_e` the supremum of
//! the edge curve's second derivative per unit edge parameter.
//!
//! *A lattice triangle.* Let `M_k >= sup |D²P[d_k, d_k]|` over the element ([`Bounds::second`]).
//! Take `x` in a lattice triangle `x0 x1 x2`, on the segment from `x0` to the point `q` of the
//! opposite side: `x = (1 − t) x0 + t q`, `q = (1 − s) x1 + s x2`. Then
//! `P(x) − I P(x) = [P(x) − (1 − t) P(x0) − t P(q)] + t [P(q) − I P(q)]`. The second bracket is
//! the one-dimensional error on side `x1 x2`: `<= s(1 − s)/2 · M_12`. The first is the
//! one-dimensional error along `v = q − x0 = (1 − s) d01 + s d02`, and for the quadratic form
//! `Q = D²P(y)` at any `y`, `Q(v) = (1 − s) Q(d01) + s Q(d02) − s(1 − s) Q(d12)` (the variance
//! identity), so `|Q(v)| <= (1 − s) M01 + s M02 + s(1 − s) M12`. With every `M <= M = max_k M_k / N²`,
//! `error <= M · [t(1 − t)(1 + s(1 − s))/2 + t s(1 − s)/2] <= M · max_t (5/8 t(1 − t) + t/8) =
//! 9/40 · M` (at `t = 3/5`). So an element at level `N` is within `c2 = 9/40 · max_k M_k` over `N²`
//! ([`ELEMENT_FACTOR`]); for kinks the same steps give `25/64` times a lattice segment's
//! weighted jumps, `J (1 + L/2)` summed over the families of lines it crosses, a smooth part
//! between the lines (a bilinear cell's twist) counting at half its supremum as above
//! ([`KINK_FACTOR`]).
//!
//! *A polynomial patch.* Where the surface is a polynomial of degree at most 3 (undisplaced
//! `flat`, `phong`, `pn`, `stpn`), a tighter bound holds. Take `x` in a lattice triangle with
//! corners `v_i`, weights `λ_i`, and `w_i = v_i − x`. Taylor's expansion at `x` stops at the
//! third order (`D³P` is constant): `P(v_i) = P(x) + DP(x) w_i + ½ D²P(x)[w_i, w_i] +
//! (1/6) D³P[w_i, w_i, w_i]`. As `Σ λ_i w_i = 0` and `Σ λ_i w_i ⊗ w_i = Σ_{i<j} λ_i λ_j
//! e_ij ⊗ e_ij` (`e_ij = v_i − v_j`, a lattice side `±d_k / N`),
//! `I P(x) − P(x) = ½ Σ_{i<j} λ_i λ_j D²P(x)[e_ij, e_ij] + (1/6) Σ_i λ_i D³P[w_i, w_i, w_i]`.
//! The first part is at most `½ (λ0 λ1 + λ1 λ2 + λ2 λ0) max_k M_k / N² <= max_k M_k / (6N²)`
//! (the sum is at most 1/3, at the centroid). For the second, `w_i = Σ_{j≠i} λ_j e_ij` has
//! lattice coordinates whose absolute values sum to `1 − λ_i`, so `|D³P[w_i, w_i, w_i]| <=
//! C̄ (1 − λ_i)³ / N³` with `C̄` bounding `|D³P|` on any three lattice directions
//! ([`Net::third`]), and `Σ λ_i (1 − λ_i)³ <= 8/27` (at the centroid). So the lattice
//! triangles are within `max_k M_k / (6N²) + 4 C̄ / (81 N³)` ([`QUADRATIC_FACTOR`],
//! [`CUBIC_FACTOR`], [`Bounds::cubic`]): the quadratic term is 20/27 of the general one's, and
//! Phong's quadratic has no cubic term. Each element takes the smaller of the two bounds
//! (`lod::frame::own_level`). The cubic term is turned into a level without solving a cubic:
//! with `N0` the level of the quadratic term alone, the level `N1` of
//! `c2 = max_k M_k / 6 + 4 C̄ / (81 N0)` is at least `N0`, so at `N1` the cubic term is at most
//! `4 C̄ / (81 N0 N1²)` and both terms together at most `c2 / N1²`. Where the driver glides, a
//! geomorphing element drawn at the power of two `n` (`n/2 < N1 <= n`) blends from level `n/2`
//! with a factor that assumes an error of the form `c2 / N²` at both (docs/adaptivity.md,
//! "Geomorphing"); there `c2` takes `2 · 4 C̄ / (81 N0)`, which bounds the cubic term at every
//! level from `N0 / 2` up (`lod::frame::own_level`; without it the blend passed the tolerance
//! by 1 % on Spot, `polynomial_levels_meet_their_bound`). The tessellator's triangles
//! (below) take the same identity with their own sides: `max(max_k M_k, R) / 6` and, their
//! sides spanning up to `4/3` of a lattice side in lattice coordinates (the diagonals), `(4/3)³`
//! times the cubic term ([`TESS_CUBIC`]).
//!
//! *The tessellator's inside.* The tess driver's inside is the tessellator's, not the lattice:
//! with equal spacing at level `N`, concentric rings of `N, N − 2, ...` segments a side
//! (src/render/tess.rs), each vertex at barycentric coordinates `K/(3N)` with integers `K`.
//! Its triangles' sides are lattice sides `d_k / N` along the rings and, between two rings, the
//! sides of parallelograms and corner triangles: `(d_a − d_b)/(3N)` across and the diagonals
//! `2(d_a − d_b)/(3N)` (which diagonal a parallelogram takes, and whether a ring's corner joins
//! the next ring's corner, the specification leaves to the implementation: both are allowed
//! for). A diagonal's `|Q|` can exceed every lattice side's: `Q(d_0 − d_2) = 2Q(d_0) + 2Q(d_2)
//! − Q(d_1)`, up to `5M` (a saddle with `Q(d_0) = Q(d_2) = M`, `Q(d_1) = −M`), and
//! `(2/3)² · 5 = 20/9`; on that saddle a corner triangle deviates `0.278 M/N²`, above the
//! lattice's `9/40 M/N²`. So a tess element's `c2` takes `9/40 · max(max_k M_k, R)`,
//! `R = 4/9 · max` over the three pairs of [`Bounds::second_along`]`(d_a − d_b)`
//! ([`RING_DIAGONAL`], `lod::frame::own_chord`); the level pass applies it for the tessellator's
//! roundings. The height map's kink terms count at a side's extent across each family of texel
//! lines: a lattice side spans at most `s` (the lattice directions' largest), a diagonal
//! `(2/3)(|d_a| + |d_b|) <= 4/3 s`, so the tessellator's `c1` takes a third more of the
//! element's `k1` and its `c2` 7/9 more of `k2` (`(4/3)² − 1`).
//!
//! # Per surface and displacement
//! Each surface and displacement declares how its chord error is bounded
//! (`FACTS.bound`, src/surface/bounds.rs), with the proof beside its code; src/lod/bound.rs
//! combines them without naming any:
//! - `flat` (src/surface/flat.rs, `net`): a linear net: zero.
//! - `phong` (src/surface/phong.rs, `net`): a quadratic, `D²P[d_ij, d_ij] = 2α K_ij` exactly; a
//!   corner whose two edges pick different normals (a flagged seam) is not a polynomial: no
//!   finite interior bound, the maximum level (its edges keep their exact bounds).
//! - `pn`, `stpn` (src/surface/pn.rs and stpn.rs, `net`): cubic Bézier triangles, the second
//!   differences of the ten-point net (the 2006 paper's edge bound, sign-free).
//! - `loop` (src/surface/loop_bound.rs): second differences of the exact limit points on the
//!   tables' lattice ([`crate::surface::loop_`]).
//! - displacement `P' = P + h N`, `N = n/|n|` the unit direction field (a polynomial `n` of degree
//!   1 or 2 with `|n| >= ρ > 0` on the patch, from its Bernstein coefficients' projection on their
//!   mean; each surface's `direction` nets: for `pn` and `stpn` the chosen normal field,
//!   `--normal-field`: quadratic for `paper` and `vlachos`, whose control normals differ, linear
//!   for `linear`): `|(hN)''| <= |h''| + 2|h'||N'| + |h||N''|`, with `|N'| <= |n'|/ρ` and
//!   `|N''| <= |n''|/ρ + 2|n'|²/ρ²` (src/lod/bound.rs `moved_second`: with `r = |n|`, `N' = n'⊥/r`
//!   for `n'⊥` the part of `n'` across `N`; `N''`'s part along `N` is `−|N'|² N`, and across it
//!   `n''⊥/r − 2 n'⊥ (N·n')/r²`, where `2|n'⊥||N·n'| <= |n'|²`). For a height `h = η(P)` of the point
//!   (`sine`: src/surface/displace.rs; `noise`: src/surface/noise.rs),
//!   `|h''| <= H |P'|² + G |P''|` (`h'' = ∇²η[P', P'] + ∇η · P''`, `|P'|` bounded by
//!   [`Net::first_sup`](bound::Net::first_sup), `|P''|` by the net's second differences) with `G` a bound of `η`'s
//!   gradient length and `H` of its second derivative along any unit direction over the
//!   patch's sphere ([`crate::surface::bounds::Height`]). Where `η = φ(|p − o|)` depends on
//!   the distance from a point alone (`sine`), `h'' = φ'' r'² + φ' r''` with `r = |P − o|`,
//!   `|r''| <= (|P'|² − r'²)/r + |P''|`: the patch's own `sup |r'|` (from
//!   [`Net::radial_first`](bound::Net::radial_first)) replaces `|P'|` in the curvature term
//!   (src/lod/bound.rs `radial_height`), far smaller where the patch runs around `o`. The height map's `h`
//!   (src/surface/heightmap_bound.rs, `BOUND`) is bilinear in texels (kinks at texel lines):
//!   its slope jumps by at most the second difference of the texels under the patch per texel
//!   line crossed, one jump at the peak weight, which gives the `c1 / N` term, the rest in
//!   `c2 / N²` (above).
//!
//! Edges: an edge's bound, sphere and level come from its own data only (its corners in
//! canonical order, src/surface/mod.rs, with the third weight zero, exactly as the surfaces
//! evaluate the edge), so the two elements that share it compute the same bits.
//!
//! # The screen-space metric
//! `K = H / (2 tan(fov_y / 2))` ([`View`]): a world distance `d` at point `p` counts
//! `d · K / |p − eye|` pixels (distance, not depth: turning the camera changes no level). For a
//! patch inside the sphere `(c, r)` every point is at least `|c − eye| − r` from the eye, so
//! level `N` meets a pixel error `PX` when `c1/N + c2/N² <= PX · (|c − eye| − r) / K`. The
//! continuous level ([`Chord::level_for`]) is the real `N` where equality holds, clamped to
//! `[1, max]`; its ceiling is the integer level. An eye inside the sphere gets the maximum level.
//! The metric counts distance, not depth: on screen, a deviation at angle φ off the view axis
//! shows up to `1/cos²φ` times the pixels the metric counts (the end-to-end test checks both).
//! An edge's level uses the edge's own bound and sphere; an element's inner level is at least
//! the largest of its edges' ([`View::levels`]). Where a bound is infinite (a Phong element with
//! blended seam normals, unless its alpha is 0, a direction field that may vanish, `sine` around its centre, `loop`
//! displaced where M1's normals may cancel, a height map read past `2^18` texels of texture
//! coordinates: src/surface/heightmap_bound.rs, `FAR`) the level is the maximum and the pixel
//! error is not guaranteed there.
//!
//! The displacement direction's lower bound `ρ` ([`net::Net::min_length`]) is the better of
//! the Bernstein hull's distance from the origin and a lattice's cells, each bounded below by
//! the better of its corners' largest `|n|` less the change possible within it and its
//! corners' least projection on their mean direction less the cell's interpolation error (the
//! lattice triangle's bound above applied to `n`: `|n| >= n · u >= min_c n(x_c) · u − E`), on
//! 8, then 32, then 128 segments per side (the finer ones only while the bound is below half
//! the largest `|n|` at the corners: PN's normal field can turn by more than 90° along an
//! edge). The second-order cell bound keeps a turning field's `ρ` within about 1% of its least
//! length on 8 segments, where the first-order one falls 20% short.
//! Scalar-tagged edges with crease corners take the worst of both sides' sharp normals, which
//! only the element knows.
//!
//! # Culling (src/lod/cull.rs)
//! A sphere wholly outside one of the view-projection's six planes is invisible. A patch faces
//! away when every drawn triangle does: a drawn triangle's edge vectors are averages of `P_u`
//! and `P_v`, which lie in the convex hulls of the net's scaled first differences, so its normal
//! lies in the cone of their cross products; if that cone and the directions from the eye to the
//! sphere are less than 90° apart everywhere, the element draws nothing visible. Cones exist
//! for undisplaced `flat`, `phong` and `pn`/`stpn` elements; displaced and `loop` elements are
//! never culled as back faces (frustum culling still applies, with their displaced spheres).
//!
//! # Transition triangles
//! A driver that draws an element at its inner level with boundary vertices on its edges' own
//! (coarser) samples draws triangles that are not lattice triangles. [`Bounds::triangle_error`]
//! bounds any parameter triangle of the element from the same three directional bounds
//! (polarization: each pair of lattice directions sums to the third).
#![forbid(unsafe_code)]

pub mod bound;
pub mod cull;
pub mod frame;
pub mod levels;
pub mod net;
pub mod report;

pub use bound::{Bounds, Lod};
pub use cull::{Frustum, NormalCone};
pub use net::Net;
pub use report::{px, LevelReport};

use glam::Vec3;

/// `c2` of an element from its per-direction second-derivative bounds: `9/40 · max_k M_k`.
pub const ELEMENT_FACTOR: f32 = 9.0 / 40.0;
/// The quadratic term of a polynomial patch's lattice triangles: `max_k M_k / 6` over `N²`
/// (module notes, "A polynomial patch"). Mirror: `LOD_QUADRATIC_FACTOR`.
pub const QUADRATIC_FACTOR: f32 = 1.0 / 6.0;
/// The cubic term's factor on the third differences' bound `C̄` ([`Net::third`]): `(1/6) ·
/// max Σ λ_i (1 − λ_i)³ = (1/6)(8/27) = 4/81` (module notes, "A polynomial patch").
pub const CUBIC_FACTOR: f32 = 4.0 / 81.0;
/// The cubic term of the tessellator's triangles against the lattice's: `(4/3)³`, their
/// sides spanning up to `4/3` of a lattice side in lattice directions (the diagonals
/// `(2/3)(d_a − d_b)`). Mirror: `LOD_TESS_CUBIC`.
pub const TESS_CUBIC: f32 = 64.0 / 27.0;
/// The scale of the tessellator's ring diagonals `(2/3)(d_a − d_b)` in `|Q|`: `(2/3)²` (module
/// notes, "The tessellator's inside"). Mirror: `LOD_RING_DIAGONAL`.
pub const RING_DIAGONAL: f32 = 4.0 / 9.0;
/// `c2` of an edge from its curve's second-derivative bound: `M_e / 8`.
pub const EDGE_FACTOR: f32 = 1.0 / 8.0;
/// The factor of a lattice segment's weighted kinks (one jump of each family of lines at the
/// peak weight, the rest at half of it: module notes), in a triangle.
pub const KINK_FACTOR: f32 = 25.0 / 64.0;
/// The same on an edge: `max t(1 − t) = 1/4`.
pub const EDGE_KINK_FACTOR: f32 = 0.25;

/// A chord-error bound: at level `N` (segments per edge) the surface is within
/// `c1 / N + c2 / N²` world units of its piecewise-linear interpolation. Infinite coefficients
/// mean no finite bound (the maximum level).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Chord {
    pub c1: f32,
    pub c2: f32,
}

impl Chord {
    pub const ZERO: Chord = Chord { c1: 0.0, c2: 0.0 };

    /// The bound at level `n` (segments per edge, `n >= 1`).
    pub fn error(&self, n: f32) -> f32 {
        let x = 1.0 / n;
        (self.c1 + self.c2 * x) * x
    }

    /// The smallest real level `N >= 1` with `error(N) <= tol`, uncapped (infinite where no
    /// finite level does): `N = (c1 + sqrt(c1² + 4 c2 tol)) / (2 tol)`, made a hair larger so
    /// that rounding never lands below the exact root.
    pub fn level_for(&self, tol: f32) -> f32 {
        // Level 1 meets it with room to spare (the coefficients are non-negative; the formula
        // gives 1 there too wherever its intermediates are normal floats): said before the
        // formula, whose `c2 · tol` overflows for a huge tolerance (a pixel error near f32's
        // largest), where it would give NaN or infinity.
        if (self.c1 + self.c2) * LEVEL_ONE_MARGIN <= tol {
            return 1.0;
        }
        let root = (self.c1 + (self.c1 * self.c1 + 4.0 * self.c2 * tol).sqrt()) / (2.0 * tol);
        // 0/0 (a zero bound and a zero tolerance) is no refinement needed.
        let n = if root.is_nan() { 1.0 } else { root };
        (n * (1.0 + 1.0 / 65536.0)).max(1.0)
    }

    /// The larger of two bounds, coefficient by coefficient.
    pub fn max(self, o: Chord) -> Chord {
        Chord {
            c1: self.c1.max(o.c1),
            c2: self.c2.max(o.c2),
        }
    }
}

/// How far below a tolerance an error bound at level 1 must be for the level to be 1 without
/// solving for it: then (the bounds' coefficients being non-negative) the solution is at most
/// `1 / sqrt(1.0001)`, below `1 / (1 + 2^-16)`, which the solvers' margin keeps at 1 too, so
/// the shortcut changes no level the solvers give in normal floats (with subnormal
/// intermediates they could give just above 1). Mirror: `LOD_LEVEL_ONE_MARGIN`.
pub const LEVEL_ONE_MARGIN: f32 = 1.0001;

/// A sphere that contains a patch (surface and displacement).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    pub centre: Vec3,
    pub radius: f32,
}

impl Sphere {
    /// A sphere around `points`: the centre of their bounding box, the largest distance from it
    /// (with a few ulps of room for the rounding of the points' own evaluation). The result does
    /// not depend on the points' order.
    pub fn around(points: &[Vec3]) -> Sphere {
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for &p in points {
            lo = lo.min(p);
            hi = hi.max(p);
        }
        let centre = (lo + hi) * 0.5;
        let mut r = 0.0f32;
        for &p in points {
            r = r.max((p - centre).length());
        }
        let scale = centre.abs().max_element().max(r);
        Sphere {
            centre,
            radius: r + scale * (8.0 * f32::EPSILON),
        }
    }

    /// The same sphere grown by `d` (a displacement's largest height).
    pub fn grown(self, d: f32) -> Sphere {
        Sphere {
            radius: self.radius + d,
            ..self
        }
    }
}

/// The camera as the metric sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    pub eye: Vec3,
    /// `K = H / (2 tan(fov_y / 2))`: pixels per world unit at distance 1.
    pub k: f32,
    /// The largest allowed error, in pixels.
    pub pixel_error: f32,
    /// The largest level (segments per edge) any edge or element gets.
    pub max_level: u32,
}

impl View {
    /// `fov_y` in radians, `height` the image's height in pixels.
    pub fn new(eye: Vec3, fov_y: f32, height: u32, pixel_error: f32, max_level: u32) -> Self {
        Self {
            eye,
            k: height as f32 / (2.0 * (0.5 * fov_y).tan()),
            pixel_error,
            max_level: max_level.max(1),
        }
    }

    /// How many pixels a world distance `d` at point `p` counts.
    pub fn pixels(&self, d: f32, p: Vec3) -> f32 {
        d * self.k / (p - self.eye).length()
    }

    /// The world distance allowed anywhere inside sphere `s`: `PX · dist(eye, s) / K`, zero when
    /// the eye is inside.
    pub fn tolerance(&self, s: &Sphere) -> f32 {
        let dist = (s.centre - self.eye).length() - s.radius;
        self.pixel_error * dist.max(0.0) / self.k
    }

    /// The continuous level of a patch with bound `chord` inside `s`, in `[1, max_level]`; its
    /// ceiling ([`integer_level`]) is the smallest integer level that meets the pixel error
    /// (or the maximum level).
    pub fn level(&self, chord: &Chord, s: &Sphere) -> f32 {
        let tol = self.tolerance(s);
        let max = self.max_level as f32;
        if tol > 0.0 {
            chord.level_for(tol).min(max)
        } else if chord.c1 == 0.0 && chord.c2 == 0.0 {
            1.0
        } else {
            max
        }
    }

    /// The continuous level of an element's lattice triangles: that of its chord bound or, for
    /// a polynomial patch ([`Bounds::cubic`]), the smaller level `N1` of `max_k M_k / 6 +
    /// cubic / N0`, `N0` the level of the quadratic term alone (module notes, "A polynomial
    /// patch"), at integer levels. The level pass's own, written on its records:
    /// `lod::frame::own_level`.
    pub fn element_level(&self, b: &Bounds) -> f32 {
        let general = self.level(&b.chord, &b.sphere);
        if !b.cubic.is_finite() {
            return general;
        }
        let q = QUADRATIC_FACTOR * b.second.iter().fold(0.0f32, |a, &m| a.max(m));
        let n0 = self.level(&Chord { c1: 0.0, c2: q }, &b.sphere);
        let c2 = q + b.cubic / n0;
        general.min(self.level(&Chord { c1: 0.0, c2 }, &b.sphere))
    }

    /// The levels of an element and its three edges (stored edge order): each edge's own, and the
    /// element's inner level ([`View::element_level`]) at least the largest of them.
    pub fn levels(&self, element: &Bounds, edges: &[Bounds; 3]) -> ([f32; 3], f32) {
        let e = edges.each_ref().map(|b| self.level(&b.chord, &b.sphere));
        let inner = self.element_level(element);
        (e, inner.max(e[0]).max(e[1]).max(e[2]))
    }
}

/// The integer level of a continuous one.
pub fn integer_level(level: f32) -> u32 {
    level.ceil() as u32
}

/// The dyadic level (a power of two, `2^l` segments) that meets what level `n` meets.
pub fn dyadic(n: u32) -> u32 {
    n.max(1).next_power_of_two()
}

#[cfg(test)]
mod tests;
