//! Chord-error bounds of the `loop` surface (its `FACTS.bound`, src/surface/bounds.rs). What the drivers draw is the tables' surface
//! (src/surface/loop.rs): exact limit points `Q` on the face's lattice of `S = 2^lmax`
//! segments per edge, interpolated linearly between them. Its bounds come from that lattice:
//! `D_k`, the largest second difference `|Q_{p−d_k} − 2 Q_p + Q_{p+d_k}|` along lattice direction
//! `k`, is a second derivative of `D_k S²` per unit of the face's parameter, which enters the
//! formulas of src/lod/mod.rs like a smooth surface's `M_k` (extraordinary vertices included:
//! the lattice points are exact there too). On an edge and at dyadic levels `N <= S` this is a
//! proof (the drawn edge samples are lattice points, and a sequence with second differences
//! `<= D` is within `H² D / 8` of its chord over `H` steps); inside the face the unit tests
//! check it against dense sampling. The mixed bound `B_k` of directions `k, k + 1` (for the
//! transition triangles, [`Bounds::mixed`]) is likewise the largest mixed difference
//! `|Q_p − Q_{p+d_k} − Q_{p+d_{k+1}} + Q_{p+d_k+d_{k+1}}|` over the lattice's parallelograms,
//! times `S²`: a second difference along a lattice vector `α d_k + β d_{k+1}` is a sum of `α²`
//! pure differences along `d_k`, `β²` along `d_{k+1}` and `2αβ` mixed ones, as the quadratic form
//! is; never above polarization's `Σ/2`. Every drawn point lies in the convex hull of the lattice
//! points, whose sphere is the patch's. Displacement over `loop` has no bound here: such elements
//! get the maximum level (one that moves nothing, [`crate::surface::SurfaceParams::moves`],
//! is bounded as none).

use crate::lod::{Bounds, Chord, Lod, Sphere, EDGE_FACTOR, ELEMENT_FACTOR};
use crate::pattern::weight;
use crate::surface::bounds::DisplaceBound;
use crate::surface::{loop_, ElementRecord, SurfaceInputs};
use glam::Vec3;

/// Loop's inputs: only `loop` declares these bounds, and a mirror of `loop` holds them.
fn inputs<'a>(lod: &Lod<'a>) -> loop_::Inputs<'a> {
    match lod.mirror.surface {
        SurfaceInputs::Loop(inputs) => inputs,
        _ => unreachable!("loop's bounds are declared by loop alone"),
    }
}

fn segments(lod: &Lod, rec: &ElementRecord) -> u32 {
    let (data, _) = inputs(lod);
    1 << (data.faces[rec.words[0] as usize][3] >> 3)
}

/// The drawn surface's point at `bary`: `loop_::eval`'s position.
fn at(lod: &Lod, rec: &ElementRecord, bary: [f32; 3]) -> Vec3 {
    let (data, frame) = inputs(lod);
    loop_::position(data, frame, rec, bary)
}

/// `|(a + c) − 2b|²`: the same bits read in either direction. The largest of these, square
/// rooted, is the largest length (the square root is monotonic, correctly rounded).
fn second2(a: Vec3, b: Vec3, c: Vec3) -> f32 {
    ((a + c) - b * 2.0).length_squared()
}

/// `|(a + d) − (b + c)|²`: the mixed difference of a lattice parallelogram `a, b, c, d` (`d`
/// opposite `a`), the same bits whichever diagonal comes first.
fn mixed2(a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> f32 {
    ((a + d) - (b + c)).length_squared()
}

fn finish(lod: &Lod, m: [f32; 3], b: Option<[f32; 3]>, factor: f32, points: &[Vec3]) -> Bounds {
    let sphere = Sphere::around(points);
    let worst = m.iter().fold(0.0f32, |a, &b| a.max(b));
    // A displacement that moves nothing (zero amplitude, or a sine or noise of frequency zero)
    // leaves the limit surface as it is, and its bound.
    let (c2, grow) = match lod.displace.facts().bound {
        DisplaceBound::Zero => (factor * worst, 0.0),
        _ if !lod.params.moves(lod.displace) => (factor * worst, 0.0),
        d => (f32::INFINITY, d.max_height(&lod.params, &sphere)),
    };
    Bounds {
        chord: Chord { c1: 0.0, c2 },
        sphere: sphere.grown(grow),
        second: m,
        // The lattice's mixed differences where given (elements), never above polarization's
        // `Σ/2` (src/lod/bound.rs, `Bounds::mixed`), which is all an edge has.
        mixed: {
            let half = 0.5 * (m[0] + m[1] + m[2]);
            b.map_or([half; 3], |b| b.map(|x| x.min(half)))
        },
        kink: Chord::ZERO,
        cone: None,
        cubic: f32::INFINITY,
    }
}

pub fn element(lod: &Lod, rec: &ElementRecord) -> Bounds {
    let s = segments(lod, rec);
    let n = s as usize + 1;
    // q(j, i): lattice point (i, j), weight i/S on corner 1, j/S on corner 2.
    let mut flat = vec![Vec3::ZERO; n * n];
    let mut points = Vec::with_capacity(n * (n + 1) / 2);
    for j in 0..=s {
        for i in 0..=s - j {
            let p = if i > 0 && j > 0 && i + j < s {
                let (data, frame) = inputs(lod);
                loop_::interior_point(data, frame, rec, i, j)
            } else {
                // On an edge or corner: its owner's point, as every driver draws it.
                at(lod, rec, [weight(s - i - j, s), weight(i, s), weight(j, s)])
            };
            flat[j as usize * n + i as usize] = p;
            points.push(p);
        }
    }
    let q = |j: usize, i: usize| flat[j * n + i];
    let mut d = [0.0f32; 3];
    let s = s as usize;
    for j in 0..=s {
        for i in 0..=s - j {
            let c = q(j, i);
            if i >= 1 && i + j < s {
                d[0] = d[0].max(second2(q(j, i - 1), c, q(j, i + 1)));
            }
            if i >= 1 && j >= 1 {
                d[1] = d[1].max(second2(q(j - 1, i + 1), c, q(j + 1, i - 1)));
            }
            if j >= 1 && i + j < s {
                d[2] = d[2].max(second2(q(j - 1, i), c, q(j + 1, i)));
            }
        }
    }
    // Mixed differences per stored pair (k, k + 1) of directions d0 = (1, 0), d1 = (−1, 1),
    // d2 = (0, −1) in (i, j): over every lattice parallelogram p, p + a, p + b, p + a + b.
    let mut b = [0.0f32; 3];
    for j in 0..=s {
        for i in 0..=s - j {
            let c = q(j, i);
            // (d0, d1): p, p + (1, 0), p + (−1, 1), p + (0, 1).
            if i >= 1 && i + j < s {
                b[0] = b[0].max(mixed2(c, q(j, i + 1), q(j + 1, i - 1), q(j + 1, i)));
            }
            // (d1, d2): p, p + (−1, 1), p + (0, −1), p + (−1, 0).
            if i >= 1 && j >= 1 {
                b[1] = b[1].max(mixed2(c, q(j + 1, i - 1), q(j - 1, i), q(j, i - 1)));
            }
            // (d2, d0): p, p + (0, −1), p + (1, 0), p + (1, −1).
            if j >= 1 && i + j < s {
                b[2] = b[2].max(mixed2(c, q(j - 1, i), q(j, i + 1), q(j - 1, i + 1)));
            }
        }
    }
    let s2 = (s * s) as f32;
    finish(
        lod,
        d.map(|x| x.sqrt() * s2),
        Some(b.map(|x| x.sqrt() * s2)),
        ELEMENT_FACTOR,
        &points,
    )
}

pub fn edge(lod: &Lod, rec: &ElementRecord, e: usize) -> Bounds {
    let s = segments(lod, rec);
    let points: Vec<Vec3> = (0..=s)
        .map(|t| {
            let mut b = [0.0f32; 3];
            b[e] = weight(s - t, s);
            b[(e + 1) % 3] = weight(t, s);
            at(lod, rec, b)
        })
        .collect();
    let d = points
        .windows(3)
        .map(|w| second2(w[0], w[1], w[2]))
        .fold(0.0f32, f32::max)
        .sqrt();
    finish(
        lod,
        [d * (s * s) as f32, 0.0, 0.0],
        None,
        EDGE_FACTOR,
        &points,
    )
}
