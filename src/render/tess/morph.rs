//! Geomorphing on the tessellator (docs/adaptivity.md, "Geomorphing"): the CPU mirror of
//! `glsl/tess/tess_morph.glsl`.
//!
//! A geomorphing tess draw rounds its levels to powers of two as the pattern driver does
//! ([`morph_levels`]), so that every level's vertices are a subset of the next finer one's, and
//! glides the vertices the finest drawn level adds from their parents' midpoint:
//!
//! - The tessellator draws every side at the inner level `n`, and the vertices of its outer
//!   ring move onto their edge's own samples `k/n_e` ([`snap_ring`]: the pattern driver's
//!   snapping, so the transition triangles are bounded as the pattern's, src/lod/frame/
//!   transitions.rs, `Rounding::TessSnapped`). A sample with `k` odd is new; its parents are
//!   the samples `k ± 1` and it morphs with its edge's continuous level, from exact dyadic
//!   weights, so the two elements sharing the edge draw the same bits (as the pattern's edges
//!   do).
//! - Inside, with equal spacing at an even inner level `n` the tessellator makes concentric
//!   rings: ring `r` is the outer triangle scaled about the centre by `(n − 2r)/n`, cut into
//!   `n − 2r` equal segments a side, so every vertex has barycentric coordinates `K/(3n)` with
//!   integers `K` summing to `3n`, the smallest `2r` (Vulkan spec, "Triangle Tessellation":
//!   each inner corner is where the perpendiculars through the outer ring's first samples
//!   meet). Level `n/2`'s rings are level `n`'s even rings with every other vertex. A vertex new
//!   at `n` is either on an even ring at an odd position (parents: its two ring neighbours) or
//!   on an odd ring, where it is the midpoint of a side or the centre of a parallelogram between
//!   level `n/2`'s rings `(r − 1)/2` and `(r + 1)/2` (parents: a vertex of each, found in
//!   integers: `K ± (6 e_a − 2)` toward ring corner `a` at a corner, and at an even position
//!   toward the nearer of the side's corners `a` and `b`, the diagonal the tessellator draws
//!   (it mirrors its diagonals about the middle of each side); `K ± (3 e_c − 1)` away from the
//!   side opposite corner `c` at an odd position). It morphs with
//!   the element's largest continuous level. A parent on the outer ring (ring 1's vertices) is
//!   taken where the edge draws it: snapped onto the edge's samples and morphing with the edge.
//!   At level 2 the centre's parents are corner 0 and the midpoint of the opposite edge (level
//!   1 has no inside).
//!
//! At `m = 1` every vertex is its true point, bit for bit: levels at powers of two draw what
//! they draw without geomorphing.
#![forbid(unsafe_code)]

use crate::lod::levels::ElementLevels;
use crate::pattern::adaptive::{drawn_levels, morph, morph_factor, snap_edge};
use glam::Vec3;

/// The levels a geomorphing tess draw gives an element with continuous `levels` and largest
/// level `max`: the pattern driver's dyadic levels at the largest power of two at most `max`,
/// as `(outer, inner)`, `outer` the edges' in `gl_TessLevelOuter` order (outer `i` is stored
/// edge `i + 1`); `None`: culled. The tessellator itself draws every side at `inner`, and the
/// outer ring's vertices move onto the edges' own samples ([`snap_ring`]). Mirror of
/// glsl/tess/tess.tesc with `GEOMORPH` (its `tess_edges` and inner level).
pub fn morph_levels(levels: &ElementLevels, max: u32) -> Option<([u32; 3], u32)> {
    let f = 1u32 << (31 - max.max(1).leading_zeros());
    let d = drawn_levels(levels, f, true)?;
    Some(([d.edges[1], d.edges[2], d.edges[0]], d.inner))
}

/// Where a geomorphing tess draw puts the tessellator's vertex `tc` (every side at level
/// `inner`): a vertex of the outer ring on its edge's own samples (`outer`, [`morph_levels`]),
/// the nearest, a tie toward the nearer corner (at an edge's middle toward the stored edge's
/// first corner: `snap_edge`, as the pattern driver's boundary), the rest where the tessellator
/// made them. Mirror of `tess_snap`.
pub fn snap_ring(tc: [f32; 3], outer: [u32; 3], inner: u32) -> [f32; 3] {
    let n = inner;
    let half_step = 0.5 / n as f32;
    let Some(edge) = tc.iter().position(|&c| c < half_step) else {
        return tc;
    };
    let (a, b) = ((edge + 1) % 3, (edge + 2) % 3);
    let s = snap_edge((tc[b] * n as f32).round() as u32, outer[edge], n);
    let mut r = [0.0; 3];
    r[a] = (n - s) as f32 / n as f32;
    r[b] = s as f32 / n as f32;
    r
}

/// The weights a geomorphing tess draw evaluates its vertex `tc` at before morphing: [`snap_ring`],
/// then the edge's integer weights (`tess_weights_levels`), as glsl/tess/tess.tese does.
pub fn morph_weights(tc: [f32; 3], outer: [u32; 3], inner: u32) -> [f32; 3] {
    super::tess_weights_levels(snap_ring(tc, outer, inner), outer, inner)
}

/// The continuous level of patch edge `i` (stored edge `i + 1`).
fn edge_lambda(levels: &ElementLevels, i: usize) -> f32 {
    levels.edges[(i + 1) % 3]
}

/// How one tessellator vertex morphs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TessMorph {
    /// Drawn at its true point.
    Still,
    /// On patch edge `edge`, at (snapped) weights `w`: the edge rule.
    Edge { edge: usize, w: [f32; 3] },
    /// Inside, between parent `a` (on patch edge `a_edge`: snapped there and drawn by the edge
    /// rule) and parent `b` (a true point), with factor `m`.
    Inner {
        a: [f32; 3],
        a_edge: Option<usize>,
        b: [f32; 3],
        m: f32,
    },
}

/// A point on patch edge `edge` at weights `w` (multiples of `1/n_e`): its parents on the edge
/// and its factor when it is new at the edge's level and not yet in place, else `None`.
/// Mirror of `tess_edge_parents`.
pub fn edge_parents(
    w: [f32; 3],
    edge: usize,
    outer: [u32; 3],
    levels: &ElementLevels,
) -> Option<([f32; 3], [f32; 3], f32)> {
    let ne = outer[edge];
    if ne <= 1 {
        return None;
    }
    let (a, b) = ((edge + 1) % 3, (edge + 2) % 3);
    let kb = (w[b] * ne as f32).round() as u32;
    if kb % 2 == 0 {
        return None;
    }
    let m = morph_factor(edge_lambda(levels, edge), ne);
    if m >= 1.0 {
        return None;
    }
    let at = |k: u32| {
        let mut q = [0.0; 3];
        q[a] = (ne - k) as f32 / ne as f32;
        q[b] = k as f32 / ne as f32;
        q
    };
    Some((at(kb - 1), at(kb + 1), m))
}

/// How the vertex at `tc = gl_TessCoord` (weights `w`, [`morph_weights`]) of an
/// element drawn geomorphing at `(outer, inner)` ([`morph_levels`]) with continuous `levels`
/// morphs. Mirror of `tess_morph_classify`.
pub fn classify(
    tc: [f32; 3],
    w: [f32; 3],
    outer: [u32; 3],
    inner: u32,
    levels: &ElementLevels,
) -> TessMorph {
    let n = inner;
    let half_step = 0.5 / n as f32;
    if let Some(edge) = tc.iter().position(|&c| c < half_step) {
        return TessMorph::Edge { edge, w };
    }
    if n <= 1 {
        return TessMorph::Still;
    }
    let lambda = levels.edges.iter().copied().fold(levels.inner, f32::max);
    let m = morph_factor(lambda, n);
    if m >= 1.0 {
        return TessMorph::Still;
    }
    let s = 3 * n as i32;
    let k = tc.map(|c| (c * s as f32).round() as i32);
    let (a, b) = if n == 2 {
        // The centre: level 1 has no inside.
        ([0, 3, 3], [6, 0, 0])
    } else {
        let kmin = k[0].min(k[1]).min(k[2]);
        let r = kmin / 2;
        if 2 * r == n as i32 {
            return TessMorph::Still; // the centre: level n/2's too
        }
        let at_min = k.map(|x| x == kmin);
        let corner = (at_min.iter().filter(|&&x| x).count() >= 2)
            .then(|| (0..3).max_by_key(|&i| k[i]).unwrap());
        let c = at_min.iter().position(|&x| x).unwrap();
        let (ea, eb) = ((c + 1) % 3, (c + 2) % 3);
        let j = (k[eb] - kmin) / 3;
        let unit = |i: usize, x: i32, rest: i32| -> [i32; 3] {
            std::array::from_fn(|q| if q == i { x + rest } else { rest })
        };
        let d = if r % 2 == 0 {
            if corner.is_some() || j % 2 == 0 {
                return TessMorph::Still;
            }
            let mut d = [0; 3];
            d[ea] = -3;
            d[eb] = 3;
            d
        } else if let Some(q) = corner {
            unit(q, 6, -2)
        } else if j % 2 == 0 {
            // A parallelogram's centre: the diagonal the tessellator draws runs toward the
            // nearer ring corner (it mirrors its diagonals about the middle of each side).
            unit(if 2 * j < n as i32 - 2 * r { ea } else { eb }, 6, -2)
        } else {
            unit(c, 3, -1)
        };
        let p: [i32; 3] = std::array::from_fn(|i| k[i] + d[i]);
        let q: [i32; 3] = std::array::from_fn(|i| k[i] - d[i]);
        // Parent a: the outer one (the smaller least coordinate).
        if p.iter().min() <= q.iter().min() {
            (p, q)
        } else {
            (q, p)
        }
    };
    let weights = |k: [i32; 3]| k.map(|x| x as f32 / s as f32);
    let (wa, a_edge) = match a.iter().position(|&x| x == 0) {
        Some(i) => {
            // On patch edge i: snapped onto the edge's samples.
            let (ea, eb) = ((i + 1) % 3, (i + 2) % 3);
            let ne = outer[i];
            let kb = snap_edge((a[eb] / 3) as u32, ne, n) / (n / ne);
            let mut q = [0.0; 3];
            q[ea] = (ne - kb) as f32 / ne as f32;
            q[eb] = kb as f32 / ne as f32;
            (q, Some(i))
        }
        None => (weights(a), None),
    };
    TessMorph::Inner {
        a: wa,
        a_edge,
        b: weights(b),
        m,
    }
}

/// Where the geomorphing tess driver draws the vertex at `tc` (weights `w`, true position `p`);
/// `eval` is the surface at weights. Mirror of `tess_geomorph_position`.
pub fn geomorph_position(
    tc: [f32; 3],
    w: [f32; 3],
    p: Vec3,
    outer: [u32; 3],
    inner: u32,
    levels: &ElementLevels,
    eval: &dyn Fn([f32; 3]) -> Vec3,
) -> Vec3 {
    let edge_drawn = |w: [f32; 3], edge: usize, pw: Vec3| match edge_parents(w, edge, outer, levels)
    {
        Some((qa, qb, m)) => morph(eval(qa), eval(qb), pw, m),
        None => pw,
    };
    match classify(tc, w, outer, inner, levels) {
        TessMorph::Still => p,
        TessMorph::Edge { edge, w } => edge_drawn(w, edge, p),
        TessMorph::Inner { a, a_edge, b, m } => {
            let pa = match a_edge {
                Some(e) => edge_drawn(a, e, eval(a)),
                None => eval(a),
            };
            morph(pa, eval(b), p, m)
        }
    }
}

/// The parameter the vertex at `tc` (weights `w`) stands for while geomorphing: its weights
/// blended as [`geomorph_position`] blends its position (the drawn mesh is linear in them).
pub fn geomorph_weights(
    tc: [f32; 3],
    w: [f32; 3],
    outer: [u32; 3],
    inner: u32,
    levels: &ElementLevels,
) -> [f32; 3] {
    let blend = |a: [f32; 3], b: [f32; 3], p: [f32; 3], m: f32| -> [f32; 3] {
        std::array::from_fn(|k| {
            let mid = (a[k] as f64 + b[k] as f64) * 0.5;
            (mid + (p[k] as f64 - mid) * m as f64) as f32
        })
    };
    let edge_drawn = |w: [f32; 3], edge: usize| match edge_parents(w, edge, outer, levels) {
        Some((qa, qb, m)) => blend(qa, qb, w, m),
        None => w,
    };
    match classify(tc, w, outer, inner, levels) {
        TessMorph::Still => w,
        TessMorph::Edge { edge, w } => edge_drawn(w, edge),
        TessMorph::Inner { a, a_edge, b, m } => {
            let qa = match a_edge {
                Some(e) => edge_drawn(a, e),
                None => a,
            };
            blend(qa, b, w, m)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tessellator's vertices at even level `n` (every level `n`): the rings of the Vulkan
    /// spec's construction, as integers `K` (weights `K/(3n)`).
    fn rings(n: u32) -> Vec<[i32; 3]> {
        let s = 3 * n as i32;
        let mut out = vec![];
        for r in 0..=(n / 2) as i32 {
            let m = n as i32 - 2 * r;
            if m == 0 {
                out.push([s / 3; 3]);
                continue;
            }
            for c in 0..3 {
                let (a, b) = ((c + 1) % 3, (c + 2) % 3);
                for j in 0..m {
                    let mut k = [0; 3];
                    k[c] = 2 * r;
                    k[b] = 2 * r + 3 * j;
                    k[a] = s - k[b] - k[c];
                    out.push(k);
                }
            }
        }
        out
    }

    fn weights(k: [i32; 3], n: u32) -> [f32; 3] {
        k.map(|x| x as f32 / (3 * n) as f32)
    }

    /// Every vertex new at level `n` has two parents that are vertices of level `n/2` (a parent
    /// on the outer ring: a sample of its edge), whose midpoint it is; old vertices stay.
    #[test]
    fn parents_are_coarser_vertices_around_the_new_ones() {
        for n in [2u32, 4, 8, 16] {
            let fine = rings(n);
            let coarse: std::collections::HashSet<[i32; 3]> =
                rings(n / 2).into_iter().map(|k| k.map(|x| 2 * x)).collect();
            let levels = ElementLevels::uniform(n as f32 * 0.6);
            let outer = [n; 3];
            let mut new = 0;
            for k in fine {
                let tc = weights(k, n);
                let w = super::super::tess_weights_levels(tc, outer, n);
                match classify(tc, w, outer, n, &levels) {
                    TessMorph::Still => {
                        assert!(coarse.contains(&k) || n == 2 && k == [2; 3], "{n}: {k:?}")
                    }
                    TessMorph::Edge { edge, w } => {
                        assert_eq!(w[edge], 0.0);
                        let p = edge_parents(w, edge, outer, &levels);
                        assert_eq!(p.is_some(), !coarse.contains(&k), "{n}: {k:?}");
                    }
                    TessMorph::Inner { a, b, .. } => {
                        new += 1;
                        assert!(!coarse.contains(&k), "{n}: {k:?}");
                        let s = (3 * n) as f32;
                        let ka = a.map(|x| (x * s).round() as i32);
                        let kb = b.map(|x| (x * s).round() as i32);
                        if n > 2 {
                            assert!(coarse.contains(&ka) && coarse.contains(&kb), "{n}: {k:?}");
                            assert_eq!([0, 1, 2].map(|i| ka[i] + kb[i]), k.map(|x| 2 * x));
                        }
                    }
                }
            }
            assert!(new > 0, "level {n}");
        }
    }

    /// The outer ring, drawn at the inner level, lands on each edge's own samples: every
    /// sample of the edge reached, none between them, no vertex moved by more than half a
    /// sample, the vertices beside a corner onto it where the edge is at most half the inner
    /// level (but at level 2); the inside stays where the tessellator made it.
    #[test]
    fn snap_ring_puts_the_outer_ring_on_the_edges_samples() {
        for n in [2u32, 4, 8, 16] {
            for outer in [[n; 3], [n / 2, n, 1], [1, (n / 4).max(1), n / 2]] {
                let mut reached = [(); 3].map(|_| std::collections::BTreeSet::new());
                for k in rings(n) {
                    let tc = weights(k, n);
                    let r = snap_ring(tc, outer, n);
                    let Some(edge) = k.iter().position(|&x| x == 0) else {
                        assert_eq!(r, tc);
                        continue;
                    };
                    let (a, b) = ((edge + 1) % 3, (edge + 2) % 3);
                    let ne = outer[edge];
                    let s = r[b] * ne as f32;
                    assert_eq!(s, s.round(), "{n} {outer:?}: {k:?} -> {r:?}");
                    assert_eq!(r[a] + r[b], 1.0);
                    assert!((r[b] - tc[b]).abs() <= 0.5 / ne as f32 + 1e-6, "{k:?}");
                    let beside = k[b] == 3 || k[a] == 3;
                    if beside && n >= 4 && 2 * ne <= n {
                        assert!(r[a] == 1.0 || r[b] == 1.0, "{n} {outer:?}: {k:?} -> {r:?}");
                    }
                    reached[edge].insert(s as u32);
                }
                for e in 0..3 {
                    // The corner where two edges meet is found on the first of them.
                    let want: Vec<u32> = (0..=outer[e]).collect();
                    let got: Vec<u32> = reached[e].iter().copied().collect();
                    let inner: Vec<u32> = want[1..want.len() - 1].to_vec();
                    assert!(
                        inner.iter().all(|x| got.contains(x)),
                        "{n} {outer:?} edge {e}: {got:?}"
                    );
                    assert!(
                        got.iter().all(|x| want.contains(x)),
                        "{n} {outer:?} edge {e}: {got:?}"
                    );
                }
            }
        }
    }

    /// At whole levels nothing moves; just past half a level new vertices sit at their
    /// parents' midpoint.
    #[test]
    fn morph_ends() {
        let n = 8;
        let eval = |b: [f32; 3]| Vec3::new(b[1], b[2], b[1] * b[1] + 3.0 * b[2] * b[0]);
        for k in rings(n) {
            let tc = weights(k, n);
            let l = ElementLevels::uniform(8.0);
            let (outer, inner) = morph_levels(&l, 64).unwrap();
            let w = morph_weights(tc, outer, inner);
            let p = eval(w);
            assert_eq!(geomorph_position(tc, w, p, outer, inner, &l, &eval), p);
            assert_eq!(geomorph_weights(tc, w, outer, inner, &l), w);
            let l = ElementLevels::uniform(4.0 + 1e-5);
            let (outer, inner) = morph_levels(&l, 64).unwrap();
            assert_eq!((outer, inner), ([8; 3], 8));
            let got = geomorph_position(tc, w, p, outer, inner, &l, &eval);
            let gw = geomorph_weights(tc, w, outer, inner, &l);
            // A linear function of the weights morphs as its parameter does.
            let lin = |b: [f32; 3]| Vec3::new(b[1], b[2], 0.0);
            assert!((Vec3::new(got.x, got.y, 0.0) - lin(gw)).length() < 1e-5);
        }
    }

    #[test]
    fn morph_levels_are_dyadic() {
        let l = ElementLevels {
            edges: [3.0, 1.0, 9.0],
            inner: 5.0,
        };
        assert_eq!(morph_levels(&l, 64), Some(([1, 16, 4], 16)));
        assert_eq!(morph_levels(&l, 12), Some(([1, 8, 4], 8)));
        assert_eq!(morph_levels(&ElementLevels::CULLED, 64), None);
    }
}
