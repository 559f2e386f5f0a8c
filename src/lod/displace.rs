//! Bounds of the displacements' heights (src/surface/displace.rs): the procedural heights'
//! largest value, gradient and Hessian over a sphere, and the height map's largest texel
//! differences per pyramid level. How they enter the chord error is in src/lod/bound.rs and the
//! proofs in src/lod/mod.rs.

use super::Sphere;
use crate::surface::{Displace, Heightmap, SurfaceParams};
use glam::{Vec2, Vec3};

/// Bounds of a height `η(p)` of the point over a sphere: `|η| <= max`, `|∇η| <= grad`,
/// `‖∇²η‖ <= hess`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Height {
    pub max: f32,
    pub grad: f32,
    pub hess: f32,
}

/// `|noise| <=` this. The noise constants are the exact largest values over every choice of
/// the cells' corner gradients ([`noise_scan`]: each quantity is linear in each corner's
/// gradient, so the worst choice is found corner by corner), at a fine grid of the cell
/// (converged to four digits between 48³ and 128³ points), with 3% added; a unit test
/// recomputes them. Improved noise reaches 1.036.
pub const NOISE_MAX: f32 = 1.07;
/// `|∇noise| <= √3 ·` the largest gradient component (3.75, reached).
pub const NOISE_GRAD: f32 = 3.87 * 1.732_051;
/// `‖∇²noise‖ <=` the largest row sum of the Hessian: diagonal entries at most 12.03,
/// off-diagonal 10.80.
pub const NOISE_HESS: f32 = 1.03 * (12.034 + 2.0 * 10.799);

/// Bounds of the procedural heights over sphere `s` (in the mesh's coordinates).
pub fn height(d: Displace, params: &SurfaceParams, s: &Sphere) -> Height {
    let (a, f) = (params.amplitude.abs(), params.frequency);
    match d {
        Displace::None | Displace::Heightmap => Height {
            max: 0.0,
            grad: 0.0,
            hess: 0.0,
        },
        Displace::Sine => {
            // η = a sin(f r): radial curvature −a f² sin(f r), tangential a f cos(f r) / r.
            let r_min = (s.centre - params.origin).length() - s.radius;
            let tangential = if r_min > 0.0 {
                f / r_min
            } else {
                f32::INFINITY
            };
            Height {
                max: a,
                grad: a * f,
                hess: a * (f * f).max(tangential),
            }
        }
        Displace::Noise => {
            let o = params.octaves.max(1);
            let amp_sum = 2.0 - 1.0 / (1u32 << (o - 1)) as f32;
            Height {
                max: a * NOISE_MAX * amp_sum,
                grad: a * f * o as f32 * NOISE_GRAD,
                hess: a * f * f * ((1u64 << o) - 1) as f32 * NOISE_HESS,
            }
        }
    }
}

/// The largest texel differences of one pyramid level (coordinates repeat, so the differences
/// wrap around too).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapLevel {
    pub size: Vec2,
    /// Largest `|t(x+1) − t(x)|` along x and along y.
    pub first: Vec2,
    /// Largest `|t(x+1) − 2 t(x) + t(x−1)|` along x and along y.
    pub second: Vec2,
    /// Largest `|t00 − t10 − t01 + t11|`.
    pub mixed: f32,
}

impl MapLevel {
    pub fn of(map: &Heightmap, l: usize) -> MapLevel {
        let lv = &map.levels[l];
        let (w, h) = (lv.w as i64, lv.h as i64);
        let t = |x: i64, y: i64| lv.texels[(y.rem_euclid(h) * w + x.rem_euclid(w)) as usize];
        let (mut first, mut second, mut mixed) = (Vec2::ZERO, Vec2::ZERO, 0.0f32);
        for y in 0..h {
            for x in 0..w {
                let c = t(x, y);
                first = first.max(Vec2::new((t(x + 1, y) - c).abs(), (t(x, y + 1) - c).abs()));
                second = second.max(Vec2::new(
                    (t(x + 1, y) + t(x - 1, y) - 2.0 * c).abs(),
                    (t(x, y + 1) + t(x, y - 1) - 2.0 * c).abs(),
                ));
                mixed = mixed.max((c - t(x + 1, y) - t(x, y + 1) + t(x + 1, y + 1)).abs());
            }
        }
        // Room for the rounding of the f32 sums above.
        let pad = 8.0 * f32::EPSILON;
        MapLevel {
            size: Vec2::new(lv.w as f32, lv.h as f32),
            first: first + pad,
            second: second + pad,
            mixed: mixed + pad,
        }
    }
}

/// Perlin's gradients (the 12 distinct ones of the 16-entry table).
fn noise_gradients() -> Vec<Vec3> {
    let mut g: Vec<Vec3> = (0..16).map(crate::surface::noise::gradient).collect();
    g.sort_by(|a, b| a.to_array().partial_cmp(&b.to_array()).unwrap());
    g.dedup();
    g
}

/// The largest improved-noise value, gradient component, Hessian diagonal and off-diagonal
/// entry over every choice of corner gradients, at the points of a `steps³` grid of the cell.
/// Each quantity is `Σ_c g_c · a_c(p)` with the corner gradients `g_c` chosen independently
/// from a set closed under negation, so its largest magnitude at `p` is exactly
/// `Σ_c max_g g · a_c(p)`.
pub fn noise_scan(steps: u32) -> (f32, f32, f32, f32) {
    let gs = noise_gradients();
    let best = |a: Vec3| gs.iter().map(|g| g.dot(a)).fold(f32::MIN, f32::max);
    let fade = |t: f32| t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
    let d1 = |t: f32| 30.0 * t * t * (t * (t - 2.0) + 1.0);
    let d2 = |t: f32| 60.0 * t - 180.0 * t * t + 120.0 * t * t * t;
    // Per axis and corner bit: the weight and its first two derivatives.
    let w = |bit: usize, t: f32| {
        if bit == 1 {
            [fade(t), d1(t), d2(t)]
        } else {
            [1.0 - fade(t), -d1(t), -d2(t)]
        }
    };
    let (mut mv, mut mg, mut md, mut mo) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
    for ix in 0..=steps {
        for iy in 0..=steps {
            for iz in 0..=steps {
                let f = Vec3::new(ix as f32, iy as f32, iz as f32) / steps as f32;
                let (mut v, mut g, mut d, mut o) = (0.0, 0.0, 0.0, 0.0);
                for c in 0..8usize {
                    let bits = [c & 1, (c >> 1) & 1, (c >> 2) & 1];
                    let off = f - Vec3::new(bits[0] as f32, bits[1] as f32, bits[2] as f32);
                    let (x, y, z) = (w(bits[0], f.x), w(bits[1], f.y), w(bits[2], f.z));
                    let wc = x[0] * y[0] * z[0];
                    v += best(off * wc);
                    g += best(off * (x[1] * y[0] * z[0]) + Vec3::X * wc);
                    d += best(off * (x[2] * y[0] * z[0]) + Vec3::X * (2.0 * x[1] * y[0] * z[0]));
                    o += best(
                        off * (x[1] * y[1] * z[0])
                            + Vec3::Y * (x[1] * y[0] * z[0])
                            + Vec3::X * (x[0] * y[1] * z[0]),
                    );
                }
                mv = mv.max(v);
                mg = mg.max(g);
                md = md.max(d);
                mo = mo.max(o);
            }
        }
    }
    (mv, mg, md, mo)
}
