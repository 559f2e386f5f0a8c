//! Packing: the tables as the drawing stages read them ([`Packed`]), still CPU data (no Vulkan;
//! `render::loop_gpu` uploads it as it is). A symmetric table keeps the rows on one side of its
//! axis and reads the others as their mirror images, its columns in the pairs the reflection
//! swaps ([`arrange`]); rows with the same weights are stored once among all tables.
#![forbid(unsafe_code)]

use super::lattice::reflection;
use super::table::rounded;
use super::{Config, Lattice};
use std::collections::HashMap;

/// Tables as the drawing stages read them: distinct rows stored once in `pool`, and for every
/// table a map from its rows to theirs. Two tables share a row where their faces' neighbourhoods
/// agree as far as that lattice point reaches (a boundary fan's faces far from its extraordinary
/// vertex, whatever the fan's width), and a symmetric table ([`Config::symmetry`]) reads the rows
/// on one side of its axis as its own with every column pair swapped.
#[derive(Clone, Debug, Default)]
pub struct Packed {
    /// The distinct rows, f32, each padded with zeros to the longest (multiple of four) of the
    /// tables that read it, so every row starts at a multiple of four.
    pub pool: Vec<f32>,
    /// Table t's row r at `t * rows + r`: the row's first weight in `pool` over four, times
    /// two, plus one where the row is read as its mirror image ([`ROW_SWAPPED`]).
    pub rows: Vec<u32>,
}

/// Bit 0 of a [`Packed::rows`] entry: the row is the mirror image of the stored one, read with
/// the weights of columns 2m and 2m + 1 swapped for m < [`Config::pairs`] (a symmetric table's
/// row across its axis).
pub const ROW_SWAPPED: u32 = 1;

impl Packed {
    /// Bytes on the GPU: the pool and the row maps.
    pub fn bytes(&self) -> u64 {
        (self.pool.len() + self.rows.len()) as u64 * 4
    }

    /// Entry `i` of [`Packed::rows`] (table t's row r is `t * rows + r`): where its weights
    /// start in `pool`, and whether it is read as its mirror image.
    pub fn entry(&self, i: usize) -> (usize, bool) {
        let e = self.rows[i];
        ((e >> 1) as usize * 4, e & ROW_SWAPPED != 0)
    }

    /// Weight `c` of a row at `entry` of a table with `pairs` column pairs, as the GPU reads
    /// it. Mirror of `bft_weights` in loop.glsl.
    pub fn weight(&self, (at, swapped): (usize, bool), c: usize, pairs: usize) -> f32 {
        self.pool[at + if swapped && c < 2 * pairs { c ^ 1 } else { c }]
    }
}

/// Puts `c`'s columns in an order that depends only on their weights, so that two tables whose
/// rows agree far from canonical corner 0 order the columns weighing there alike and [`pack`]
/// can share those rows: by their weights at the lattice points from the edge opposite corner
/// 0 inwards, larger first, a column that weighs nothing there after those that do. Where the
/// table is its own mirror image under a reflection (found from the weights: every column
/// reflected is another column), the columns come in the pairs it swaps instead
/// ([`Config::symmetry`]). Rewrites `c` and returns its new columns as indices of its old.
pub(super) fn arrange(c: &mut Config, lattice: Lattice) -> Vec<usize> {
    let (rows, k) = (lattice.rows(), c.control);
    // Far from corner 0 first: the rows by decreasing i + j, then by i.
    let s = lattice.segments();
    let mut far: Vec<usize> = Vec::with_capacity(rows);
    for d in (0..=s).rev() {
        for i in (0..=d).rev() {
            far.push(lattice.row(i, d - i));
        }
    }
    // Larger weights first (negated), so a column weighing nothing there comes after.
    let keys: Vec<Vec<i64>> = (0..k)
        .map(|j| {
            far.iter()
                .map(|&r| -rounded(c.weights[r * k + j]))
                .collect()
        })
        .collect();
    let mut order: Vec<usize> = (0..k).collect();
    order.sort_by(|&a, &b| keys[a].cmp(&keys[b]).then(a.cmp(&b)));
    // A reflection under which every column is another column's mirror image, to 1e-12 of
    // each weight (the two are summed in different orders, every term non-negative; a far
    // column's weights are as small as 1e-13).
    let w = &c.weights;
    let same = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs());
    // Only inside faces fold: a boundary face's far rows are shared with its neighbours'
    // tables, which the pairs' order would lose (for every configuration to valence 18,
    // folding the boundary's symmetric tables too takes 0.82 MiB instead of 0.77).
    let symmetric = (0..3u8).filter(|_| !c.boundary).find_map(|a| {
        let image = reflection(lattice, a);
        let mirrors =
            |j: usize, d: usize| (0..rows).all(|r| same(w[image[r] * k + j], w[r * k + d]));
        // Paired greedily: columns can be equal (the far ring of a high valence vertex, reached
        // only through the vertex's own rule), and any of equal columns will do.
        let mut sigma = vec![usize::MAX; k];
        for j in 0..k {
            if sigma[j] == usize::MAX {
                let d = (j + 1..k)
                    .chain([j])
                    .find(|&d| sigma[d] == usize::MAX && mirrors(j, d))?;
                sigma[j] = d;
                sigma[d] = j;
            }
        }
        // The reflection is an involution, so d mirrors j exactly when j mirrors d.
        (0..k).all(|j| mirrors(sigma[j], j)).then_some((a, sigma))
    });
    let (layout, pairs) = match &symmetric {
        None => (order, 0),
        Some((_, sigma)) => {
            // The pairs (j, σj) in the order of their first column, then the fixed columns.
            let mut layout: Vec<usize> = Vec::with_capacity(k);
            for &j in &order {
                if sigma[j] != j && !layout.contains(&j) {
                    layout.extend([j, sigma[j]]);
                }
            }
            let pairs = layout.len() / 2;
            layout.extend(order.iter().filter(|&&j| sigma[j] == j));
            (layout, pairs)
        }
    };
    c.weights = (0..rows)
        .flat_map(|r| layout.iter().map(move |&j| r * k + j))
        .map(|i| c.weights[i])
        .collect();
    c.symmetry = symmetric.map(|(a, _)| a);
    c.pairs = pairs;
    layout
}

/// Stores `tables` as the GPU reads them ([`Packed`]): every row once, rows with the same
/// weights (as f32, trailing zeros aside) shared among tables, a symmetric table's rows across
/// its axis read as their mirror images with the column pairs swapped.
pub fn pack(tables: &[&Config], lattice: Lattice) -> Packed {
    let rows = lattice.rows();
    let images: Vec<Vec<usize>> = (0..3u8).map(|a| reflection(lattice, a)).collect();
    // The distinct rows (f32 bits, trailing zeros trimmed) and the longest table reading each.
    let mut ids: HashMap<Vec<u32>, usize> = HashMap::new();
    let mut distinct: Vec<(Vec<u32>, usize)> = Vec::new();
    // Per table row: (distinct row, swapped).
    let mut refs: Vec<(usize, bool)> = Vec::with_capacity(tables.len() * rows);
    for (t, c) in tables.iter().enumerate() {
        let k = c.control;
        let image = c.symmetry.map(|a| &images[a as usize]);
        for r in 0..rows {
            if let Some(image) = image {
                if image[r] < r {
                    let (id, _) = refs[t * rows + image[r]];
                    refs.push((id, true));
                    continue;
                }
            }
            let mut bits: Vec<u32> = c.weights[r * k..(r + 1) * k]
                .iter()
                .map(|&w| (w as f32).to_bits())
                .collect();
            while bits.last() == Some(&0) {
                bits.pop();
            }
            let next = distinct.len();
            let id = *ids.entry(bits).or_insert_with_key(|bits| {
                distinct.push((bits.clone(), 0));
                next
            });
            distinct[id].1 = distinct[id].1.max(k.next_multiple_of(4));
            refs.push((id, false));
        }
    }
    let mut first = Vec::with_capacity(distinct.len());
    let mut pool = Vec::new();
    for (bits, len) in &distinct {
        first.push(pool.len());
        pool.extend(bits.iter().map(|&b| f32::from_bits(b)));
        pool.resize(first.last().unwrap() + len, 0.0);
    }
    let rows = refs
        .iter()
        .map(|&(id, swapped)| (first[id] / 4) as u32 * 2 + swapped as u32)
        .collect();
    Packed { pool, rows }
}
