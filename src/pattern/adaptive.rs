//! Hierarchical dyadic patterns for adaptive drawing (Schwarz et al. 2006, §3: the vertices of
//! every coarser 1-to-4 pattern are a subset of the finest one's, so one vertex buffer of the
//! finest level `F = 2^L` and one index range per level `2^l`, `l = 0..=L`, indexing into it) and
//! the CPU mirror of what the adaptive pattern driver draws for one element: its drawn levels,
//! the weights of every vertex it draws (boundary vertices snapped onto their edge's level) and
//! its triangles. docs/adaptivity.md, "How cracks are excluded", has the argument.
//!
//! Every weight here is `k / 2^l`, exactly representable: the hierarchy's `(w, u, v)` are the
//! finest uniform pattern's (in hierarchical order), and a snapped weight is again a multiple of
//! `1/F`.
#![forbid(unsafe_code)]

use super::{index_count, lattice_index, weight, Pattern};
use crate::lod::levels::{drawn_level, ElementLevels};
use glam::Vec3;

/// The levels one element is drawn with: its three stored edges' and its inner level, at most
/// the frame's largest level (powers of two for the hierarchical patterns), each edge at most
/// the inner level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DrawnLevels {
    pub edges: [u32; 3],
    pub inner: u32,
}

/// The levels the adaptive pattern driver draws `levels` with at largest level `max` (a power
/// of two), powers of two where `dyadic` (the hierarchical patterns, while geomorphing), else
/// any integer (the integer patterns); `None`: culled. Mirror of `adaptive_levels` in
/// glsl/pattern/adaptive.glsl. The inner level is raised to the largest edge level (a level
/// pass promises it; raising it keeps a wrong one from opening a crack) and an edge level is at
/// least 1.
pub fn drawn_levels(levels: &ElementLevels, max: u32, dyadic: bool) -> Option<DrawnLevels> {
    let inner = drawn_level(levels.inner, dyadic, max);
    if inner == 0 {
        return None;
    }
    let edges = levels.edges.map(|e| drawn_level(e, dyadic, max).max(1));
    let inner = edges.iter().copied().fold(inner, u32::max);
    Some(DrawnLevels { edges, inner })
}

/// Parameter `a` (in units of `1/f`) along an edge drawn at level `n` snapped onto that edge's
/// samples, multiples of `f/n`: the nearest one, a tie going toward the nearer corner (to the
/// smaller at the middle), so that a point beside a corner snaps onto it (unless it is the
/// middle itself) and no transition triangle spans two edges' samples
/// (src/lod/frame/transitions.rs). Mirror of `snap_edge` in
/// glsl/pattern/adaptive.glsl.
pub fn snap_edge(a: u32, n: u32, f: u32) -> u32 {
    let r = f / n;
    let up = if 2 * a > f { r } else { r - 1 };
    (2 * a + up) / (2 * r) * r
}

/// The sample of an edge drawn at level `m` that lattice parameter `a/n` (`m <= n`) snaps to,
/// as [`snap_edge`] snaps (the nearest, a tie toward the nearer corner, to the smaller at the
/// middle), for any integer levels: its index `k`, the sample being `k/m`. Mirror of
/// `snap_sample` in glsl/pattern/adaptive.glsl.
pub fn snap_sample(a: u32, m: u32, n: u32) -> u32 {
    let down = u32::from(2 * a <= n);
    (2 * a * m + n - down) / (2 * n)
}

/// The weights the integer patterns draw lattice point `(i, j)` of an element's inner level
/// `d.inner` at: on stored edge `k` (as [`edge_of`] classifies it), the sample of the edge's
/// level `d.edges[k]` it snaps to ([`snap_sample`]), `(m − s)/m` for corner `k` and `s/m` for
/// corner `k + 1`, each divided as written (the two elements sharing the edge divide the same
/// integers; a corner exactly 1 and 0); inside, the uniform pattern's `(n − i − j)/n, i/n, j/n`. Mirror of
/// `integer_weights` in glsl/pattern/adaptive.glsl.
pub fn integer_bary(i: u32, j: u32, d: &DrawnLevels) -> [f32; 3] {
    let n = d.inner;
    let Some(k) = edge_of(i, j, n) else {
        return [weight(n - i - j, n), weight(i, n), weight(j, n)];
    };
    // The parameter from corner k (edge 0: i; edge 1: j; edge 2: n - j).
    let a = [i, j, n - j][k];
    let m = d.edges[k];
    let s = snap_sample(a, m, n);
    let mut b = [0.0f32; 3];
    // The corners exactly (a device may divide m by m inexactly, and a corner's edges
    // have different levels in different elements).
    (b[k], b[(k + 1) % 3]) = match s {
        0 => (1.0, 0.0),
        s if s == m => (0.0, 1.0),
        s => ((m - s) as f32 / m as f32, s as f32 / m as f32),
    };
    b
}

/// The integer patterns for adaptive drawing without geomorphing: every level `1..=f`'s uniform
/// pattern, its vertices (weights) after the previous levels' and its triangles (indices local
/// to its own vertices) after theirs, drawn with a vertex offset ([`IntegerPatterns::base_vertex`]).
#[derive(Clone, Debug, PartialEq)]
pub struct IntegerPatterns {
    pub level: u32,
    pub bary: Vec<[f32; 3]>,
    pub indices: Vec<u32>,
}

impl IntegerPatterns {
    /// Levels `1..=f`.
    pub fn new(f: u32) -> Self {
        let mut bary = Vec::with_capacity(Self::base_vertex(f + 1) as usize);
        let mut indices = Vec::with_capacity(Self::first_index(f + 1) as usize);
        for n in 1..=f {
            let p = Pattern::uniform(n);
            bary.extend(p.bary);
            indices.extend(p.indices);
        }
        Self {
            level: f,
            bary,
            indices,
        }
    }

    /// First index of level `n`'s triangles: `3 (1² + ... + (n − 1)²)`.
    pub const fn first_index(n: u32) -> u32 {
        (n - 1) * n * (2 * n - 1) / 2
    }

    /// First vertex of level `n`: the vertices of levels `1..n`, `n (n + 1)(n + 2)/6 − 1`.
    pub const fn base_vertex(n: u32) -> u32 {
        n * (n + 1) * (n + 2) / 6 - 1
    }
}

/// Vertices and indices the adaptive draws up to `f` store: at powers of two (`dyadic`) the
/// [`Hierarchy`]'s (the finest level's vertices, every level's index range), else every integer
/// level's pattern ([`IntegerPatterns`]).
pub const fn adaptive_stored(f: u32, dyadic: bool) -> (u64, u64) {
    if dyadic {
        let levels = f.trailing_zeros() + 1;
        (
            super::vertex_count(f) as u64,
            Hierarchy::first_index(levels) as u64,
        )
    } else {
        let next = f + 1;
        (
            IntegerPatterns::base_vertex(next) as u64,
            IntegerPatterns::first_index(next) as u64,
        )
    }
}

/// Lattice point `(i, j)` of the finest level `f` moved onto its edge's samples where it lies on
/// a stored edge (edge 0: `j = 0`, measured from corner 0; edge 1: `i + j = f`, from corner 1;
/// edge 2: `i = 0`, from corner 2); interior points stay. Mirror of `adaptive_snap`.
pub fn snap(i: u32, j: u32, levels: &DrawnLevels, f: u32) -> (u32, u32) {
    if j == 0 {
        (snap_edge(i, levels.edges[0], f), 0)
    } else if i + j == f {
        let j = snap_edge(j, levels.edges[1], f);
        (f - j, j)
    } else if i == 0 {
        (0, f - snap_edge(f - j, levels.edges[2], f))
    } else {
        (i, j)
    }
}

/// The finest lattice's weights `(w, u, v)` of `(i, j)`.
pub fn bary(i: u32, j: u32, f: u32) -> [f32; 3] {
    [weight(f - i - j, f), weight(i, f), weight(j, f)]
}

/// The hierarchy of dyadic patterns up to level `f = 2^L`: the finest pattern's vertices in
/// hierarchical order ([`hierarchy_vertex`]: level `2^l`'s vertices are the first
/// `vertex_count(2^l)`), then level `2^l`'s triangles (the uniform pattern's, in its order)
/// indexing them, level after level. A level's draw then reads only its own vertices, the first
/// ones, near one another (on lavapipe, draws whose few indices were spread over the whole
/// finest pattern shaded far more vertices than they used: docs/bench/hierarchy-order.md).
#[derive(Clone, Debug, PartialEq)]
pub struct Hierarchy {
    pub level: u32,
    /// The finest lattice's points `(i, j)` in hierarchical order, and their weights.
    pub points: Vec<(u32, u32)>,
    pub bary: Vec<[f32; 3]>,
    pub indices: Vec<u32>,
}

impl Hierarchy {
    /// The hierarchy up to `f`, a power of two.
    pub fn new(f: u32) -> Self {
        assert!(
            f.is_power_of_two(),
            "hierarchical patterns need a power of two"
        );
        // Level after level, the points it adds (an odd coordinate of its own lattice), in its
        // lattice order.
        let mut points = Vec::with_capacity(super::vertex_count(f) as usize);
        for l in 0..=f.trailing_zeros() {
            let (n, s) = (1u32 << l, f >> l);
            let p = Pattern::uniform(n);
            let new = p.lattice().filter(|&(i, j)| n == 1 || (i | j) % 2 == 1);
            points.extend(new.map(|(i, j)| (i * s, j * s)));
        }
        let bary = points.iter().map(|&(i, j)| bary(i, j, f)).collect();
        let mut indices = Vec::with_capacity(Self::first_index(f.trailing_zeros() + 1) as usize);
        for l in 0..=f.trailing_zeros() {
            indices.extend(Self::level_indices(f, 1 << l));
        }
        Self {
            level: f,
            points,
            bary,
            indices,
        }
    }

    /// Level `n`'s triangle list with indices into the finest level `f`'s vertices in
    /// hierarchical order ([`hierarchy_vertex`]).
    pub fn level_indices(f: u32, n: u32) -> Vec<u32> {
        let s = f / n;
        let p = Pattern::uniform(n);
        let lattice: Vec<(u32, u32)> = p.lattice().collect();
        p.indices
            .iter()
            .map(|&k| {
                let (i, j) = lattice[k as usize];
                hierarchy_vertex(f, i * s, j * s)
            })
            .collect()
    }

    /// First index of level `2^l`'s range: `3 (4^0 + ... + 4^(l-1)) = 4^l - 1`.
    pub const fn first_index(l: u32) -> u32 {
        (1u32 << (2 * l)) - 1
    }

    /// The index range of level `n` (a power of two up to the hierarchy's).
    pub fn range(n: u32) -> std::ops::Range<u32> {
        let first = Self::first_index(n.trailing_zeros());
        first..first + index_count(n)
    }
}

/// Where point `(i, j)` of the finest lattice (level `f`, a power of two) is among the
/// [`Hierarchy`]'s vertices: the corners first, then each level `n = 2, 4, ..., f` the points it
/// adds to level `n / 2`'s (those with an odd coordinate on its own lattice), in its lattice
/// order, so that level `n`'s points are the first `vertex_count(n)`.
pub fn hierarchy_vertex(f: u32, i: u32, j: u32) -> u32 {
    // The coarsest level the point is on: `n = f / 2^t`, at `(i, j) / 2^t` of its lattice.
    let t = (i | j).trailing_zeros().min(f.trailing_zeros());
    let (n, ci, cj) = (f >> t, i >> t, j >> t);
    if n == 1 {
        return lattice_index(1, ci, cj);
    }
    // Level n / 2's points before (ci, cj) in level n's lattice order: both coordinates even,
    // (n - r)/2 + 1 of them on each even row r < cj, and (ci + 1)/2 before it on an even row.
    let rows = cj.div_ceil(2);
    let mut old = rows * (n / 2 + 1) - rows * rows.saturating_sub(1) / 2;
    if cj % 2 == 0 {
        old += ci.div_ceil(2);
    }
    super::vertex_count(n / 2) + lattice_index(n, ci, cj) - old
}

/// What the adaptive pattern driver draws for one element at largest level `f`.
#[derive(Clone, Debug, PartialEq)]
pub struct AdaptiveElement {
    pub levels: DrawnLevels,
    /// The vertices the element's inner level draws (the [`Hierarchy`]'s, or the
    /// [`IntegerPatterns`]'), and each one's weights after snapping (`bary[k]` belongs to `vertices[k]`).
    pub vertices: Vec<u32>,
    pub bary: Vec<[f32; 3]>,
    /// Each vertex's finest-lattice point `(i, j)` before snapping (what
    /// [`geomorph_position`] takes).
    pub points: Vec<(u32, u32)>,
    /// The triangles, indices into the same vertices (the draw's order). Where snapping
    /// welds two corners of a triangle it is degenerate (zero area): an exporter drops it.
    pub triangles: Vec<[u32; 3]>,
}

/// The CPU mirror of one element drawn adaptively with `levels` at largest level `f` (a power
/// of two), at powers of two where `dyadic` ([`dyadic_element`]) else at integer levels
/// ([`integer_element`]); `None`: culled, nothing drawn.
pub fn adaptive_element(levels: &ElementLevels, f: u32, dyadic: bool) -> Option<AdaptiveElement> {
    if dyadic {
        dyadic_element(levels, f)
    } else {
        integer_element(levels, f)
    }
}

/// One element drawn from the integer patterns ([`IntegerPatterns`]): vertices numbered in
/// the patterns' vertex buffer, weights from [`integer_bary`], `points` its inner level's
/// lattice points.
pub fn integer_element(levels: &ElementLevels, f: u32) -> Option<AdaptiveElement> {
    let d = drawn_levels(levels, f, false)?;
    let n = d.inner;
    let base = IntegerPatterns::base_vertex(n);
    let p = Pattern::uniform(n);
    let points: Vec<(u32, u32)> = p.lattice().collect();
    Some(AdaptiveElement {
        levels: d,
        vertices: (0..points.len() as u32).map(|k| base + k).collect(),
        bary: points
            .iter()
            .map(|&(i, j)| integer_bary(i, j, &d))
            .collect(),
        points,
        triangles: p.triangles().iter().map(|t| t.map(|k| base + k)).collect(),
    })
}

/// One element drawn from the hierarchical patterns ([`Hierarchy`]).
pub fn dyadic_element(levels: &ElementLevels, f: u32) -> Option<AdaptiveElement> {
    let d = drawn_levels(levels, f, true)?;
    let s = f / d.inner;
    let mut vertices = Vec::new();
    let mut out = Vec::new();
    let mut points = Vec::new();
    for j in 0..=d.inner {
        for i in 0..=(d.inner - j) {
            let (fi, fj) = (i * s, j * s);
            vertices.push(hierarchy_vertex(f, fi, fj));
            points.push((fi, fj));
            let (si, sj) = snap(fi, fj, &d, f);
            out.push(bary(si, sj, f));
        }
    }
    let triangles = Hierarchy::level_indices(f, d.inner)
        .chunks_exact(3)
        .map(|t| [t[0], t[1], t[2]])
        .collect();
    Some(AdaptiveElement {
        levels: d,
        vertices,
        bary: out,
        points,
        triangles,
    })
}

/// Geomorphing (docs/adaptivity.md, "Geomorphing"): the morph factor of a vertex that drawn
/// level `n` (a power of two) adds to level `n / 2`, for continuous level `lambda`:
/// `clamp((4 − (n/λ)²) / 3, 0, 1)`, 0 where `λ` just passed `n / 2`, 1 at `λ = n`. Level 1 adds
/// nothing (1). Mirror of `morph_factor` in glsl/pattern/adaptive.glsl.
pub fn morph_factor(lambda: f32, n: u32) -> f32 {
    if n <= 1 {
        return 1.0;
    }
    let x = n as f32 / lambda;
    ((4.0 - x * x) / 3.0).clamp(0.0, 1.0)
}

/// A morphing vertex between its parents' midpoint (`m = 0`) and its true position `p`
/// (`m = 1`, exactly `p`). The parents' sum is commutative, so the two elements sharing an edge,
/// which may name an edge vertex's parents in either order, compute the same bits. Mirror of
/// `morph` (GLSL, `precise`).
pub fn morph(pa: Vec3, pb: Vec3, p: Vec3, m: f32) -> Vec3 {
    if m >= 1.0 {
        return p;
    }
    let mid = (pa + pb) * 0.5;
    mid + (p - mid) * m
}

/// Whether finest-lattice point `(i, j)` is new at the level of lattice step `s` (not a point
/// of the level with step `2s`).
pub fn is_new(i: u32, j: u32, s: u32) -> bool {
    (i / s) % 2 == 1 || (j / s) % 2 == 1
}

/// The two points of the level with step `2s` whose midpoint is `(i, j)` (new at step `s`): along
/// `u` (`i / s` odd), along `v` (`j / s` odd) or along the third lattice direction (both odd),
/// the edge of the coarser lattice triangle that the 1-to-4 split halves.
pub fn parents(i: u32, j: u32, s: u32) -> [(u32, u32); 2] {
    match ((i / s) % 2 == 1, (j / s) % 2 == 1) {
        (true, false) => [(i - s, j), (i + s, j)],
        (false, true) => [(i, j - s), (i, j + s)],
        _ => [(i - s, j + s), (i + s, j - s)],
    }
}

/// The stored edge finest-lattice point `(i, j)` lies on, as [`snap`] classifies it (a corner
/// counts as on the first edge tested); `None` inside.
pub fn edge_of(i: u32, j: u32, f: u32) -> Option<usize> {
    if j == 0 {
        Some(0)
    } else if i + j == f {
        Some(1)
    } else if i == 0 {
        Some(2)
    } else {
        None
    }
}

/// Where the geomorphing driver draws finest-lattice point `(i, j)` (before snapping) of an
/// element with continuous `levels`, drawn at `d`, largest level `f`; `eval` is the surface at
/// weights. A boundary point is its snapped sample, morphing with its edge's level when that
/// sample is new at the edge's drawn level; an interior point new at the inner level morphs
/// between its parents' drawn positions (a boundary parent snapped and morphing with its edge)
/// with the inner level (the largest of the element's levels, as [`drawn_levels`] raises it).
/// Mirror of `geomorph_position` in glsl/pattern/adaptive.vert.
pub fn geomorph_position(
    levels: &ElementLevels,
    d: &DrawnLevels,
    f: u32,
    (i, j): (u32, u32),
    eval: &dyn Fn([f32; 3]) -> Vec3,
) -> Vec3 {
    let point = |(i, j): (u32, u32)| eval(bary(i, j, f));
    // A boundary point drawn: snapped onto its edge, morphing with the edge's level.
    let edge_drawn = |(i, j): (u32, u32), k: usize| {
        let (si, sj) = snap(i, j, d, f);
        let p = point((si, sj));
        let s = f / d.edges[k];
        if !is_new(si, sj, s) {
            return p;
        }
        let m = morph_factor(levels.edges[k], d.edges[k]);
        if m >= 1.0 {
            return p;
        }
        let [a, b] = parents(si, sj, s);
        morph(point(a), point(b), p, m)
    };
    if let Some(k) = edge_of(i, j, f) {
        return edge_drawn((i, j), k);
    }
    let p = point((i, j));
    let s = f / d.inner;
    if !is_new(i, j, s) {
        return p;
    }
    let lambda = levels.edges.iter().copied().fold(levels.inner, f32::max);
    let m = morph_factor(lambda, d.inner);
    if m >= 1.0 {
        return p;
    }
    let drawn = |q: (u32, u32)| match edge_of(q.0, q.1, f) {
        Some(k) => edge_drawn(q, k),
        None => point(q),
    };
    let [a, b] = parents(i, j, s);
    morph(drawn(a), drawn(b), p, m)
}

/// The parameter a geomorphing vertex stands for: its weights blended as
/// [`geomorph_position`] blends its position (from its parents' drawn parameters at `m = 0` to
/// its own snapped sample at `m = 1`). The drawn mesh is linear in these parameters, so the
/// triangles over them tile the element, and a check of the drawn mesh against the surface
/// at matching parameters sees no tangential slide (docs/adaptivity.md, "Geomorphing").
pub fn geomorph_weights(
    levels: &ElementLevels,
    d: &DrawnLevels,
    f: u32,
    (i, j): (u32, u32),
) -> [f32; 3] {
    let at = |(i, j): (u32, u32)| [(f - i - j) as f64, i as f64, j as f64];
    let blend = |a: [f64; 3], b: [f64; 3], p: [f64; 3], m: f32| {
        let m = m as f64;
        std::array::from_fn(|k| {
            let mid = (a[k] + b[k]) * 0.5;
            mid + (p[k] - mid) * m
        })
    };
    let edge_drawn = |(i, j): (u32, u32), k: usize| -> [f64; 3] {
        let (si, sj) = snap(i, j, d, f);
        let s = f / d.edges[k];
        let m = morph_factor(levels.edges[k], d.edges[k]);
        if !is_new(si, sj, s) || m >= 1.0 {
            return at((si, sj));
        }
        let [a, b] = parents(si, sj, s);
        blend(at(a), at(b), at((si, sj)), m)
    };
    let w = if let Some(k) = edge_of(i, j, f) {
        edge_drawn((i, j), k)
    } else {
        let s = f / d.inner;
        let lambda = levels.edges.iter().copied().fold(levels.inner, f32::max);
        let m = morph_factor(lambda, d.inner);
        if !is_new(i, j, s) || m >= 1.0 {
            at((i, j))
        } else {
            let drawn = |q: (u32, u32)| match edge_of(q.0, q.1, f) {
                Some(k) => edge_drawn(q, k),
                None => at(q),
            };
            let [a, b] = parents(i, j, s);
            blend(drawn(a), drawn(b), at((i, j)), m)
        }
    };
    w.map(|x| (x / f as f64) as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What the adaptive draws store is what the hierarchy and the integer patterns hold.
    #[test]
    fn adaptive_stored_counts_what_the_patterns_hold() {
        for f in [1, 2, 8, 64] {
            let h = Hierarchy::new(f);
            let dyadic = (h.bary.len() as u64, h.indices.len() as u64);
            assert_eq!(adaptive_stored(f, true), dyadic, "hierarchy up to {f}");
            let p = IntegerPatterns::new(f);
            let integer = (p.bary.len() as u64, p.indices.len() as u64);
            assert_eq!(adaptive_stored(f, false), integer, "integer up to {f}");
        }
        assert_eq!(adaptive_stored(64, false), (47_904, 268_320));
    }

    #[test]
    fn hierarchy_levels_are_the_uniform_patterns() {
        let f = 16;
        let h = Hierarchy::new(f);
        for l in 0..=4 {
            let n = 1 << l;
            let r = Hierarchy::range(n);
            let coarse = Pattern::uniform(n);
            let range = &h.indices[r.start as usize..r.end as usize];
            // A level reads only its own vertices, the first ones.
            let own = crate::pattern::vertex_count(n);
            assert!(
                range.iter().all(|&k| k < own),
                "level {n} reads past its vertices"
            );
            let got: Vec<[f32; 3]> = range.iter().map(|&k| h.bary[k as usize]).collect();
            let want: Vec<[f32; 3]> = coarse
                .indices
                .iter()
                .map(|&k| coarse.bary[k as usize])
                .collect();
            assert_eq!(got, want, "level {n}");
        }
        assert_eq!(h.indices.len() as u32, Hierarchy::first_index(5));
    }

    /// The hierarchical order holds every point of the finest lattice once, and
    /// [`hierarchy_vertex`] finds each where [`Hierarchy::new`] put it.
    #[test]
    fn hierarchy_vertex_numbers_the_hierarchical_order() {
        for f in [1, 2, 4, 16, 64, 256] {
            let h = Hierarchy::new(f);
            assert_eq!(h.points.len() as u32, crate::pattern::vertex_count(f));
            let mut seen = std::collections::HashSet::new();
            for (k, &(i, j)) in h.points.iter().enumerate() {
                assert!(seen.insert((i, j)), "level {f}: ({i}, {j}) twice");
                assert_eq!(hierarchy_vertex(f, i, j), k as u32, "level {f}: ({i}, {j})");
                assert_eq!(h.bary[k], bary(i, j, f));
            }
        }
    }

    #[test]
    fn snapping_lands_on_the_edge_samples_from_either_side() {
        for f in [1u32, 2, 8, 64] {
            for n in (0..=f.trailing_zeros()).map(|l| 1 << l) {
                for inner in (0..=f.trailing_zeros())
                    .map(|l| 1u32 << l)
                    .filter(|&m| m >= n)
                {
                    let step = f / inner;
                    // Both directions give every sample k f/n, and only those.
                    let fwd: std::collections::BTreeSet<u32> =
                        (0..=inner).map(|a| snap_edge(a * step, n, f)).collect();
                    let back: std::collections::BTreeSet<u32> = (0..=inner)
                        .map(|a| f - snap_edge(f - a * step, n, f))
                        .collect();
                    let want: std::collections::BTreeSet<u32> =
                        (0..=n).map(|k| k * (f / n)).collect();
                    assert_eq!(fwd, want);
                    assert_eq!(back, want);
                }
            }
        }
    }

    /// What the transition triangles' bound takes of the snapping (src/lod/frame/transitions.rs):
    /// a move of at most half a sample, in order, and onto the corner for the points beside one
    /// whenever the edge is coarser than the inside; the same from either end.
    #[test]
    fn snapping_moves_half_a_sample_and_collapses_corners() {
        let f = 64u32;
        for n in (0..=6).map(|l| 1u32 << l) {
            for inner in (0..=6).map(|l| 1u32 << l).filter(|&m| m > n) {
                let step = f / inner;
                let snapped: Vec<u32> = (0..=inner).map(|a| snap_edge(a * step, n, f)).collect();
                for (a, &s) in snapped.iter().enumerate() {
                    let a = a as u32 * step;
                    assert!(2 * s.abs_diff(a) <= f / n, "{a} -> {s} at {n}");
                    // The reversed edge snaps the mirrored point to the mirrored sample (but
                    // the middle of an edge at level 1, a tie between its corners).
                    if 2 * a != f || n > 1 {
                        assert_eq!(f - snap_edge(f - a, n, f), s, "{a} at {n} from the end");
                    }
                }
                assert!(snapped.windows(2).all(|w| w[0] <= w[1]));
                // (At inner level 2 the one point beside both corners is the middle: it goes to
                // the smaller.)
                if inner == 2 {
                    assert_eq!(snapped[1], 0);
                } else {
                    let ends = (snapped[1], snapped[inner as usize - 1]);
                    assert_eq!(ends, (0, f), "{n} in {inner}");
                }
            }
        }
    }

    #[test]
    fn uniform_levels_draw_the_uniform_pattern() {
        let f = 32;
        for (n, dyadic) in [
            (1u32, true),
            (4, true),
            (32, true),
            (1, false),
            (7, false),
            (32, false),
        ] {
            let e = adaptive_element(&ElementLevels::uniform(n as f32), f, dyadic).unwrap();
            let p = Pattern::uniform(n);
            assert_eq!(e.bary, p.bary, "level {n}");
            assert_eq!(e.triangles.len() as u32, n * n);
        }
        assert!(adaptive_element(&ElementLevels::CULLED, f, true).is_none());
        assert!(adaptive_element(&ElementLevels::CULLED, f, false).is_none());
    }

    #[test]
    fn morph_factor_glides_from_the_coarser_level() {
        assert_eq!(morph_factor(4.0, 4), 1.0);
        assert_eq!(morph_factor(2.0, 4), 0.0);
        assert_eq!(morph_factor(5.0, 1), 1.0);
        // Increasing in λ between the two levels, and the c2 bound's blend meets the tolerance
        // exactly: (1 − m)·4/n² + m/n² = 1/λ².
        let mut last = 0.0;
        for k in 1..=64 {
            let lambda = 8.0 + k as f32 / 8.0;
            let m = morph_factor(lambda, 16);
            assert!(m > last, "λ {lambda}");
            let blend = (1.0 - m) * 4.0 / 256.0 + m / 256.0;
            assert!((blend - 1.0 / (lambda * lambda)).abs() < 1e-6, "λ {lambda}");
            last = m;
        }
    }

    #[test]
    fn parents_halve_a_coarser_lattice_edge() {
        let f = 16;
        for s in [1u32, 2, 4] {
            for j in 0..=f {
                for i in 0..=(f - j) {
                    if i % s != 0 || j % s != 0 || !is_new(i, j, s) {
                        continue;
                    }
                    let [a, b] = parents(i, j, s);
                    assert_eq!((a.0 + b.0, a.1 + b.1), (2 * i, 2 * j));
                    for q in [a, b] {
                        assert!(q.0 + q.1 <= f && !is_new(q.0, q.1, s), "{q:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn geomorph_at_whole_levels_draws_the_true_points() {
        // λ at a power of two: nothing morphs; just above half of it: new points at midpoints.
        let f = 8;
        let eval = |b: [f32; 3]| Vec3::new(b[1], b[2], b[1] * b[1] + b[2] * b[2]);
        let l = ElementLevels::uniform(4.0);
        let d = drawn_levels(&l, f, true).unwrap();
        let e = dyadic_element(&l, f).unwrap();
        for (&pt, b) in e.points.iter().zip(&e.bary) {
            assert_eq!(geomorph_position(&l, &d, f, pt, &eval), eval(*b));
            assert_eq!(geomorph_weights(&l, &d, f, pt), *b);
        }
        let l = ElementLevels::uniform(2.0 + 1e-6);
        let d = drawn_levels(&l, f, true).unwrap();
        let e = dyadic_element(&l, f).unwrap();
        for (&(i, j), b) in e.points.iter().zip(&e.bary) {
            let got = geomorph_position(&l, &d, f, (i, j), &eval);
            if is_new(i, j, 2) {
                let [a, c] = parents(i, j, 2);
                let mid = (eval(bary(a.0, a.1, f)) + eval(bary(c.0, c.1, f))) * 0.5;
                assert!((got - mid).length() < 1e-5, "{i} {j}");
                let w = geomorph_weights(&l, &d, f, (i, j));
                let (ba, bc) = (bary(a.0, a.1, f), bary(c.0, c.1, f));
                for k in 0..3 {
                    assert!((w[k] - (ba[k] + bc[k]) * 0.5).abs() < 1e-5, "{i} {j}");
                }
            } else {
                assert_eq!(got, eval(*b));
            }
        }
    }

    #[test]
    fn levels_are_dyadic_and_the_inner_covers_the_edges() {
        let l = ElementLevels {
            edges: [3.0, 0.0, 20.0],
            inner: 5.0,
        };
        assert_eq!(
            drawn_levels(&l, 16, true),
            Some(DrawnLevels {
                edges: [4, 1, 16],
                inner: 16
            })
        );
        assert_eq!(
            drawn_levels(&l, 16, false),
            Some(DrawnLevels {
                edges: [3, 1, 16],
                inner: 16
            })
        );
    }

    /// Integer snapping reaches every sample of the edge's level and nothing else, moves no
    /// vertex by more than half a sample, keeps the corners, goes toward the nearer corner on
    /// a tie, and equals the dyadic snapping where the edge's level divides the inner level.
    #[test]
    fn integer_snapping_reaches_every_sample_within_half_a_sample() {
        for n in 1..=40u32 {
            for m in 1..=n {
                let k: Vec<u32> = (0..=n).map(|a| snap_sample(a, m, n)).collect();
                assert_eq!((k[0], k[n as usize]), (0, m), "{m} of {n}");
                for w in k.windows(2) {
                    assert!(w[1] == w[0] || w[1] == w[0] + 1, "{m} of {n}: {k:?}");
                }
                for (a, &s) in k.iter().enumerate() {
                    // |a/n − s/m| <= 1/(2m), in integers.
                    let d = (2 * a as i64 * m as i64 - 2 * s as i64 * n as i64).abs();
                    assert!(d <= n as i64, "{a}/{n} to {s}/{m}");
                    if d == n as i64 {
                        // A tie: toward the nearer corner (the first at the middle).
                        assert_eq!(2 * s * n <= 2 * a as u32 * m, 2 * a as u32 <= n);
                    }
                    if n % m == 0 && (n / m).is_power_of_two() && n.is_power_of_two() {
                        assert_eq!(snap_edge(a as u32, m, n), s * (n / m));
                    }
                }
            }
        }
    }

    /// The integer patterns' ranges: each level's first index and vertex, and its weights the
    /// uniform pattern's.
    #[test]
    fn integer_patterns_number_every_level_after_the_previous() {
        let p = IntegerPatterns::new(9);
        for n in 1..=9u32 {
            let u = Pattern::uniform(n);
            let (v, i) = (
                IntegerPatterns::base_vertex(n),
                IntegerPatterns::first_index(n),
            );
            assert_eq!(&p.bary[v as usize..][..u.bary.len()], &u.bary[..]);
            assert_eq!(&p.indices[i as usize..][..u.indices.len()], &u.indices[..]);
        }
        assert_eq!(p.bary.len() as u32, IntegerPatterns::base_vertex(10));
        assert_eq!(p.indices.len() as u32, IntegerPatterns::first_index(10));
    }

    /// Both elements sharing an edge draw its vertices at the same weights, whichever way each
    /// measures it and whatever their inner levels: the same bits for the same corner.
    #[test]
    fn integer_edges_get_the_same_weights_from_both_sides() {
        for m in 1..=13u32 {
            for (na, nb) in [(m, m), (m, m + 1), (m + 3, 2 * m + 1), (3 * m, m + 5)] {
                // Element A has the edge as stored edge 0 (corner 0 to corner 1), B as stored
                // edge 2 (corner 2 to corner 0) with B's corner 2 = A's corner 1.
                let da = DrawnLevels {
                    edges: [m, na, na],
                    inner: na,
                };
                let db = DrawnLevels {
                    edges: [nb, nb, m],
                    inner: nb,
                };
                let side = |w: &[[f32; 3]], c0: usize, c1: usize| -> Vec<(u32, u32)> {
                    let mut v: Vec<(u32, u32)> = w
                        .iter()
                        .map(|b| (b[c0].to_bits(), b[c1].to_bits()))
                        .collect();
                    v.sort_unstable();
                    v.dedup();
                    v
                };
                let a: Vec<[f32; 3]> = (0..=na).map(|i| integer_bary(i, 0, &da)).collect();
                let b: Vec<[f32; 3]> = (0..=nb).map(|j| integer_bary(0, j, &db)).collect();
                // A's corner 0 is B's corner 0; A's corner 1 is B's corner 2.
                assert_eq!(
                    side(&a, 0, 1),
                    side(&b, 0, 2),
                    "edge {m}, inner {na} and {nb}"
                );
                assert_eq!(side(&a, 0, 1).len() as u32, m + 1);
            }
        }
    }
}

#[cfg(test)]
#[path = "geomorph_tests.rs"]
mod geomorph_tests;
