//! Ken Perlin's improved noise (SIGGRAPH 2002, his reference implementation): the permutation
//! table below, fade `6t⁵ − 15t⁴ + 10t³`, gradients chosen by `hash & 15`, trilinear blend with
//! the fade weights, in f32. Mirror of `glsl/include/noise.glsl`. [`noise_grad`] also returns the
//! analytic gradient (derivatives of the fade weights and of the corner gradients' dot products).

use super::bounds::Height;
use glam::Vec3;

/// Perlin's permutation of 0..=255.
pub const PERM: [u8; 256] = [
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225, 140, 36, 103, 30, 69,
    142, 8, 99, 37, 240, 21, 10, 23, 190, 6, 148, 247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219,
    203, 117, 35, 11, 32, 57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175,
    74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83, 111, 229, 122, 60, 211, 133, 230,
    220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54, 65, 25, 63, 161, 1, 216, 80, 73, 209, 76,
    132, 187, 208, 89, 18, 169, 200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198, 173,
    186, 3, 64, 52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212, 207, 206,
    59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213, 119, 248, 152, 2, 44, 154, 163,
    70, 221, 153, 101, 155, 167, 43, 172, 9, 129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232,
    178, 185, 112, 104, 218, 246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179, 162,
    241, 81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157, 184, 84, 204,
    176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93, 222, 114, 67, 29, 24, 72, 243, 141,
    128, 195, 78, 66, 215, 61, 156, 180,
];

fn perm(i: u32) -> u32 {
    PERM[(i & 255) as usize] as u32
}

/// The gradient Perlin's `grad(hash, x, y, z)` dots with `(x, y, z)`: `u = h < 8 ? x : y`,
/// `v = h < 4 ? y : (h == 12 || h == 14 ? x : z)`, signs from bits 0 and 1.
pub fn gradient(hash: u32) -> Vec3 {
    const G: [[f32; 3]; 16] = [
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
        [1.0, -1.0, 0.0],
        [-1.0, -1.0, 0.0],
        [1.0, 0.0, 1.0],
        [-1.0, 0.0, 1.0],
        [1.0, 0.0, -1.0],
        [-1.0, 0.0, -1.0],
        [0.0, 1.0, 1.0],
        [0.0, -1.0, 1.0],
        [0.0, 1.0, -1.0],
        [0.0, -1.0, -1.0],
        [1.0, 1.0, 0.0],
        [0.0, -1.0, 1.0],
        [-1.0, 1.0, 0.0],
        [0.0, -1.0, -1.0],
    ];
    Vec3::from(G[(hash & 15) as usize])
}

fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

fn dfade(t: f32) -> f32 {
    30.0 * t * t * (t * (t - 2.0) + 1.0)
}

fn lerp(t: f32, a: f32, b: f32) -> f32 {
    a + t * (b - a)
}

/// Improved noise at `p` (in [-1, 1]) and its gradient.
pub fn noise_grad(p: Vec3) -> (f32, Vec3) {
    let fl = p.floor();
    let cell = [fl.x as i32 as u32, fl.y as i32 as u32, fl.z as i32 as u32];
    let f = p - fl;
    let (u, v, w) = (fade(f.x), fade(f.y), fade(f.z));
    let a = perm(cell[0]).wrapping_add(cell[1]);
    let aa = perm(a).wrapping_add(cell[2]);
    let ab = perm(a.wrapping_add(1)).wrapping_add(cell[2]);
    let b = perm(cell[0].wrapping_add(1)).wrapping_add(cell[1]);
    let ba = perm(b).wrapping_add(cell[2]);
    let bb = perm(b.wrapping_add(1)).wrapping_add(cell[2]);
    // Corners (x, y, z) in {0, 1}³: gradient and offset from the corner.
    let corner = |h: u32, dx: f32, dy: f32, dz: f32| {
        let g = gradient(perm(h));
        let d = Vec3::new(f.x - dx, f.y - dy, f.z - dz);
        (g, g.x * d.x + g.y * d.y + g.z * d.z)
    };
    let (g000, n000) = corner(aa, 0.0, 0.0, 0.0);
    let (g100, n100) = corner(ba, 1.0, 0.0, 0.0);
    let (g010, n010) = corner(ab, 0.0, 1.0, 0.0);
    let (g110, n110) = corner(bb, 1.0, 1.0, 0.0);
    let (g001, n001) = corner(aa.wrapping_add(1), 0.0, 0.0, 1.0);
    let (g101, n101) = corner(ba.wrapping_add(1), 1.0, 0.0, 1.0);
    let (g011, n011) = corner(ab.wrapping_add(1), 0.0, 1.0, 1.0);
    let (g111, n111) = corner(bb.wrapping_add(1), 1.0, 1.0, 1.0);
    // Value: Perlin's nested lerps, in his order.
    let value = lerp(
        w,
        lerp(v, lerp(u, n000, n100), lerp(u, n010, n110)),
        lerp(v, lerp(u, n001, n101), lerp(u, n011, n111)),
    );
    // Gradient: the same trilinear blend written as a polynomial in (u, v, w).
    let k1 = n100 - n000;
    let k2 = n010 - n000;
    let k3 = n001 - n000;
    let k4 = n000 - n100 - n010 + n110;
    let k5 = n000 - n010 - n001 + n011;
    let k6 = n000 - n100 - n001 + n101;
    let k7 = -n000 + n100 + n010 - n110 + n001 - n101 - n011 + n111;
    let blend = g000
        + (g100 - g000) * u
        + (g010 - g000) * v
        + (g001 - g000) * w
        + (g000 - g100 - g010 + g110) * (u * v)
        + (g000 - g010 - g001 + g011) * (v * w)
        + (g000 - g100 - g001 + g101) * (w * u)
        + (-g000 + g100 + g010 - g110 + g001 - g101 - g011 + g111) * (u * v * w);
    let weights = Vec3::new(
        dfade(f.x) * (k1 + k4 * v + k6 * w + k7 * v * w),
        dfade(f.y) * (k2 + k4 * u + k5 * w + k7 * u * w),
        dfade(f.z) * (k3 + k5 * v + k6 * u + k7 * u * v),
    );
    (value, blend + weights)
}

/// `|noise| <=` this. The noise constants are the exact largest values over every choice of
/// the cells' corner gradients ([`noise_scan`], [`noise_scan_along`]: each quantity is linear in
/// each corner's gradient, so the worst choice is found corner by corner), at a fine grid of the
/// cell (converged to three digits between 24³ and 64³ points), with 3% added; a unit test
/// recomputes them. Improved noise reaches 1.036.
pub const NOISE_MAX: f32 = 1.07;
/// `|∇noise| <=` this: the largest derivative along any unit direction (3.75, along an axis),
/// which is the largest gradient length.
pub const NOISE_GRAD: f32 = 3.87;
/// `|∇²noise[u, u]| <=` this for every unit direction `u`: the largest second derivative along
/// any direction (14.47, near the diagonal `(1, 1, 1)/√3`). A bound of the Hessian's entries
/// (diagonal at most 12.03, off-diagonal 10.80) would give 33.6, as those maxima are not reached
/// together.
pub const NOISE_HESS: f32 = 14.9;

/// The noise displacement's height bound over sphere `s` (octave `o` adds
/// `a/2^o · noise(2^o f p)`): `|η| <= |a| · NOISE_MAX · Σ 2^−o`, `|∇η| <= |a| f · octaves ·
/// NOISE_GRAD`, `|∇²η[u, u]| <= |a| f² (2^octaves − 1) · NOISE_HESS` along every unit `u`, from
/// the noise's largest value and derivatives over every choice of corner gradients
/// ([`noise_scan`], [`noise_scan_along`]).
pub fn bound(params: &crate::surface::SurfaceParams, _: &crate::lod::Sphere) -> Height {
    // Noise of frequency zero is `noise(0) = 0` everywhere (zero on the integer lattice).
    if !params.moves(super::Displace::Noise) {
        return Height {
            max: 0.0,
            grad: 0.0,
            hess: 0.0,
            radial: None,
        };
    }
    let (a, f) = (params.amplitude.abs(), params.frequency);
    let o = params.octaves.max(1);
    let amp_sum = 2.0 - 1.0 / (1u32 << (o - 1)) as f32;
    Height {
        max: a * NOISE_MAX * amp_sum,
        grad: a * f * o as f32 * NOISE_GRAD,
        hess: a * f * f * ((1u64 << o) - 1) as f32 * NOISE_HESS,
        radial: None,
    }
}

/// The corner weight along one axis (`bit` the corner's coordinate there) at `t`, and its
/// first two derivatives: the fade or one minus it.
fn axis_weight(bit: usize, t: f32) -> [f32; 3] {
    let d2 = 60.0 * t - 180.0 * t * t + 120.0 * t * t * t;
    if bit == 1 {
        [fade(t), dfade(t), d2]
    } else {
        [1.0 - fade(t), -dfade(t), -d2]
    }
}

/// The largest improved-noise value and gradient component over every choice of corner
/// gradients, at the points of a `steps³` grid of the cell. Each quantity is `Σ_c g_c · a_c(p)`
/// with the corner gradients `g_c` chosen independently from a set closed under negation, so
/// its largest magnitude at `p` is exactly `Σ_c max_g g · a_c(p)`.
pub fn noise_scan(steps: u32) -> (f32, f32) {
    let (mut mv, mut mg) = (0.0f32, 0.0f32);
    scan_cell(steps, |corners| {
        let (mut v, mut g) = (0.0, 0.0);
        for (off, [x, y, z]) in corners {
            let wc = x[0] * y[0] * z[0];
            v += best_gradient(off * wc);
            g += best_gradient(off * (x[1] * y[0] * z[0]) + Vec3::X * wc);
        }
        mv = mv.max(v);
        mg = mg.max(g);
    });
    (mv, mg)
}

/// The largest `g · a` over Perlin's gradients `g` (a set closed under negation).
fn best_gradient(a: Vec3) -> f32 {
    (0..16).map(|h| gradient(h).dot(a)).fold(f32::MIN, f32::max)
}

/// What a scan sees of one corner at a point: the offset `p − c` and the corner's per-axis
/// weights with their first two derivatives ([`axis_weight`]).
type CornerAt = (Vec3, [[f32; 3]; 3]);

/// Calls `visit(corners)` at every point of a `steps³` grid of the cell.
fn scan_cell(steps: u32, mut visit: impl FnMut([CornerAt; 8])) {
    for ix in 0..=steps {
        for iy in 0..=steps {
            for iz in 0..=steps {
                let f = Vec3::new(ix as f32, iy as f32, iz as f32) / steps as f32;
                let corners = std::array::from_fn(|c| {
                    let bits = [c & 1, (c >> 1) & 1, (c >> 2) & 1];
                    let off = f - Vec3::new(bits[0] as f32, bits[1] as f32, bits[2] as f32);
                    let w = [0, 1, 2].map(|a| axis_weight(bits[a], f[a]));
                    (off, w)
                });
                visit(corners);
            }
        }
    }
}

/// Unit directions `(1, a, ab)/|·|` for `a`, `b` in `0, 1/n, …, 1`: every direction with
/// `x >= y >= z >= 0`. The cell, its corner weights and Perlin's twelve gradients are unchanged
/// by permuting the axes and by reflecting one (`x → 1 − x` with the corners swapped; the
/// gradient set is closed under each), and a derivative along `−u` is one along `u` negated (or
/// the same, for the second): so the largest derivatives along these directions, over the whole
/// cell, are the largest along any.
pub fn noise_directions(n: u32) -> Vec<Vec3> {
    let mut out = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            let (a, b) = (i as f32 / n as f32, j as f32 / n as f32);
            out.push(Vec3::new(1.0, a, a * b).normalize());
        }
    }
    out
}

/// The largest first and second derivatives of improved noise along unit direction `u`, over
/// every choice of corner gradients, at the points of a `steps³` grid of the cell (as
/// [`noise_scan`]): corner `c` contributes `g_c · (w_c (p − c))'`, whose derivatives along `u`
/// are `(∇w_c · u)(p − c) + w_c u` and `(uᵀ ∇²w_c u)(p − c) + 2 (∇w_c · u) u`.
pub fn noise_scan_along(steps: u32, u: Vec3) -> (f32, f32) {
    let (mut m1, mut m2) = (0.0f32, 0.0f32);
    scan_cell(steps, |corners| {
        let (mut s1, mut s2) = (0.0f32, 0.0f32);
        for (off, ws) in corners {
            // The weight's derivatives: ∂_a w = w_a' Π others, ∂_a∂_b likewise.
            let part = |a: usize, da: usize, b: usize, db: usize| {
                let mut order = [0usize; 3];
                order[a] += da;
                order[b] += db;
                ws[0][order[0]] * ws[1][order[1]] * ws[2][order[2]]
            };
            let grad = Vec3::new(part(0, 1, 0, 0), part(1, 1, 1, 0), part(2, 1, 2, 0));
            let mut huu = 0.0f32;
            for a in 0..3 {
                for b in 0..3 {
                    huu += u[a] * u[b] * part(a, 1, b, 1);
                }
            }
            let gu = grad.dot(u);
            s1 += best_gradient(off * gu + u * part(0, 0, 0, 0));
            s2 += best_gradient(off * huu + u * (2.0 * gu));
        }
        m1 = m1.max(s1);
        m2 = m2.max(s2);
    });
    (m1, m2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_is_a_permutation() {
        let mut seen = [false; 256];
        for &p in &PERM {
            assert!(!seen[p as usize], "{p} twice");
            seen[p as usize] = true;
        }
    }

    /// The value Perlin's Java reference prints for noise(3.14, 42, 7).
    #[test]
    #[allow(clippy::approx_constant)] // 3.14 is the reference's input, not π
    fn matches_the_reference_implementation() {
        let (n, _) = noise_grad(Vec3::new(3.14, 42.0, 7.0));
        assert!((n - 0.136_919_96).abs() < 1e-5, "{n}");
        // Zero on the integer lattice.
        assert_eq!(noise_grad(Vec3::new(3.0, -2.0, 5.0)).0, 0.0);
    }

    #[test]
    fn gradient_matches_finite_differences() {
        let h = 1e-3;
        for p in [
            Vec3::new(0.3, 0.7, 0.1),
            Vec3::new(-2.2, 5.5, 1.9),
            Vec3::new(10.01, -0.49, 3.3),
        ] {
            let (_, g) = noise_grad(p);
            for a in 0..3 {
                let mut e = Vec3::ZERO;
                e[a] = h;
                let fd = (noise_grad(p + e).0 - noise_grad(p - e).0) / (2.0 * h);
                assert!(
                    (fd - g[a]).abs() < 1e-2,
                    "axis {a} at {p}: {fd} vs {}",
                    g[a]
                );
            }
        }
    }

    /// The noise constants cover the scans of every corner-gradient choice, with at most 10% room:
    /// the value on a fine grid, the derivatives along every direction of the symmetry's
    /// fundamental domain on a coarser grid, then along the worst of them on a fine one.
    #[test]
    fn noise_constants_cover_the_scan() {
        let (v, g) = noise_scan(64);
        assert!(NOISE_MAX >= v && NOISE_MAX <= 1.1 * v, "value {v}");
        let (mut first, mut second) = ((0.0f32, Vec3::X), (0.0f32, Vec3::X));
        for u in noise_directions(8) {
            let (d1, d2) = noise_scan_along(16, u);
            if d1 > first.0 {
                first = (d1, u);
            }
            if d2 > second.0 {
                second = (d2, u);
            }
        }
        let (d1, _) = noise_scan_along(48, first.1);
        let (_, d2) = noise_scan_along(48, second.1);
        eprintln!(
            "noise: value {v}, along {}: {d1}, along {}: {d2}",
            first.1, second.1
        );
        assert!(NOISE_GRAD >= d1 && NOISE_GRAD <= 1.1 * d1, "gradient {d1}");
        assert!(
            NOISE_HESS >= d2 && NOISE_HESS <= 1.1 * d2,
            "second derivative {d2}"
        );
        // The largest derivative along a direction is the largest gradient component: the scans
        // agree with each other.
        assert!((d1 - g).abs() <= 1e-3 * g, "{d1} vs {g}");
        // The scan finds what sampling the real noise finds (its largest gradient component is
        // reached), so it is the noise's, not another function's.
        let (mut worst, mut worst2) = (0.0f32, 0.0f32);
        let (u, h) = (second.1, 1e-3f32);
        for i in 0..20000 {
            let p = Vec3::new(
                i as f32 * 0.0137,
                i as f32 * 0.0291 + 0.3,
                i as f32 * 0.0077 + 0.6,
            );
            let (n, grad) = noise_grad(p);
            assert!(n.abs() <= v && grad.abs().max_element() <= g);
            worst = worst.max(grad.abs().max_element());
            // The second derivative along the worst direction, by differences of the gradient.
            let along = |q: Vec3| noise_grad(q).1.dot(u);
            let d = (along(p + u * h) - along(p - u * h)) / (2.0 * h);
            assert!(d.abs() <= 1.01 * d2, "{d} at {p}");
            worst2 = worst2.max(d.abs());
        }
        assert!(worst > 0.5 * g, "{worst}");
        assert!(worst2 > 0.5 * d2, "{worst2}");
    }
}
