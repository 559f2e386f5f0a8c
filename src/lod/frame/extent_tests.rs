//! The transition triangles' extents (src/lod/frame/transitions.rs, "Extents") against every
//! triangle the pattern driver draws.

use super::*;

/// A side's extent in lattice coordinates, `min Σ |c_k|` over `δ = Σ c_k d_k` (the three
/// directions summing to zero): with `δ = y − x` in weights, `c = (−δ0, δ2, 0) + t (1, 1, 1)`,
/// so the sum's minimum is the spread of those three numbers.
fn lattice_extent(x: [f32; 3], y: [f32; 3]) -> f32 {
    let c = [x[0] - y[0], y[2] - x[2], 0.0];
    let (lo, hi) = c
        .iter()
        .fold((0.0f32, 0.0f32), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    hi - lo
}

/// The extents the transition triangles' kink and cubic terms are taken at
/// (src/lod/frame/transitions.rs, "Extents") hold for what the pattern driver draws: at
/// integer levels and at powers of two, every triangle with a vertex moved from a coarser edge
/// `e` has sides spanning at most `max(a_e, a_e/2 + β)` in lattice coordinates (with vertices
/// moved from two coarser edges, a corner's at integer levels, the coarser edge's `a`; at
/// powers of two both edges' extents), every other one a lattice side `β`; and the bound is
/// reached.
#[test]
fn snapped_transition_sides_span_what_their_extent_allows() {
    use crate::pattern::adaptive::adaptive_element;
    use std::collections::HashMap;
    let f = 16u32;
    let (mut checked, mut reached) = (0u64, 0u64);
    for dyadic in [false, true] {
        let levels: Vec<u32> = if dyadic {
            vec![1, 2, 4, 8, 16]
        } else {
            (1..=12).collect()
        };
        for &n in &levels {
            let below: Vec<u32> = levels.iter().copied().filter(|&m| m <= n).collect();
            for &e0 in &below {
                for &e1 in &below {
                    for &e2 in &below {
                        let edges = [e0, e1, e2];
                        let l = ElementLevels {
                            edges: edges.map(|e| e as f32),
                            inner: n as f32,
                        };
                        let el = adaptive_element(&l, f, dyadic).unwrap();
                        assert_eq!(el.levels.inner, n);
                        let at: HashMap<u32, ([f32; 3], (u32, u32))> = (el.vertices.iter())
                            .copied()
                            .zip(el.bary.iter().copied().zip(el.points.iter().copied()))
                            .collect();
                        // The lattice the points are given on (the finest drawn level's where
                        // dyadic), and the coarser edges a point moved from (its edge before
                        // snapping: stored edge 0 `j = 0`, 1 `i + j = N`, 2 `i = 0`; a corner
                        // stays).
                        let scale = if dyadic { f } else { n };
                        let moved_from = |(i, j): (u32, u32)| {
                            let on = [j == 0, i + j == scale, i == 0];
                            let corner = on.iter().filter(|&&x| x).count() > 1;
                            (0..3).filter(move |&k| on[k] && !corner && edges[k] < n)
                        };
                        let beta = 1.0 / n as f32;
                        for t in &el.triangles {
                            let w = t.map(|k| at[&k].0);
                            if w[0] == w[1] || w[1] == w[2] || w[0] == w[2] {
                                continue;
                            }
                            let extent = [(0, 1), (1, 2), (2, 0)]
                                .map(|(x, y)| lattice_extent(w[x], w[y]))
                                .into_iter()
                                .fold(0.0, f32::max);
                            // A triangle with points moved from two coarser edges: the coarser
                            // edge's `a` at integer levels, both edges' extents at powers of two.
                            let from: Vec<f32> = (0..3)
                                .filter(|&k| t.iter().any(|v| moved_from(at[v].1).any(|e| e == k)))
                                .map(|k| 1.0 / edges[k] as f32)
                                .collect();
                            let extent_of = |a: f32| a.max(0.5 * a + beta);
                            let allowed = match from[..] {
                                [] => beta,
                                [a] => extent_of(a),
                                _ if dyadic => {
                                    from.iter().map(|&a| extent_of(a)).fold(1.0, f32::min)
                                }
                                _ => from.iter().fold(beta, |m, &a| m.max(a)),
                            };
                            assert!(
                                extent <= allowed * (1.0 + 1e-5),
                                "inner {n}, edges {edges:?} ({}): {w:?} spans {extent} > {allowed}",
                                if dyadic { "dyadic" } else { "integer" }
                            );
                            checked += 1;
                            if extent >= 0.999 * allowed && allowed > beta {
                                reached += 1;
                            }
                        }
                    }
                }
            }
        }
    }
    assert!(
        checked > 100_000 && reached > 1000,
        "{checked} triangles, {reached} at the bound"
    );
}
