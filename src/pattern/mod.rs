//! Refinement patterns (Boubekeur & Schlick 2005, §3.2 "Refinement Pattern").
//!
//! A pattern of level `N` is the coarse triangle split into `N` segments per edge: a triangular
//! lattice of `(N+1)(N+2)/2` vertices and `N²` triangles. Each vertex stores its barycentric
//! coordinates `(w, u, v)` as its position, exactly as the paper encodes them (`V.xyz := {w, u, v}`,
//! `w = 1 - u - v`), so a vertex shader can map it onto any coarse triangle:
//! `P = w·P0 + u·P1 + v·P2`.
//!
//! Layout (an invariant the drivers rely on):
//! - vertex `(i, j)` (`i` steps along `u`, `j` along `v`, `i + j <= N`) has index
//!   [`lattice_index`]`(N, i, j)`: rows of constant `j`, row `j` holding `N - j + 1` vertices;
//! - each coordinate is the correctly rounded `f32` of an exact fraction: `u = i/N`, `v = j/N`,
//!   `w = (N-i-j)/N` (not `1 - u - v`). Two triangles that share an edge therefore see the very same
//!   pair of weights for the shared corners, which is what makes refinement watertight
//!   (see `surface::canonical`);
//! - the index buffer is an indexed triangle list (`3N²` indices), row after row, each row's
//!   triangles from `u = 0` on, alternating the upward and downward triangle: consecutive rows
//!   share a row of vertices, which the implementation's post-transform vertex cache then shades
//!   once (row strips with primitive restart re-shaded every row: on lavapipe they shaded every
//!   strip index, 1.57 M vertex-shader invocations for Spot at level 64, against 0.80 M distinct
//!   vertices). Every triangle is counter-clockwise in the `(u, v)` plane, i.e. it has the
//!   winding of the coarse triangle `P0 P1 P2`.
//!
//! At `N = 64` a pattern has 2,145 vertices, where the paper's square-grid pattern stored 65² = 4,225.
#![forbid(unsafe_code)]

pub mod adaptive;

/// Number of vertices of a level-`n` pattern: `(n+1)(n+2)/2`.
pub const fn vertex_count(n: u32) -> u32 {
    (n + 1) * (n + 2) / 2
}

/// Number of triangles of a level-`n` pattern: `n²`.
pub const fn triangle_count(n: u32) -> u32 {
    n * n
}

/// Number of indices of a level-`n` pattern's triangle list: `3n²`.
pub const fn index_count(n: u32) -> u32 {
    3 * n * n
}

/// Index of lattice vertex `(i, j)` (`i` along `u`, `j` along `v`) in a level-`n` pattern: the one
/// function that numbers a triangular lattice (the basis function tables number their rows with
/// it too; `bft_row` in glsl/include/loop.glsl mirrors it).
pub const fn lattice_index(n: u32, i: u32, j: u32) -> u32 {
    // Rows before j hold (n+1) + n + ... + (n-j+2) vertices.
    j * (n + 1) - j * j.saturating_sub(1) / 2 + i
}

/// Barycentric weight `k/n`, correctly rounded. The one place a lattice weight is made.
pub fn weight(k: u32, n: u32) -> f32 {
    (k as f64 / n as f64) as f32
}

/// A refinement pattern: barycentric vertices and a triangle list.
#[derive(Clone, Debug, PartialEq)]
pub struct Pattern {
    pub level: u32,
    /// `(w, u, v)` per vertex.
    pub bary: Vec<[f32; 3]>,
    /// Triangle list, three indices per triangle, row after row.
    pub indices: Vec<u32>,
}

impl Pattern {
    /// The uniform pattern of level `n >= 1`.
    pub fn uniform(n: u32) -> Self {
        assert!(n >= 1, "pattern level must be at least 1");
        let mut bary = Vec::with_capacity(vertex_count(n) as usize);
        for j in 0..=n {
            for i in 0..=(n - j) {
                bary.push([weight(n - i - j, n), weight(i, n), weight(j, n)]);
            }
        }
        let mut indices = Vec::with_capacity(index_count(n) as usize);
        let at = |i, j| lattice_index(n, i, j);
        for j in 0..n {
            let m = n - j;
            for i in 0..m {
                // Upward (i,j) (i+1,j) (i,j+1), then downward (i+1,j) (i+1,j+1) (i,j+1).
                indices.extend([at(i, j), at(i + 1, j), at(i, j + 1)]);
                if i + 1 < m {
                    indices.extend([at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
                }
            }
        }
        debug_assert_eq!(bary.len() as u32, vertex_count(n));
        debug_assert_eq!(indices.len() as u32, index_count(n));
        Self {
            level: n,
            bary,
            indices,
        }
    }

    /// Lattice coordinates `(i, j)` of each vertex, in vertex order.
    pub fn lattice(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        let n = self.level;
        (0..=n).flat_map(move |j| (0..=(n - j)).map(move |i| (i, j)))
    }

    /// The triangles, in drawing order.
    pub fn triangles(&self) -> Vec<[u32; 3]> {
        self.indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect()
    }
}

/// The patterns kept on the GPU for level-of-detail selection (paper §3.3): every power of two
/// below the finest level, and the finest level itself.
#[derive(Clone, Debug)]
pub struct PatternSet {
    pub patterns: Vec<Pattern>,
}

impl PatternSet {
    /// Levels 1, 2, 4, ... below `finest`, then `finest`.
    pub fn up_to(finest: u32) -> Self {
        let mut levels: Vec<u32> = (0..32)
            .map(|s| 1u32 << s)
            .take_while(|&l| l < finest)
            .collect();
        levels.push(finest);
        Self {
            patterns: levels.into_iter().map(Pattern::uniform).collect(),
        }
    }

    /// Exactly these levels (sorted, deduplicated; a level below 1 is ignored).
    pub fn from_levels(levels: &[u32]) -> Self {
        let mut l: Vec<u32> = levels.iter().copied().filter(|&l| l >= 1).collect();
        l.sort_unstable();
        l.dedup();
        if l.is_empty() {
            l.push(1);
        }
        Self {
            patterns: l.into_iter().map(Pattern::uniform).collect(),
        }
    }

    pub fn levels(&self) -> impl Iterator<Item = u32> + '_ {
        self.patterns.iter().map(|p| p.level)
    }

    /// Position of the pattern with the given level in the set.
    pub fn find(&self, level: u32) -> Option<usize> {
        self.patterns.iter().position(|p| p.level == level)
    }

    /// The level to draw for an object of bounding radius `radius` seen from `distance`, among
    /// the set's levels up to `max` (the smallest where none is): the finest of them when the
    /// object is close, one level coarser each time the distance doubles past
    /// `near = 2·radius`.
    pub fn level_for_distance(&self, distance: f32, radius: f32, max: u32) -> u32 {
        let near = 2.0 * radius.max(f32::MIN_POSITIVE);
        let steps = if distance <= near {
            0
        } else {
            (distance / near).log2().floor() as usize
        };
        let count = self
            .patterns
            .iter()
            .filter(|p| p.level <= max)
            .count()
            .max(1);
        let idx = count.saturating_sub(1 + steps);
        self.patterns[idx].level
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    fn uv(p: &Pattern, i: u32) -> (f64, f64) {
        let b = p.bary[i as usize];
        (b[1] as f64, b[2] as f64)
    }

    #[test]
    fn counts_match_formulas() {
        for n in 1..=70 {
            let p = Pattern::uniform(n);
            assert_eq!(p.bary.len() as u32, (n + 1) * (n + 2) / 2);
            assert_eq!(p.triangles().len() as u32, n * n);
            assert_eq!(p.indices.len() as u32, index_count(n));
        }
        assert_eq!(vertex_count(64), 2145);
    }

    #[test]
    fn lattice_index_matches_vertex_order() {
        for n in [1, 2, 3, 7, 64] {
            let p = Pattern::uniform(n);
            for (k, (i, j)) in p.lattice().enumerate() {
                assert_eq!(lattice_index(n, i, j), k as u32);
                let b = p.bary[k];
                assert_eq!(b, [weight(n - i - j, n), weight(i, n), weight(j, n)]);
            }
        }
    }

    #[test]
    fn barycentrics_sum_to_one_and_corners_are_exact() {
        let p = Pattern::uniform(13);
        for b in &p.bary {
            assert!((b[0] + b[1] + b[2] - 1.0).abs() <= 2.0 * f32::EPSILON);
            assert!(b.iter().all(|&x| (0.0..=1.0).contains(&x)));
        }
        assert_eq!(p.bary[lattice_index(13, 0, 0) as usize], [1.0, 0.0, 0.0]);
        assert_eq!(p.bary[lattice_index(13, 13, 0) as usize], [0.0, 1.0, 0.0]);
        assert_eq!(p.bary[lattice_index(13, 0, 13) as usize], [0.0, 0.0, 1.0]);
    }

    #[test]
    fn triangles_are_ccw_tile_the_triangle_and_share_edges() {
        for n in [1, 2, 5, 16] {
            let p = Pattern::uniform(n);
            let tris = p.triangles();
            let mut area = 0.0;
            let mut edges = std::collections::HashMap::new();
            for t in &tris {
                let (a, b, c) = (uv(&p, t[0]), uv(&p, t[1]), uv(&p, t[2]));
                let cross = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
                assert!(
                    cross > 0.0,
                    "level {n}: triangle {t:?} is not counter-clockwise"
                );
                area += cross / 2.0;
                for e in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                    // Directed edges must be unique (consistent orientation, no overlap).
                    assert!(edges.insert(e, ()).is_none(), "directed edge {e:?} twice");
                }
            }
            assert!((area - 0.5).abs() < 1e-6, "level {n}: area {area}");
            // Every vertex is used.
            let used: HashSet<u32> = tris.iter().flatten().copied().collect();
            assert_eq!(used.len() as u32, vertex_count(n));
            // Boundary edges (no twin) are exactly the 3n edges on the coarse triangle's border.
            let boundary = edges
                .keys()
                .filter(|(a, b)| !edges.contains_key(&(*b, *a)))
                .count() as u32;
            assert_eq!(boundary, 3 * n);
        }
    }

    #[test]
    fn pattern_set_and_lod() {
        let set = PatternSet::up_to(48);
        assert_eq!(
            set.levels().collect::<Vec<_>>(),
            vec![1, 2, 4, 8, 16, 32, 48]
        );
        assert_eq!(PatternSet::up_to(1).levels().collect::<Vec<_>>(), vec![1]);
        assert_eq!(set.level_for_distance(1.0, 1.0, 48), 48);
        assert_eq!(set.level_for_distance(4.5, 1.0, 48), 32);
        assert_eq!(set.level_for_distance(1e9, 1.0, 48), 1);
        // Up to a cap: the finest level at most it, coarser from there.
        assert_eq!(set.level_for_distance(1.0, 1.0, 8), 8);
        assert_eq!(set.level_for_distance(1.0, 1.0, 12), 8);
        assert_eq!(set.level_for_distance(4.5, 1.0, 8), 4);
        assert_eq!(set.level_for_distance(1.0, 1.0, 0), 1);
        assert_eq!(set.find(16), Some(4));
    }
}
