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
//! points, whose sphere is the patch's.
//!
//! # Levels whose samples are not lattice points
//! A drawn segment whose ends are not lattice points cuts the lattice's kinks unevenly: a
//! kink near its middle weighs up to twice what the second differences, read as a second
//! derivative, give it (src/lod/mod.rs, "One dimension": jumps `J` spaced `δ` weigh
//! `J t(1 − t)(h/δ)/2` on average, one of them up to `J t(1 − t)`). Over `k = S/N` lattice
//! steps the worst case is `1 + 1/k²` times `H² D / 8` with every jump at `D`, and the tables'
//! surface comes close to it: on Spot's M1 faces an edge drawn at level 6, 12, 24, 31 or 40 is
//! up to 1.03, 1.13, 1.5, 1.9 or 2.5 times that bound, lattice triangles up to 1.07 times theirs
//! at levels 30 and 31 and 2.3 times at 48. So where a driver's levels are not powers of two
//! (its edges' samples are not lattice points: [`Rounding::dyadic`]), an edge's curve takes
//! the kink terms that hold at every level, the peak weight of one jump, `c1 = S D / 4`
//! (src/lod/mod.rs, "One dimension", with `J = S D` per unit parameter; at most one jump per
//! segment past level `S`): a proof. Where the drawn inside's vertices are not lattice points
//! (every rounding but the pattern driver's powers of two, [`Rounding::Snapped`]: integer
//! levels, and the tessellator's rings, which sit between the lattice's rows) the element's
//! chord and kink terms take `c1 = S max_k D_k / 4` ([`INSIDE_KINK`]). That one is checked
//! against dense sampling of lattice triangles at integer levels 3, 6, 12, 24, 31, 40 and 63
//! (`loop_bounds_hold`) and end to end on the tessellator's rings (`pixel_error_holds_end_to_end`),
//! not proven: a bound from each family's jumps (`25/64 · S Σ_f B_f`, `B_f` the mixed
//! differences) would be, and would draw Spot's close-up at integer levels with about four
//! times the triangles. At the pattern driver's powers of two the lattice triangles' vertices
//! are lattice points up to level `S` (past it each triangle lies in one cell), and the bounds
//! are those above; its transition triangles, whose vertices are lattice points but whose
//! sides cut cells, are checked end to end only.
//!
//! # Displaced
//! A height of the point (`sine`, `noise`) moves the drawn point `P` along `N = n/|n|`, `n` the
//! sum of M1's normals that subdivision shading interpolates: `D = P + h(P) N`. Both `P` and `n`
//! are linear inside each lattice cell (the drivers interpolate the cell's three table rows), so
//! there `P'' = 0`, `P' = S ΔP` and `n' = S Δn` along a lattice side (`Δ` the difference of its
//! two lattice points), `n'' = 0`, and the displacement's chain rule (src/lod/bound.rs
//! `moved_second`: `|h'| <= G |P'|`, `|h''| <= H |P'|²`, `|N'| <= |n'|/ρ`,
//! `|N''| <= 2|n'|²/ρ²`, `ρ` a lower bound of `|n|` over the cell) bounds `|D''|` inside every
//! cell by `E_k`, the largest over the cells along lattice direction `k`. The bounds are then
//! `M_k = S² D_k + E_k`, `D_k` the largest second difference of the displaced lattice points
//! (and the mixed ones likewise, with the displacement's own mixed term by polarization,
//! `ΣE/2`). On an edge at dyadic levels `N <= S` this is again a proof: the drawn samples are
//! lattice points, whose polyline is within `H² D/8` of the chord over `H` steps, and the curve
//! within `E/(8S²) <= E/(8N²)` of that polyline; at dyadic levels `N >= S` every drawn segment
//! lies in one cell, where `|D''| <= E`. Where the samples are not lattice points the curve
//! is off its lattice polyline at both ends of a segment too (`2E/(8S²)`), and a one-sided
//! derivative of `D` differs from its cell's chord slope by up to `E/(2S)`, so a jump is at
//! most `S D + E/S`: `M` takes `2E` and the peak term `(S D + E/S)/4` (`E/S` likewise in an
//! element's). Inside the face the unit tests check it against dense sampling, as for the
//! undisplaced surface. Where `ρ` is not positive (M1's normals may cancel,
//! and the drawn direction falls back to one control vertex's), or for a displacement this
//! module does not bound (a height map: `loop` has no texture coordinates), the bound is
//! infinite and the element gets the maximum level. A displacement that moves nothing
//! ([`crate::surface::SurfaceParams::moves`]) is bounded as none.

use crate::lod::bound::moved_second;
use crate::lod::frame::Rounding;
use crate::lod::{Bounds, Chord, Lod, Sphere, EDGE_FACTOR, EDGE_KINK_FACTOR, ELEMENT_FACTOR};
use crate::pattern::weight;
use crate::surface::bounds::{DisplaceBound, Height};
use crate::surface::{loop_, ElementRecord, SurfaceInputs, FIELD_MIN2};
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

/// An element's kink terms per unit size (times `S` and the largest raw second difference):
/// the peak weight of one jump, where the drawn inside's vertices are not lattice points
/// (module notes).
pub const INSIDE_KINK: f32 = 0.25;

/// Whether a driver rounding as `rounding` draws its edges' samples on lattice points (powers
/// of two), and its insides' vertices there too (the pattern driver's powers of two; the
/// tessellator's rings are not) (module notes): what loop's bounds depend on.
pub fn aligned(rounding: Rounding) -> (bool, bool) {
    (rounding.dyadic(), rounding == Rounding::Snapped)
}

/// Whether the displacement moves the surface (module notes, "Displaced").
fn moves(lod: &Lod) -> bool {
    !matches!(lod.displace.facts().bound, DisplaceBound::Zero) && lod.params.moves(lod.displace)
}

/// A lattice point: the undisplaced point, every driver's bits, and where a displacement moves
/// the surface, M1's normal sum there (zero otherwise) and the drawn (displaced) point.
#[derive(Clone, Copy, Default)]
struct Moved {
    p: Vec3,
    n: Vec3,
    drawn: Vec3,
}

fn moved_at(lod: &Lod, rec: &ElementRecord, bary: [f32; 3]) -> Moved {
    let (data, frame) = inputs(lod);
    let (p, n) = loop_::position_and_field(data, frame, rec, bary);
    Moved {
        p,
        n,
        drawn: lod.mirror.eval(&lod.params, 0, rec, bary).position,
    }
}

/// The height's bounds over `sphere` (the undisplaced patch's), `None` for a displacement this
/// module does not bound.
fn height(lod: &Lod, sphere: &Sphere) -> Option<Height> {
    match lod.displace.facts().bound {
        DisplaceBound::OfPoint(f) => Some(f(&lod.params, sphere)),
        _ => None,
    }
}

/// A lower bound of `|n|` over the convex hull of `ns`: with `u` the unit vector along their
/// sum, every point `x` of the hull has `|x| >= x · u >= min n_c · u`, less a margin for the
/// rounding of the sums; zero where that does not keep `|n|²` above `FIELD_MIN2` (where the
/// drawn direction may be a control vertex's instead, not continuous).
fn least_length(ns: &[Vec3]) -> f32 {
    let u = ns
        .iter()
        .fold(Vec3::ZERO, |a, &b| a + b)
        .normalize_or_zero();
    let low = ns.iter().map(|&n| n.dot(u)).fold(f32::INFINITY, f32::min);
    let big = ns.iter().map(|n| n.length()).fold(0.0, f32::max);
    let rho = low - 16.0 * f32::EPSILON * big;
    if rho * rho > 4.0 * FIELD_MIN2 {
        rho
    } else {
        0.0
    }
}

/// `|D''|` inside a lattice cell along its side from `a` to `b`, the cell's `|n|` at least `rho`
/// (module notes, "Displaced"; `s` the lattice's segments).
fn inside_cell(h: &Height, s: f32, a: &Moved, b: &Moved, rho: f32) -> f32 {
    let v = (b.p - a.p).length() * s;
    let n1 = (b.n - a.n).length() * s;
    moved_second(h.grad * v, h.hess * v * v, h.max, n1, 0.0, rho)
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

/// The bounds from `M_k` (`m`), the lattice's mixed bounds where given (elements) and the
/// sphere holding the drawn patch.
fn finish(m: [f32; 3], b: Option<[f32; 3]>, factor: f32, sphere: Sphere) -> Bounds {
    let worst = m.iter().fold(0.0f32, |a, &b| a.max(b));
    Bounds {
        chord: Chord {
            c1: 0.0,
            c2: factor * worst,
        },
        sphere,
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

/// The largest squared second differences along the stored directions and mixed differences
/// of the stored pairs, over the lattice `q(j, i)` of `s` segments (module notes).
fn differences(s: usize, q: impl Fn(usize, usize) -> Vec3) -> ([f32; 3], [f32; 3]) {
    let mut d = [0.0f32; 3];
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
    (d, b)
}

/// `E_k` over the face's lattice cells `q(j, i)` of `s` segments (module notes, "Displaced").
fn inside_cells(h: &Height, s: usize, q: impl Fn(usize, usize) -> Moved) -> [f32; 3] {
    let mut e = [0.0f32; 3];
    let sf = s as f32;
    // A cell's three sides, each with its stored direction.
    let mut cell = |sides: [(usize, Moved, Moved); 3]| {
        let rho = least_length(&[sides[0].1.n, sides[1].1.n, sides[2].1.n]);
        for (k, a, b) in sides {
            e[k] = e[k].max(inside_cell(h, sf, &a, &b, rho));
        }
    };
    for j in 0..s {
        for i in 0..s - j {
            // (i, j), (i + 1, j), (i, j + 1): sides (1, 0), (−1, 1), (0, 1).
            let (a, b, c) = (q(j, i), q(j, i + 1), q(j + 1, i));
            cell([(0, a, b), (1, b, c), (2, c, a)]);
            if i + j + 2 <= s {
                // (i, j + 1), (i + 1, j + 1), (i + 1, j): sides (1, 0), (0, −1), (−1, 1).
                let (a, b, c) = (q(j + 1, i), q(j + 1, i + 1), q(j, i + 1));
                cell([(0, a, b), (2, b, c), (1, c, a)]);
            }
        }
    }
    e
}

pub fn element(lod: &Lod, rec: &ElementRecord) -> Bounds {
    let s = segments(lod, rec);
    let n = s as usize + 1;
    let moving = moves(lod);
    let (data, frame) = inputs(lod);
    let face = loop_::FaceRows::new(data, frame, rec);
    // q(j, i): lattice point (i, j), weight i/S on corner 1, j/S on corner 2: the drawn points
    // (`grid`), and where a displacement moves them each point's `Moved` too; `points`, the
    // undisplaced ones in order, for the sphere.
    let mut grid = vec![Vec3::ZERO; n * n];
    let mut moved = if moving {
        vec![Moved::default(); n * n]
    } else {
        Vec::new()
    };
    let mut points = Vec::with_capacity(n * (n + 1) / 2);
    for j in 0..=s {
        for i in 0..=s - j {
            let bary = [weight(s - i - j, s), weight(i, s), weight(j, s)];
            let at_point = j as usize * n + i as usize;
            let p = if moving {
                let m = moved_at(lod, rec, bary);
                moved[at_point] = m;
                grid[at_point] = m.drawn;
                m.p
            } else if i == 0 || j == 0 || i + j == s {
                // On an edge or corner: its owner's point, as every driver draws it.
                let p = at(lod, rec, bary);
                grid[at_point] = p;
                p
            } else {
                // Inside: filled a run at a time at its first point (below).
                if i == 1 {
                    let row = &mut grid[at_point..at_point + (s - j - 1) as usize];
                    for (r, run) in row.chunks_mut(loop_::FaceRows::RUN).enumerate() {
                        face.points(1 + (r * loop_::FaceRows::RUN) as u32, j, run);
                    }
                }
                grid[at_point]
            };
            points.push(p);
        }
    }
    let s = s as usize;
    let (d, b) = differences(s, |j, i| grid[j * n + i]);
    let s2 = (s * s) as f32;
    let (mut m, mut b) = (d.map(|x| x.sqrt() * s2), b.map(|x| x.sqrt() * s2));
    let mut sphere = Sphere::around(&points);
    let inside = aligned(lod.rounding).1;
    let mut e = [0.0f32; 3];
    if moving {
        e = height(lod, &sphere).map_or([f32::INFINITY; 3], |h| {
            sphere = sphere.grown(h.max);
            inside_cells(&h, s, |j, i| moved[j * n + i])
        });
        // Twice where the drawn vertices are not lattice points (module notes, "Displaced").
        let times = if inside { 1.0 } else { 2.0 };
        // The displacement's own mixed term by polarization of its directional ones, as in
        // src/lod/bound.rs.
        let half = times * 0.5 * (e[0] + e[1] + e[2]);
        for k in 0..3 {
            m[k] += times * e[k];
            b[k] += half;
        }
    }
    let mut bounds = finish(m, Some(b), ELEMENT_FACTOR, sphere);
    if !inside {
        // The peak weight of one jump where the drawn triangles cut cells (module notes).
        let most = |x: [f32; 3]| x.iter().fold(0.0f32, |a, &y| a.max(y));
        let c1 = INSIDE_KINK * (s as f32 * most(d.map(f32::sqrt)) + most(e) / s as f32);
        bounds.chord.c1 = c1;
        bounds.kink.c1 = c1;
    }
    bounds
}

pub fn edge(lod: &Lod, rec: &ElementRecord, e: usize) -> Bounds {
    let s = segments(lod, rec);
    let moving = moves(lod);
    let samples: Vec<Moved> = (0..=s)
        .map(|t| {
            let mut b = [0.0f32; 3];
            b[e] = weight(s - t, s);
            b[(e + 1) % 3] = weight(t, s);
            if moving {
                moved_at(lod, rec, b)
            } else {
                let p = at(lod, rec, b);
                Moved {
                    p,
                    n: Vec3::ZERO,
                    drawn: p,
                }
            }
        })
        .collect();
    let d = (samples.windows(3))
        .map(|w| second2(w[0].drawn, w[1].drawn, w[2].drawn))
        .fold(0.0f32, f32::max)
        .sqrt();
    let points: Vec<Vec3> = samples.iter().map(|m| m.p).collect();
    let mut sphere = Sphere::around(&points);
    let on_lattice = aligned(lod.rounding).0;
    let e = if moving {
        height(lod, &sphere).map_or(f32::INFINITY, |h| {
            sphere = sphere.grown(h.max);
            (samples.windows(2))
                .map(|w| {
                    let rho = least_length(&[w[0].n, w[1].n]);
                    inside_cell(&h, s as f32, &w[0], &w[1], rho)
                })
                .fold(0.0f32, f32::max)
        })
    } else {
        0.0
    };
    // Twice where the samples are not lattice points (module notes, "Displaced").
    let times = if on_lattice { 1.0 } else { 2.0 };
    let m = d * (s * s) as f32 + times * e;
    let mut bounds = finish([m, 0.0, 0.0], None, EDGE_FACTOR, sphere);
    if !on_lattice {
        // Samples between lattice points (module notes): the peak weight of one jump,
        // `(S D + E/S)/4`.
        bounds.chord.c1 = EDGE_KINK_FACTOR * (s as f32 * d + e / s as f32);
        bounds.kink.c1 = bounds.chord.c1;
    }
    bounds
}
