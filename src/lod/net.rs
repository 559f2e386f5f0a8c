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
}
