//! The height map's chord-error bound (src/lod/mod.rs has the chord error's form), from the
//! texels the bounded patch reads: each pyramid level's texel differences and heights, kept as
//! maxima over blocks of texels in a pyramid of their own, so that a patch's bound takes the
//! largest differences and heights over the texels under its texture coordinates, not the whole
//! map's (a terrain map's smooth plains do not pay for its mountains).

use super::heightmap::{Heightmap, Level};
use super::SurfaceParams;
use crate::lod::Chord;
use glam::Vec2;
use std::sync::OnceLock;

/// The largest texel differences and the range of heights of one pyramid level over a region
/// of it (coordinates repeat, so the differences wrap around too).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapLevel {
    pub size: Vec2,
    /// Largest `|t(x+1) − t(x)|` along x and along y.
    pub first: Vec2,
    /// Largest `|t(x+1) − 2 t(x) + t(x−1)|` along x and along y.
    pub second: Vec2,
    /// Largest `|t00 − t10 − t01 + t11|`.
    pub mixed: f32,
    /// Smallest and largest height.
    pub low: f32,
    pub high: f32,
}

impl MapLevel {
    /// Level `l`'s facts over the whole map.
    pub fn of(map: &Heightmap, l: usize) -> MapLevel {
        map.facts.level(map, l).whole()
    }

    /// Level `l`'s facts over the texels that bilinear samples at texture coordinates in the
    /// box `lo..=hi` read (with a texel to spare on each side for the rounding of `f32`
    /// coordinates); the whole map where the box spans it. `None` where the box is not finite
    /// or lies past `FAR` texels (`2^18`: `FAR`'s notes say why).
    pub fn over(map: &Heightmap, l: usize, lo: Vec2, hi: Vec2) -> Option<MapLevel> {
        let facts = map.facts.level(map, l);
        let lv = &map.levels[l];
        match (texels(lo.x, hi.x, lv.w)?, texels(lo.y, hi.y, lv.h)?) {
            (Some(x), Some(y)) => Some(facts.over(x, y)),
            _ => Some(facts.whole()),
        }
    }
}

/// Texel coordinates (texture coordinates times the level's side) past which the bound gives
/// up: `2^18`. The sampler's `f32` coordinate `u w − 1/2` is rounded to `2^-23` of its size, so
/// its heights step in fractions of a texel, up to `1/32` of one below this; the bound is for the
/// bilinear map at exact coordinates and leaves that rounding out, as it leaves out the rest of
/// the `f32` evaluation's. Past it the steps grow to a quarter of a texel and more (whole texels
/// past `2^23`), and no slope bounds them: no finite bound unless the level read is one height
/// throughout.
pub const FAR: f64 = (1u64 << 18) as f64;

/// The texels `floor(u n − 1/2) − 1 ..= floor(u n − 1/2) + 2` for `u` in `lo..=hi` (`Some(None)`
/// where that spans every texel), or `None` where that is not finite or lies past [`FAR`].
fn texels(lo: f32, hi: f32, n: u32) -> Option<Option<[i64; 2]>> {
    let (a, b) = (lo as f64 * n as f64 - 0.5, hi as f64 * n as f64 - 0.5);
    let within = |x: f64| x.is_finite() && x.abs() < FAR;
    if !(within(a) && within(b)) {
        return None;
    }
    Some((b - a + 4.0 < n as f64).then(|| [a.floor() as i64 - 1, b.floor() as i64 + 2]))
}

/// Texels in a block of the finest block grid: `2^BLOCK_SHIFT` a side.
const BLOCK_SHIFT: u32 = 3;

/// The most blocks one rectangle reads: the finest grid with no more than these over it (so a
/// rectangle of up to 128 texels a side, spare texels included, reads blocks of 8).
const MAX_BLOCKS: u32 = 289;

/// A region's facts: largest `first.x`, `first.y`, `second.x`, `second.y`, `mixed`, then the
/// smallest and the largest height.
#[derive(Clone, Copy, Debug)]
struct Cell([f32; 7]);

impl Cell {
    const EMPTY: Cell = Cell([0.0, 0.0, 0.0, 0.0, 0.0, f32::INFINITY, f32::NEG_INFINITY]);

    fn merge(self, o: Cell) -> Cell {
        let (a, b) = (self.0, o.0);
        Cell([
            a[0].max(b[0]),
            a[1].max(b[1]),
            a[2].max(b[2]),
            a[3].max(b[3]),
            a[4].max(b[4]),
            a[5].min(b[5]),
            a[6].max(b[6]),
        ])
    }
}

/// Block maxima over a grid of `bw` × `bh` blocks.
#[derive(Clone, Debug)]
struct Grid {
    bw: u32,
    bh: u32,
    cells: Vec<Cell>,
}

/// One pyramid level's facts: block grids, each block twice the side of the previous grid's,
/// down to one block.
#[derive(Clone, Debug)]
pub(crate) struct LevelFacts {
    size: Vec2,
    w: u32,
    h: u32,
    grids: Vec<Grid>,
}

impl LevelFacts {
    fn of(lv: &Level) -> Self {
        let (w, h) = (lv.w as i64, lv.h as i64);
        let t = |x: i64, y: i64| lv.texels[(y.rem_euclid(h) * w + x.rem_euclid(w)) as usize];
        let b = 1i64 << BLOCK_SHIFT;
        let (bw, bh) = ((w + b - 1) / b, (h + b - 1) / b);
        let mut cells = vec![Cell::EMPTY; (bw * bh) as usize];
        for y in 0..h {
            for x in 0..w {
                let c = t(x, y);
                let cell = Cell([
                    difference(&[(1.0, t(x + 1, y)), (-1.0, c)]),
                    difference(&[(1.0, t(x, y + 1)), (-1.0, c)]),
                    difference(&[(1.0, t(x + 1, y)), (1.0, t(x - 1, y)), (-2.0, c)]),
                    difference(&[(1.0, t(x, y + 1)), (1.0, t(x, y - 1)), (-2.0, c)]),
                    difference(&[
                        (1.0, c),
                        (-1.0, t(x + 1, y)),
                        (-1.0, t(x, y + 1)),
                        (1.0, t(x + 1, y + 1)),
                    ]),
                    c,
                    c,
                ]);
                let i = ((y / b) * bw + x / b) as usize;
                cells[i] = cells[i].merge(cell);
            }
        }
        let mut grids = vec![Grid {
            bw: bw as u32,
            bh: bh as u32,
            cells,
        }];
        while let Some(g) = grids.last().filter(|g| g.bw > 1 || g.bh > 1) {
            let (nw, nh) = (g.bw.div_ceil(2), g.bh.div_ceil(2));
            let mut cells = vec![Cell::EMPTY; (nw * nh) as usize];
            for y in 0..g.bh {
                for x in 0..g.bw {
                    let i = ((y / 2) * nw + x / 2) as usize;
                    cells[i] = cells[i].merge(g.cells[(y * g.bw + x) as usize]);
                }
            }
            grids.push(Grid {
                bw: nw,
                bh: nh,
                cells,
            });
        }
        Self {
            size: Vec2::new(lv.w as f32, lv.h as f32),
            w: lv.w,
            h: lv.h,
            grids,
        }
    }

    fn whole(&self) -> MapLevel {
        self.level(self.grids.last().expect("one grid at least").cells[0])
    }

    /// The facts over texels `x[0]..=x[1]`, `y[0]..=y[1]` (repeating; each span shorter than
    /// the map).
    fn over(&self, x: [i64; 2], y: [i64; 2]) -> MapLevel {
        let mut out = Cell::EMPTY;
        for xs in spans(x, self.w) {
            for ys in spans(y, self.h) {
                out = out.merge(self.rect(xs, ys));
            }
        }
        self.level(out)
    }

    /// The facts over a rectangle inside the map, from the finest grid whose blocks cover it
    /// with at most [`MAX_BLOCKS`].
    fn rect(&self, x: [u32; 2], y: [u32; 2]) -> Cell {
        let mut k = 0;
        while k + 1 < self.grids.len() {
            let s = BLOCK_SHIFT + k as u32;
            let blocks = ((x[1] >> s) - (x[0] >> s) + 1) * ((y[1] >> s) - (y[0] >> s) + 1);
            if blocks <= MAX_BLOCKS {
                break;
            }
            k += 1;
        }
        let (g, s) = (&self.grids[k], BLOCK_SHIFT + k as u32);
        let mut out = Cell::EMPTY;
        for by in y[0] >> s..=y[1] >> s {
            for bx in x[0] >> s..=x[1] >> s {
                out = out.merge(g.cells[(by * g.bw + bx) as usize]);
            }
        }
        out
    }

    fn level(&self, c: Cell) -> MapLevel {
        let c = c.0;
        MapLevel {
            size: self.size,
            first: Vec2::new(c[0], c[1]),
            second: Vec2::new(c[2], c[3]),
            mixed: c[4],
            low: c[5],
            high: c[6],
        }
    }
}

/// `|Σ w_i t_i|` for up to four texel heights `t_i` in `[0, 1]` and weights of 1 or 2, never
/// below the exact value: summed in `f64`, exactly where every height is 0 or at least `2^-26`
/// (their bits then span at most 52 places), with room for the rounding where not (three
/// additions of partial sums at most 4, each off by at most `2^-51`), and rounded up to `f32`.
/// So a flat region's differences are exactly 0 (a bound with no curvature there).
fn difference(terms: &[(f64, f32)]) -> f32 {
    let tiny = terms
        .iter()
        .any(|&(_, t)| t != 0.0 && t.abs() < 1.0 / (1u32 << 26) as f32);
    let sum: f64 = terms.iter().map(|&(w, t)| w * t as f64).sum();
    let x = sum.abs() + if tiny { 2.0 * f64::EPSILON } else { 0.0 };
    let f = x as f32;
    if (f as f64) < x {
        // The next f32 up (f is finite and at least 0 here).
        f32::from_bits(f.to_bits() + 1)
    } else {
        f
    }
}

/// A repeating span of texels `r[0]..=r[1]` (shorter than `n`) as one or two spans inside
/// `0..n`.
fn spans(r: [i64; 2], n: u32) -> Vec<[u32; 2]> {
    let n = n as i64;
    let a = r[0].rem_euclid(n);
    let b = a + (r[1] - r[0]);
    if b < n {
        vec![[a as u32, b as u32]]
    } else {
        vec![[a as u32, (n - 1) as u32], [0, (b - n) as u32]]
    }
}

/// Every level's [`LevelFacts`], each made when first asked for (bounds on every core share
/// them). Equal whatever has been made: they follow from the levels.
#[derive(Clone, Default)]
pub(crate) struct FactsCache(Vec<OnceLock<LevelFacts>>);

impl FactsCache {
    pub(crate) fn new(levels: usize) -> Self {
        Self((0..levels).map(|_| OnceLock::new()).collect())
    }

    fn level(&self, map: &Heightmap, l: usize) -> &LevelFacts {
        self.0[l].get_or_init(|| LevelFacts::of(&map.levels[l]))
    }
}

impl PartialEq for FactsCache {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl std::fmt::Debug for FactsCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let made = self.0.iter().filter(|c| c.get().is_some()).count();
        write!(f, "FactsCache({made} of {} levels made)", self.0.len())
    }
}

/// The height map's bound: `h = a·(t − b)` with `t` bilinear in the texels of the pyramid
/// levels read (one, or the two a fractional level of detail blends), over the texels under
/// the patch's texture coordinates ([`MapLevel::over`]): `|h| <= |a| max(|low − b|, |high −
/// b|)`, the slope along a lattice direction is at most `|a|` times the largest texel
/// difference per texel crossed, and the slope jumps at texel lines by at most the second
/// differences: kinks. Along a lattice segment crossing `L` lines of a family (evenly spaced),
/// one jump counts at the peak weight, the `c1 / N` term, and the rest at half of it, with the
/// cells' own twist (the bilinear's mixed term, a smooth second derivative, also half), the
/// `c2 / N²` term (src/lod/mod.rs, "One dimension").
pub const BOUND: super::bounds::TextureBound = super::bounds::TextureBound {
    max: bound_max,
    levels: bound_levels,
    slopes: bound_slopes,
};

/// `|h|` anywhere on the map: `|a| max(|b|, |1 − b|)` (heights are in `[0, 1]`).
fn bound_max(p: &SurfaceParams) -> f32 {
    let a = p.amplitude.abs();
    a * p.bias.abs().max((1.0 - p.bias).abs())
}

/// The levels [`Heightmap::sample`] reads at level of detail `lod` (the same level twice when
/// it reads one).
fn bound_levels(map: &Heightmap, lod: f32) -> [usize; 2] {
    let last = map.levels.len() - 1;
    let l0 = (lod.max(0.0).floor() as usize).min(last);
    let f = (lod.max(0.0) - l0 as f32).clamp(0.0, 1.0);
    // The second level only where the sample blends it in.
    [l0, if f == 0.0 { l0 } else { (l0 + 1).min(last) }]
}

/// `|h'|` per lattice direction of `dirs`, the kink terms (`f` times the slope's weighted jumps
/// along a lattice segment of unit size) and `|h|`, over the levels read and the texels under
/// the corners `dirs` join (all three for an element, the edge's two for an edge).
fn bound_slopes(
    p: &SurfaceParams,
    map: &Heightmap,
    levels: [usize; 2],
    uv: [Vec2; 3],
    dirs: &[usize],
    f: f32,
) -> (Vec<f32>, Chord, f32) {
    let a = p.amplitude.abs();
    let corners = dirs.iter().flat_map(|&k| [uv[k], uv[(k + 1) % 3]]);
    let (lo, hi) = corners.fold((Vec2::INFINITY, Vec2::NEG_INFINITY), |(lo, hi), c| {
        (lo.min(c), hi.max(c))
    });
    // Coordinates that are not numbers read no region (the loader refuses them in a file).
    let (lo, hi) = if uv.iter().all(|c| c.is_finite()) {
        (lo, hi)
    } else {
        (Vec2::NAN, Vec2::NAN)
    };
    let mut h1 = vec![0.0f32; dirs.len()];
    let (mut kink, mut height) = (Chord::ZERO, 0.0f32);
    let read = if levels[0] == levels[1] {
        &levels[..1]
    } else {
        &levels[..]
    };
    for &l in read {
        let lv = match MapLevel::over(map, l, lo, hi) {
            Some(lv) => lv,
            // Heights that step: bounded only where they are all one.
            None => {
                let whole = MapLevel::of(map, l);
                if whole.high > whole.low {
                    let inf = f32::INFINITY;
                    let kink = Chord { c1: inf, c2: inf };
                    return (vec![inf; dirs.len()], kink, bound_max(p));
                }
                whole
            }
        };
        let speed: Vec<Vec2> = dirs
            .iter()
            .map(|&k| ((uv[(k + 1) % 3] - uv[k]) * lv.size).abs())
            .collect();
        let s = speed.iter().fold(Vec2::ZERO, |m, &v| m.max(v));
        for (i, v) in speed.iter().enumerate() {
            h1[i] = h1[i].max(a * (lv.first.x * v.x + lv.first.y * v.y));
        }
        // One jump of each family of texel lines at the peak weight, the rest (and the cells'
        // own twist) at the mean weight, half the peak: `c2` is half the variation per unit².
        kink = kink.max(Chord {
            c1: f * a * (lv.second.x * s.x + lv.second.y * s.y),
            c2: 0.5
                * f
                * a
                * (lv.second.x * s.x * s.x + lv.second.y * s.y * s.y + 2.0 * lv.mixed * s.x * s.y),
        });
        height = height.max(a * (lv.low - p.bias).abs().max((lv.high - p.bias).abs()));
    }
    (h1, kink, height)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lcg(seed: u64) -> impl FnMut(u64) -> u64 {
        let mut s = seed;
        move |n: u64| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 33) % n
        }
    }

    /// Facts over random repeating rectangles cover each texel's own facts in the rectangle:
    /// on an odd-sized map (spans crossing the border, up to the whole map) and on a larger
    /// one with rectangles of 140 to 250 texels a side, which read the coarser block grids.
    #[test]
    fn regions_cover_their_texels() {
        for (w, h, sides, seed) in [(37u32, 20u32, 1..=37u64, 11u64), (300, 260, 140..=250, 5)] {
            let mut rnd = lcg(seed);
            let texels: Vec<f32> = (0..w * h).map(|_| rnd(1000) as f32 / 999.0).collect();
            let map = Heightmap::from_heights("random", w, h, texels.clone());
            let facts = LevelFacts::of(&map.levels[0]);
            let side = |rnd: &mut dyn FnMut(u64) -> u64, n: u32| {
                let (lo, hi) = (*sides.start(), (*sides.end()).min(n as u64));
                (lo + rnd(hi - lo + 1)) as i64 - 1
            };
            for _ in 0..60 {
                let x0 = rnd(3 * w as u64) as i64 - w as i64;
                let y0 = rnd(3 * h as u64) as i64 - h as i64;
                let x = [x0, x0 + side(&mut rnd, w)];
                let y = [y0, y0 + side(&mut rnd, h)];
                covers(&facts.over(x, y), &texels, (w, h), x, y);
            }
        }
    }

    /// `got` is at least every texel's own facts over texels `x` × `y` (repeating) of a `size`
    /// map, computed in f64 (exact for these heights).
    fn covers(got: &MapLevel, texels: &[f32], size: (u32, u32), x: [i64; 2], y: [i64; 2]) {
        let (w, h) = (size.0 as i64, size.1 as i64);
        let t = |x: i64, y: i64| texels[(y.rem_euclid(h) * w + x.rem_euclid(w)) as usize] as f64;
        for ty in y[0]..=y[1] {
            for tx in x[0]..=x[1] {
                let c = t(tx, ty);
                assert!(got.first.x as f64 >= (t(tx + 1, ty) - c).abs());
                assert!(got.first.y as f64 >= (t(tx, ty + 1) - c).abs());
                let sx = t(tx + 1, ty) + t(tx - 1, ty) - 2.0 * c;
                assert!(got.second.x as f64 >= sx.abs());
                let sy = t(tx, ty + 1) + t(tx, ty - 1) - 2.0 * c;
                assert!(got.second.y as f64 >= sy.abs());
                let m = c - t(tx + 1, ty) - t(tx, ty + 1) + t(tx + 1, ty + 1);
                assert!(got.mixed as f64 >= m.abs());
                assert!(got.low as f64 <= c && got.high as f64 >= c);
            }
        }
    }

    /// The rounding allowance where a height is tiny: `c − t10 − t01 + t11` is `1 + 2^-54`
    /// exactly for these, which f64 rounds to 1; and a flat map has no differences at all.
    #[test]
    fn differences_are_never_below_the_exact_ones() {
        let bits = [0x2963_5000u32, 0x3f7f_fffe, 0x3400_0004, 0x27e3_8000].map(f32::from_bits);
        let m = difference(&[
            (1.0, bits[0]),
            (-1.0, bits[1]),
            (-1.0, bits[2]),
            (1.0, bits[3]),
        ]);
        assert!(m > 1.0, "{m}");
        let flat = Heightmap::from_heights("flat", 5, 3, vec![0.3; 15]);
        let m = MapLevel::over(&flat, 0, Vec2::splat(0.2), Vec2::splat(0.4)).unwrap();
        assert_eq!((m.first, m.second, m.mixed), (Vec2::ZERO, Vec2::ZERO, 0.0));
        assert_eq!(MapLevel::of(&flat, 0).second, Vec2::ZERO);
    }

    /// The whole map's facts where a rectangle or a box of texture coordinates spans it, none
    /// where the coordinates are not numbers or lie far out, a part of it for a small box.
    #[test]
    fn regions_named_by_texture_coordinates() {
        let (w, h) = (37u32, 20u32);
        let mut rnd = lcg(11);
        let texels: Vec<f32> = (0..w * h).map(|_| rnd(1000) as f32 / 999.0).collect();
        let map = Heightmap::from_heights("random", w, h, texels.clone());
        let facts = LevelFacts::of(&map.levels[0]);
        let whole = MapLevel::of(&map, 0);
        assert_eq!(facts.over([-3, w as i64 - 4], [5, 4 + h as i64]), whole);
        assert_eq!(whole.low, texels.iter().copied().fold(1.0, f32::min));
        let near =
            |lo: f32, hi: f32| MapLevel::over(&map, 0, Vec2::new(lo, 0.1), Vec2::new(hi, 0.2));
        assert_eq!(near(0.0, 1.0), Some(whole));
        assert_eq!(near(-100.0, 100.0), Some(whole));
        // Not numbers, or far out (past `FAR` texels): no region.
        assert_eq!(near(f32::NAN, 0.5), None);
        assert_eq!(near(-1e30, 1e30), None);
        assert_eq!(near(1e4, 1e4), None);
        assert_ne!(near(1e3, 1e3), Some(whole));
        let small = near(0.3, 0.32).unwrap();
        assert!(small.high - small.low < whole.high - whole.low);
    }
}
