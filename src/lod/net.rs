//! Triangular Bézier nets: the form every local surface's bound is computed in
//! (src/lod/bound.rs), with their directional differences, lower bounds of their length
//! (displacement directions) and hulls (spheres, normal cones).

use crate::surface::dot3;
use glam::Vec3;

/// A triangular Bézier net of degree `degree` (1 to 3): `P(w) = Σ b_ijk · m!/(i!j!k!) w0^i w1^j
/// w2^k`, point `(i, j, k)` at [`Net::index`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Net {
    pub degree: usize,
    pub points: [Vec3; 10],
}

impl Net {
    /// Where point `w = (i, j, k)`, `i + j + k = m`, is kept: rows of falling `i`.
    pub fn index(m: usize, w: [usize; 3]) -> usize {
        let r = m - w[0];
        r * (r + 1) / 2 + w[2]
    }

    pub fn at(&self, w: [usize; 3]) -> Vec3 {
        self.points[Self::index(self.degree, w)]
    }

    /// Every multi-index of degree `m`, in storage order.
    pub fn multi(m: usize) -> impl Iterator<Item = [usize; 3]> {
        (0..=m)
            .rev()
            .flat_map(move |i| (0..=m - i).map(move |k| [i, m - i - k, k]))
    }

    /// The net whose point `w` is `f(w)`.
    pub fn from_fn(m: usize, f: impl Fn([usize; 3]) -> Vec3) -> Net {
        let mut points = [Vec3::ZERO; 10];
        for w in Self::multi(m) {
            points[Self::index(m, w)] = f(w);
        }
        Net { degree: m, points }
    }

    /// Whether multi-index `w` is kept when restricting to the edge opposite corner `third`.
    fn keep(w: &[usize; 3], edge: Option<usize>) -> bool {
        edge.is_none_or(|k| w[(k + 2) % 3] == 0)
    }

    /// `sup |D²P[d_k, d_k]|` along direction `k` (corner `k` to corner `k + 1`):
    /// `m(m − 1) · max |Δ²_k b|`; with `edge = Some(k)` only the edge's own differences, the
    /// bound of the edge curve. The differences are written `(b_a + b_b) − 2 b_ab` so that the
    /// edge's reversed net gives the same bits.
    pub fn second(&self, k: usize, edge: Option<usize>) -> f32 {
        let m = self.degree;
        if m < 2 {
            return 0.0;
        }
        let (a, b) = (k, (k + 1) % 3);
        let mut best = 0.0f32;
        for g in Self::multi(m - 2).filter(|g| Self::keep(g, edge)) {
            let (mut aa, mut bb, mut ab) = (g, g, g);
            aa[a] += 2;
            bb[b] += 2;
            ab[a] += 1;
            ab[b] += 1;
            let d = (self.at(aa) + self.at(bb)) - self.at(ab) * 2.0;
            best = best.max(d.length());
        }
        (m * (m - 1)) as f32 * best
    }

    /// `sup |D²P[d_k, d_{k+1}]|` over the patch, the mixed second derivative of directions `k`
    /// and `k + 1` (corner `k` to `k + 1`, corner `k + 1` to `k + 2`):
    /// `m(m − 1) · max |Δ_k Δ_{k+1} b|` over the mixed second differences of the net.
    ///
    /// Proof: `D_{d_a} P = m Σ_{|γ| = m−1} B^{m−1}_γ Δ_a b_γ` with `Δ_a b_γ = b_{γ+e_{a+1}} −
    /// b_{γ+e_a}` (the degree-elevation identity of the Bernstein basis), and applying it
    /// again, `D²P[d_a, d_b] = m(m − 1) Σ_{|γ| = m−2} B^{m−2}_γ Δ_a Δ_b b_γ`: a convex
    /// combination (the Bernstein polynomials are nonnegative and sum to one on the triangle),
    /// so within the largest of its terms. Exact for a quadratic (one term), zero for a linear
    /// net.
    pub fn mixed(&self, k: usize) -> f32 {
        let m = self.degree;
        if m < 2 {
            return 0.0;
        }
        let (a, b, c) = (k, (k + 1) % 3, (k + 2) % 3);
        let mut best = 0.0f32;
        for g in Self::multi(m - 2) {
            // Δ_k Δ_{k+1} b_γ = b_{γ+e_b+e_c} − b_{γ+e_b+e_b} − b_{γ+e_a+e_c} + b_{γ+e_a+e_b}.
            let at = |x: usize, y: usize| {
                let mut w = g;
                w[x] += 1;
                w[y] += 1;
                self.at(w)
            };
            let d = (at(b, c) + at(a, b)) - (at(b, b) + at(a, c));
            best = best.max(d.length());
        }
        (m * (m - 1)) as f32 * best
    }

    /// `C̄ >= |D³P[d_a, d_b, d_c]|` for every three lattice directions of the patch (any of
    /// `d0`, `d1`, `d2`, repeated or not): `m(m − 1)(m − 2) · max |Δ_a Δ_b Δ_c b_γ|` over the
    /// net's third differences (the proof of [`Net::mixed`], one order up: a convex combination
    /// of them; for a cubic one term each, the exact constant third derivative). Zero below
    /// degree 3. What [`super::CUBIC_FACTOR`] turns into the lattice's cubic term.
    pub fn third(&self) -> f32 {
        let m = self.degree;
        if m < 3 {
            return 0.0;
        }
        let mut best = 0.0f32;
        for g in Self::multi(m - 3) {
            for a in 0..3 {
                for b in a..3 {
                    for c in b..3 {
                        // Δ_k b_γ = b_{γ+e_{k+1}} − b_{γ+e_k}, applied three times: eight
                        // signed points.
                        let mut sum = Vec3::ZERO;
                        for bits in 0..8u32 {
                            let mut w = g;
                            let mut sign = 1.0f32;
                            for (i, &k) in [a, b, c].iter().enumerate() {
                                if bits >> i & 1 == 1 {
                                    w[(k + 1) % 3] += 1;
                                } else {
                                    w[k] += 1;
                                    sign = -sign;
                                }
                            }
                            sum += self.at(w) * sign;
                        }
                        best = best.max(sum.length());
                    }
                }
            }
        }
        (m * (m - 1) * (m - 2)) as f32 * best
    }

    /// `sup |DP[d_k]|`: `m · max |Δ_k b|` (restricted to the edge with `edge = Some(k)`).
    pub fn first(&self, k: usize, edge: Option<usize>) -> f32 {
        let m = self.degree;
        let (a, b) = (k, (k + 1) % 3);
        let mut best = 0.0f32;
        for g in Self::multi(m - 1).filter(|g| Self::keep(g, edge)) {
            let (mut ga, mut gb) = (g, g);
            ga[a] += 1;
            gb[b] += 1;
            best = best.max((self.at(gb) - self.at(ga)).length());
        }
        m as f32 * best
    }

    /// `sup |DP[d_k]|` as [`Net::first`] bounds it, or tighter where the derivative is not
    /// linear (a cubic's): the derivative `H = DP[d_k] = m Σ B^{m−1}_γ Δ_k b_γ` is itself a net
    /// of degree `m − 1` ([`Net::hodograph`]), so on the lattice of [`FIRST_GRID`] segments a
    /// side `|H| <= max |H(lattice points)| + 9/40 · max_j sup |D²H[d_j, d_j]| / G²` (the
    /// chord-error bound of src/lod/mod.rs applied to `H`: its piecewise-linear interpolant is
    /// within the largest value at the lattice points, being a convex combination of them), and
    /// `sup |D²H[d_j, d_j]|` is the hodograph's own [`Net::second`]. On edge `k`'s curve
    /// (`edge = Some(k)`) the samples are the edge's `G + 1` and the factor `1/8`
    /// ([`Net::sampled_sup`]). The smaller of the two bounds. Mirror: `lod_first_sup` in
    /// glsl/include/lod_derivatives.glsl.
    pub fn first_sup(&self, k: usize, edge: Option<usize>) -> f32 {
        let hull = self.first(k, edge);
        if self.degree < 3 {
            // A derivative of degree one or none is largest at a corner, a point of the net.
            return hull;
        }
        let hodograph = self.hodograph(k);
        let dirs = Self::directions(edge);
        let second = dirs.map(|j| hodograph.second(j, edge)).fold(0.0, f32::max);
        // The samples' rounding: a Bernstein sum is within a few ulps of its points' largest.
        let rounding = 8.0 * f32::EPSILON * hull;
        let tight = Self::sampled_sup(edge, second, rounding, |w| hodograph.eval(w).length());
        hull.min(tight)
    }

    /// `sup |(P − o) · DP[d_k]|` over the patch (edge `k`'s curve with `edge = Some(k)`),
    /// `r_max >= |P − o|` there: how fast the distance from `o` changes (`r' = (P − o) · P'/r`),
    /// what a height of that distance needs ([`crate::surface::bounds::Radial`]). The product
    /// `q = (P − o) · H`, `H = DP[d_k]`, sampled on the lattice of [`FIRST_GRID`]
    /// ([`Net::sampled_sup`]), its second derivatives along each lattice direction `j` being
    /// `(P − o) · D²H[d_j, d_j] + 2 DP[d_j] · D²P[d_k, d_j] + D²P[d_j, d_j] · H`, bounded by
    /// `r_max` times the hodograph's [`Net::second`], the first derivatives' [`Net::first_sup`]
    /// times the second ones ([`Net::second`] along `k`, [`Net::mixed`] across), and the
    /// second derivative's times `H`'s; at most `r_max · first_sup(k)`. `firsts` holds
    /// [`Net::first_sup`] of each direction the bound runs over (the others are not read).
    /// Mirror: `lod_radial_first` in glsl/include/lod_derivatives.glsl.
    pub fn radial_first(
        &self,
        k: usize,
        edge: Option<usize>,
        o: Vec3,
        r_max: f32,
        firsts: [f32; 3],
    ) -> f32 {
        let v = firsts[k];
        let plain = r_max * v;
        let hodograph = self.hodograph(k);
        let mut second = 0.0f32;
        for j in Self::directions(edge) {
            let across = if j == k {
                self.second(k, edge)
            } else if j == (k + 1) % 3 {
                self.mixed(k)
            } else {
                self.mixed(j)
            };
            let t = r_max * hodograph.second(j, edge)
                + 2.0 * firsts[j] * across
                + self.second(j, edge) * v;
            second = second.max(t);
        }
        // The samples' rounding: `P` within a few ulps of its points' largest length, `P − o`
        // of `r_max`, the derivative of its hull's `first`, and the product of theirs.
        // (the edge's own points on an edge: the same bits from both sides)
        let far = self
            .hull(edge)
            .iter()
            .fold(0.0f32, |a, p| a.max(p.length()));
        let rounding = 16.0 * f32::EPSILON * (r_max + far) * self.first(k, edge);
        let tight = Self::sampled_sup(edge, second, rounding, |w| {
            (self.eval(w) - o).dot(hodograph.eval(w)).abs()
        });
        plain.min(tight)
    }

    /// The derivative along direction `k` (corner `k` to `k + 1`) as a net of degree `m − 1`:
    /// points `m Δ_k b_γ` (degree 1 or more).
    pub fn hodograph(&self, k: usize) -> Net {
        let m = self.degree;
        let (a, b) = (k, (k + 1) % 3);
        Net::from_fn(m - 1, |g| {
            let (mut ga, mut gb) = (g, g);
            ga[a] += 1;
            gb[b] += 1;
            (self.at(gb) - self.at(ga)) * m as f32
        })
    }

    /// The lattice directions a bound of the patch (of edge `k`'s curve) runs over.
    fn directions(edge: Option<usize>) -> impl Iterator<Item = usize> + Clone {
        (0..3).filter(move |&j| edge.is_none_or(|e| e == j))
    }

    /// A bound of `sup f` over the patch (edge `e`'s curve) for a function `f = |F|` with
    /// `sup |D²F[d_j, d_j]| <= second` along every lattice direction: its largest value on
    /// the lattice of [`FIRST_GRID`] segments a side (the edge's `G + 1` points) plus the chord
    /// bound `9/40 · second / G²` (`1/8` on an edge), with `rounding` (a bound of the samples'
    /// rounding errors) and a relative `2^−16` added.
    pub fn sampled_sup(
        edge: Option<usize>,
        second: f32,
        rounding: f32,
        f: impl Fn([f32; 3]) -> f32,
    ) -> f32 {
        let g = FIRST_GRID;
        let step = 1.0 / g as f32;
        let mut best = 0.0f32;
        let factor = match edge {
            Some(e) => {
                for i in 0..=g {
                    let mut w = [0.0f32; 3];
                    w[(e + 1) % 3] = i as f32 * step;
                    w[e] = (g - i) as f32 * step;
                    best = best.max(f(w));
                }
                super::EDGE_FACTOR
            }
            None => {
                for i in 0..=g {
                    for j in 0..=g - i {
                        best = best.max(f([
                            (g - i - j) as f32 * step,
                            i as f32 * step,
                            j as f32 * step,
                        ]));
                    }
                }
                super::ELEMENT_FACTOR
            }
        };
        (best + rounding + factor * second * (step * step)) * (1.0 + 1.0 / 65536.0)
    }

    /// The points of the net (of edge `k`'s curve with `edge = Some(k)`).
    pub fn hull(&self, edge: Option<usize>) -> Vec<Vec3> {
        Self::multi(self.degree)
            .filter(|w| Self::keep(w, edge))
            .map(|w| self.at(w))
            .collect()
    }

    /// The patch at barycentric `w`.
    pub fn eval(&self, w: [f32; 3]) -> Vec3 {
        let m = self.degree;
        let fact = |k: usize| (1..=k).product::<usize>() as f32;
        Self::multi(m).fold(Vec3::ZERO, |s, e| {
            let c = fact(m) / (fact(e[0]) * fact(e[1]) * fact(e[2]));
            s + self.at(e)
                * (c * w[0].powi(e[0] as i32) * w[1].powi(e[1] as i32) * w[2].powi(e[2] as i32))
        })
    }

    /// A lower bound of `|P|` over the patch (the edge's curve with `edge = Some(k)`), the
    /// larger of two: the convex hull's distance from the origin along an axis (the best of the
    /// points' mean direction and each point's own), and a lattice of [`RHO_GRIDS`] segments
    /// per side bounded cell by cell (`sampled_min_length`). Zero when neither separates the
    /// patch from the origin.
    pub fn min_length(&self, edge: Option<usize>) -> f32 {
        let pts = self.hull(edge);
        let mean = pts.iter().fold(Vec3::ZERO, |s, &p| s + p);
        let along = |axis: Vec3| {
            let axis = axis.normalize_or_zero();
            pts.iter()
                .map(|&p| dot3(p, axis))
                .fold(f32::INFINITY, f32::min)
        };
        let mut low = along(mean);
        for &p in &pts {
            low = low.max(along(p));
        }
        // The coarsest lattice always, the finer ones while the bound is below half the
        // patch's largest |P| at its corners (the edge's own corners for an edge).
        let m = self.degree;
        let enough = 0.5
            * Self::multi(m)
                .filter(|w| Self::keep(w, edge) && w.contains(&m))
                .map(|w| self.at(w).length())
                .fold(0.0, f32::max);
        for g in RHO_GRIDS {
            low = low.max(self.sampled_min_length(edge, g));
            if low >= enough {
                break;
            }
        }
        // A relative margin for the rounding of the sums.
        let big = pts.iter().map(|p| p.length()).fold(0.0, f32::max);
        (low - 16.0 * f32::EPSILON * big).max(0.0)
    }

    /// A lower bound of `|P|` on the lattice of `g` segments per side, cell by cell, the better
    /// of two: the largest `|P|` at the cell's corners less what `P` changes within the cell
    /// (`max_k sup|DP[d_k]|` over a segment), and `min_c P(x_c) · u − E` for the unit `u` along
    /// the corners' sum, `E` the cell's interpolation error bound (`9/40 · max_k M_k` over a
    /// lattice triangle, `M_e / 8` over a segment, at size `1/g`; src/lod/mod.rs, "The chord
    /// error"): inside the cell `P = I P + r` with `|r| <= E` and `I P` a convex combination of
    /// the corners, so `|P| >= P · u >= min_c P(x_c) · u − E`. The second is what a turning
    /// field needs: its length changes far less within a cell than the field itself.
    fn sampled_min_length(&self, edge: Option<usize>, g: u32) -> f32 {
        self.lattice_min_length(edge, g, true)
    }

    /// [`Net::sampled_min_length`], with the second-order cell bound or (`second_order` false,
    /// for the tests) without it.
    fn lattice_min_length(&self, edge: Option<usize>, g: u32, second_order: bool) -> f32 {
        let at = |w: [u32; 3]| self.eval(w.map(|x| x as f32 / g as f32));
        let h2 = 1.0 / (g * g) as f32;
        // The cell with corners `p`: first order with `step`, second with error `e`.
        let cell = |p: &[Vec3], step: f32, e: f32| {
            let first = p.iter().map(|x| x.length()).fold(0.0, f32::max) - step;
            if !second_order {
                return first;
            }
            // As the GLSL twin divides: s / sqrt(s · s).
            let s = p.iter().fold(Vec3::ZERO, |s, &x| s + x);
            let l2 = s.dot(s);
            let u = if l2 > 0.0 { s / l2.sqrt() } else { Vec3::ZERO };
            let second = p.iter().map(|&x| dot3(x, u)).fold(f32::INFINITY, f32::min) - e;
            first.max(second)
        };
        match edge {
            Some(k) => {
                let step = self.first(k, edge) / g as f32;
                let e = super::EDGE_FACTOR * self.second(k, edge) * h2;
                let on = |t: u32| {
                    let mut w = [0u32; 3];
                    w[k] = g - t;
                    w[(k + 1) % 3] = t;
                    at(w)
                };
                (0..g)
                    .map(|t| cell(&[on(t), on(t + 1)], step, e))
                    .fold(f32::INFINITY, f32::min)
            }
            None => {
                let step = (0..3).map(|k| self.first(k, None)).fold(0.0, f32::max) / g as f32;
                let worst = (0..3).map(|k| self.second(k, None)).fold(0.0, f32::max);
                let e = super::ELEMENT_FACTOR * worst * h2;
                let mut m = f32::INFINITY;
                for j in 0..g {
                    for i in 0..g - j {
                        let (a, b, c) = (
                            at([g - i - j, i, j]),
                            at([g - i - j - 1, i + 1, j]),
                            at([g - i - j - 1, i, j + 1]),
                        );
                        m = m.min(cell(&[a, b, c], step, e));
                        if i + j + 1 < g {
                            let d = at([g - i - j - 2, i + 1, j + 1]);
                            m = m.min(cell(&[b, d, c], step, e));
                        }
                    }
                }
                m
            }
        }
    }
}

/// Lattice segments per side on which [`Net::min_length`] samples (the finer ones only while
/// the bound is below half the largest `|P|` at the corners).
pub const RHO_GRIDS: [u32; 3] = [8, 32, 128];

/// Segments a side of the lattice [`Net::first_sup`] samples a cubic's derivative on.
pub const FIRST_GRID: u32 = 4;

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (xorshift) of floats in `[-1, 1]`.
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> f32 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 40) as f32 / (1u64 << 23) as f32 - 1.0
        }

        fn vec(&mut self) -> Vec3 {
            Vec3::new(self.next(), self.next(), self.next())
        }
    }

    /// The least `|P|` on a lattice of `g` segments per side (of the edge's curve).
    fn sampled(net: &Net, edge: Option<usize>, g: u32) -> f32 {
        let mut m = f32::INFINITY;
        for j in 0..=g {
            for i in 0..=g - j {
                let w = [g - i - j, i, j];
                if edge.is_some_and(|k| w[(k + 2) % 3] != 0) {
                    continue;
                }
                m = m.min(net.eval(w.map(|x| x as f32 / g as f32)).length());
            }
        }
        m
    }

    /// A normal-like field: corners unit vectors within `spread` radians of a random axis, the
    /// other points the normalized blends of their corners (as a normal field's control normals
    /// are, near enough).
    fn turning(rng: &mut Rng, degree: usize, spread: f32) -> Net {
        let axis = rng.vec().normalize();
        let corners = [0; 3].map(|_| (axis + rng.vec().normalize() * spread.tan()).normalize());
        Net::from_fn(degree, |w| {
            let s = (0..3).fold(Vec3::ZERO, |s, c| s + corners[c] * w[c] as f32);
            s.normalize()
        })
    }

    /// `min_length` never exceeds the field's least length (a lattice of 192 segments per
    /// side: the true least is at most that), on random nets of each degree, some reaching
    /// the origin, and on turning unit fields. On the turning fields, whose length dips a
    /// little between their corners, it is within 2% of that least where the corners are at
    /// most 0.6 radians from a common axis and within 15% up to 1 radian, elements and edges:
    /// the cells' second-order bound (the corners projected on their mean direction less the
    /// interpolation error), where the corners' lengths less the field's change across a cell
    /// fall a tenth or more short on the coarsest lattice, which is all that is sampled once
    /// the bound passes half the corners' length.
    #[test]
    fn min_length_is_a_tight_lower_bound() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let (mut near, mut far, mut first_order) = (f32::INFINITY, f32::INFINITY, f32::INFINITY);
        for case in 0..300 {
            let degree = 1 + case % 3;
            let spread = 0.2 + 0.8 * (case % 7) as f32 / 6.0;
            let net = if case % 2 == 0 {
                let offset = rng.vec() * (case % 5) as f32 * 0.5;
                let points: Vec<Vec3> = (0..10).map(|_| rng.vec() + offset).collect();
                Net::from_fn(degree, |w| points[Net::index(degree, w)])
            } else {
                turning(&mut rng, degree.max(2), spread)
            };
            for edge in [None, Some(0), Some(1), Some(2)] {
                let truth = sampled(&net, edge, 192);
                let rho = net.min_length(edge);
                assert!(
                    rho <= truth,
                    "case {case} {edge:?}: bound {rho} above the least length {truth}"
                );
                if case % 2 == 0 {
                    continue;
                }
                if spread <= 0.6 {
                    near = near.min(rho / truth);
                    // The first-order bound alone on the coarsest lattice, where a bound
                    // above half the corners' length stops sampling.
                    first_order =
                        first_order.min(net.lattice_min_length(edge, RHO_GRIDS[0], false) / truth);
                } else {
                    far = far.min(rho / truth);
                }
            }
        }
        eprintln!("least ρ / |n| on turning fields: {near} within 0.6 rad, {far} beyond, first order alone on the coarsest lattice {first_order}");
        assert!(near >= 0.98 && far >= 0.85, "{near} {far}");
        assert!(first_order <= 0.9, "{first_order}");
    }

    /// A random PN triangle (Vlachos et al.): corners, normals up to `spread` radians off the
    /// face's, tangent points projected on the corners' planes, the centre pushed out.
    fn pn_triangle(rng: &mut Rng, spread: f32) -> Net {
        let p = [0; 3].map(|_| rng.vec());
        let face = (p[1] - p[0]).cross(p[2] - p[0]).normalize();
        let n = [0; 3].map(|_| (face + rng.vec().normalize() * spread.tan()).normalize());
        let tangent =
            |i: usize, j: usize| (2.0 * p[i] + p[j] - (p[j] - p[i]).dot(n[i]) * n[i]) / 3.0;
        let mut net = Net::from_fn(3, |w| match w {
            [3, 0, 0] => p[0],
            [0, 3, 0] => p[1],
            [0, 0, 3] => p[2],
            [2, 1, 0] => tangent(0, 1),
            [2, 0, 1] => tangent(0, 2),
            [1, 2, 0] => tangent(1, 0),
            [0, 2, 1] => tangent(1, 2),
            [1, 0, 2] => tangent(2, 0),
            [0, 1, 2] => tangent(2, 1),
            _ => Vec3::ZERO,
        });
        let edges = [
            [2, 1, 0],
            [2, 0, 1],
            [1, 2, 0],
            [0, 2, 1],
            [1, 0, 2],
            [0, 1, 2],
        ];
        let e = edges.iter().fold(Vec3::ZERO, |s, &w| s + net.at(w)) / 6.0;
        let v = (p[0] + p[1] + p[2]) / 3.0;
        net.points[Net::index(3, [1, 1, 1])] = e + (e - v) / 2.0;
        net
    }

    /// The largest of `f(w, up, down)` over a lattice of `g` segments a side (the edge's points
    /// with `edge = Some(e)`), `up` and `down` the points `h` along direction `k` either side.
    fn dense_max(
        edge: Option<usize>,
        k: usize,
        g: u32,
        f: impl Fn([f32; 3], [f32; 3], [f32; 3]) -> f32,
    ) -> f32 {
        let (a, b, h) = (k, (k + 1) % 3, 1e-3f32);
        let mut best = 0.0f32;
        for j in 0..=g {
            for i in 0..=g - j {
                let w = [g - i - j, i, j].map(|x| x as f32 / g as f32);
                if edge.is_some_and(|e| w[(e + 2) % 3] != 0.0) {
                    continue;
                }
                let (mut up, mut down) = (w, w);
                (up[b], up[a], down[b], down[a]) = (w[b] + h, w[a] - h, w[b] - h, w[a] + h);
                best = best.max(f(w, up, down));
            }
        }
        best
    }

    /// `first_sup` against the derivative along each direction by central differences on a
    /// lattice of 96 segments a side (the edge's 96 with `edge = Some(k)`), on random PN
    /// triangles from nearly flat to normals 1.2 radians off the face's: never below it, never above `first`, within 2%
    /// of it on some net, and within 3% of it on the median net and direction, where
    /// `first` (the hull of the derivative's net) is looser. The samples alone (the lattice of
    /// `FIRST_GRID` without the chord term) fall below the truth on some nets: the test
    /// would catch a bound without it.
    #[test]
    fn first_sup_is_a_tight_upper_bound() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let (mut tight, mut hulls, mut lowest) = (Vec::new(), Vec::new(), f32::INFINITY);
        for case in 0..200 {
            let spread: f32 = [0.05, 0.3, 0.6, 0.9, 1.2][case % 5];
            let net = pn_triangle(&mut rng, spread);
            for k in 0..3 {
                for edge in [None, Some(k)] {
                    let derivative = |up, down| ((net.eval(up) - net.eval(down)) / 2e-3).length();
                    let truth = dense_max(edge, k, 96, |_, up, down| derivative(up, down));
                    let bound = net.first_sup(k, edge);
                    assert!(
                        bound >= truth * (1.0 - 1e-3),
                        "case {case} k {k} {edge:?}: bound {bound} below the derivative {truth}"
                    );
                    assert!(bound <= net.first(k, edge), "case {case}: above the hull");
                    tight.push(bound / truth);
                    hulls.push(net.first(k, edge) / truth);
                    // The samples alone.
                    let alone = dense_max(edge, k, FIRST_GRID, |_, up, down| derivative(up, down));
                    lowest = lowest.min(alone / truth);
                }
            }
        }
        tight.sort_by(f32::total_cmp);
        hulls.sort_by(f32::total_cmp);
        let median = |v: &[f32]| v[v.len() / 2];
        eprintln!(
            "first_sup / |DP|: least {}, median {}; first: median {}; samples alone: least {lowest}",
            tight[0],
            median(&tight),
            median(&hulls)
        );
        assert!(tight[0] <= 1.02 && median(&tight) <= 1.03, "{tight:?}");
        assert!(median(&hulls) > median(&tight), "the hull is as tight");
        assert!(
            lowest < 0.999,
            "the samples alone never fall short: {lowest}"
        );
    }

    /// `radial_first` against `|(P − o) · DP[d_k]|` by central differences on a lattice of 96
    /// segments a side (the edge's with `edge = Some(k)`), on random PN triangles and points
    /// `o` from beside the patch to far from it: never below it, never above `r_max` times the
    /// derivative's bound, and within 5% of it on some patch. The samples alone (the lattice of
    /// `FIRST_GRID` without the chord term) fall below the truth on some patches: the test would
    /// catch a bound without it.
    #[test]
    fn radial_first_is_an_upper_bound() {
        let mut rng = Rng(0x5851_f42d_4c95_7f2d);
        let (mut tightest, mut lowest) = (f32::INFINITY, f32::INFINITY);
        for case in 0..150 {
            let net = pn_triangle(&mut rng, [0.1, 0.5, 1.0][case % 3]);
            let o = rng.vec() * [0.5, 2.0, 6.0][case % 3];
            let r_max = net
                .hull(None)
                .iter()
                .map(|p| (*p - o).length())
                .fold(0.0, f32::max);
            for k in 0..3 {
                for edge in [None, Some(k)] {
                    let radial = |w, up, down| {
                        let d = (net.eval(up) - net.eval(down)) / 2e-3;
                        (net.eval(w) - o).dot(d).abs()
                    };
                    let truth = dense_max(edge, k, 96, radial);
                    let firsts = [0, 1, 2].map(|j| net.first_sup(j, edge));
                    let bound = net.radial_first(k, edge, o, r_max, firsts);
                    assert!(
                        bound >= truth * (1.0 - 1e-3) - 1e-5,
                        "case {case} k {k} {edge:?}: bound {bound} below {truth}"
                    );
                    assert!(bound <= r_max * net.first_sup(k, edge) * (1.0 + 1e-6));
                    if truth > 1e-3 {
                        tightest = tightest.min(bound / truth);
                        let alone = dense_max(edge, k, FIRST_GRID, radial);
                        lowest = lowest.min(alone / truth);
                    }
                }
            }
        }
        eprintln!("radial_first / sampled: tightest {tightest}; samples alone: least {lowest}");
        assert!(tightest <= 1.05, "{tightest}");
        assert!(
            lowest < 0.999,
            "the samples alone never fall short: {lowest}"
        );
    }

    /// `third` is the largest third directional derivative along any three lattice directions:
    /// on random cubics, the third finite differences of the evaluated patch (exact for a cubic
    /// but for rounding) over every choice of directions reach it and never pass it; zero below
    /// degree 3.
    #[test]
    fn third_is_the_largest_third_derivative() {
        let mut rng = Rng(0x5eed_cafe);
        let dirs = [[-1.0f32, 1.0, 0.0], [0.0, -1.0, 1.0], [1.0, 0.0, -1.0]];
        for _ in 0..40 {
            let points = [0; 10].map(|_| rng.vec());
            let net = Net { degree: 3, points };
            let h = 0.1f32;
            let mut best = 0.0f32;
            for a in 0..3 {
                for b in 0..3 {
                    for c in 0..3 {
                        // Δ_a Δ_b Δ_c P at the centroid, step h: eight evaluations.
                        let mut sum = Vec3::ZERO;
                        for bits in 0..8u32 {
                            let mut w = [1.0f32 / 3.0; 3];
                            let mut sign = -1.0f32;
                            for (i, &k) in [a, b, c].iter().enumerate() {
                                if bits >> i & 1 == 1 {
                                    (0..3).for_each(|j| w[j] += h * dirs[k][j]);
                                    sign = -sign;
                                }
                            }
                            sum += net.eval(w) * sign;
                        }
                        best = best.max(sum.length() / (h * h * h));
                    }
                }
            }
            let third = net.third();
            assert!(
                best <= third * 1.002 && best >= third * 0.998,
                "sampled {best}, bound {third}"
            );
        }
        for degree in 1..3 {
            let points = [0; 10].map(|_| rng.vec());
            assert_eq!(Net { degree, points }.third(), 0.0);
        }
    }
}
