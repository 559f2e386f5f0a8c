// Level of detail with a guaranteed screen-space error: chord-error bounds of the local surfaces
// and the sine and noise displacements, the screen-space metric that turns them into levels,
// bounding spheres, frustum and normal-cone culling. Mirror, function for function, of src/lod
// (mod.rs, bound.rs, net.rs, cull.rs) and src/surface/displace.rs, where the proofs are;
// tests/lod_mirror.rs compares the two. Not mirrored: `stpn`'s tags, the height map's texel
// statistics, `loop`'s lattice (src/lod/bound.rs, src/surface/heightmap_bound.rs,
// src/surface/loop_bound.rs): the level pass (glsl/lod/levels.comp) reads every surface's bounds
// from the records the CPU computes once.
#ifndef LOD_GLSL
#define LOD_GLSL
#include "corners.glsl"
#include "pn.glsl"
#include "lod_metric.glsl"

const float LOD_EDGE_FACTOR = 1.0 / 8.0;
// Improved noise: largest value, derivative and second derivative along a direction
// (src/surface/noise.rs).
const float LOD_NOISE_MAX = 1.07;
const float LOD_NOISE_GRAD = 3.87;
const float LOD_NOISE_HESS = 14.9;

// ---- Bézier nets (src/lod/bound.rs `Net`) ----

struct LodNet {
    int degree;
    vec3 b[10];
};

int lod_index(int m, ivec3 w) {
    int r = m - w.x;
    return r * (r + 1) / 2 + w.z;
}

vec3 lod_at(LodNet net, ivec3 w) {
    return net.b[lod_index(net.degree, w)];
}

// Multi-index number `q` of degree m, in storage order (rows of falling i).
ivec3 lod_multi(int m, int q) {
    int r = 0;
    while ((r + 1) * (r + 2) / 2 <= q) {
        r += 1;
    }
    int k = q - r * (r + 1) / 2;
    return ivec3(m - r, r - k, k);
}

bool lod_keep(ivec3 w, int edge) {
    return edge < 0 || w[(edge + 2) % 3] == 0;
}

// sup |D^2 P[d_k, d_k]|: m(m-1) max |second differences| along k. Mirror: `Net::second`.
float lod_second(LodNet net, int k, int edge) {
    int m = net.degree;
    if (m < 2) {
        return 0.0;
    }
    int a = k, b = (k + 1) % 3;
    float best = 0.0;
    int count = (m - 1) * m / 2;
    for (int q = 0; q < count; ++q) {
        ivec3 g = lod_multi(m - 2, q);
        if (!lod_keep(g, edge)) {
            continue;
        }
        ivec3 aa = g, bb = g, ab = g;
        aa[a] += 2;
        bb[b] += 2;
        ab[a] += 1;
        ab[b] += 1;
        vec3 d = (lod_at(net, aa) + lod_at(net, bb)) - lod_at(net, ab) * 2.0;
        best = max(best, length(d));
    }
    return float(m * (m - 1)) * best;
}

// C-bar: m(m-1)(m-2) max |third differences| over any three lattice directions. Mirror:
// `Net::third`.
float lod_third(LodNet net) {
    int m = net.degree;
    if (m < 3) {
        return 0.0;
    }
    float best = 0.0;
    int count = (m - 2) * (m - 1) / 2;
    for (int q = 0; q < count; ++q) {
        ivec3 g = lod_multi(m - 3, q);
        for (int a = 0; a < 3; ++a) {
            for (int b = a; b < 3; ++b) {
                for (int c = b; c < 3; ++c) {
                    ivec3 dirs = ivec3(a, b, c);
                    vec3 sum = vec3(0.0);
                    for (int bits = 0; bits < 8; ++bits) {
                        ivec3 w = g;
                        float sign = 1.0;
                        for (int i = 0; i < 3; ++i) {
                            int k = dirs[i];
                            if (((bits >> i) & 1) == 1) {
                                w[(k + 1) % 3] += 1;
                            } else {
                                w[k] += 1;
                                sign = -sign;
                            }
                        }
                        sum += lod_at(net, w) * sign;
                    }
                    best = max(best, length(sum));
                }
            }
        }
    }
    return float(m * (m - 1) * (m - 2)) * best;
}

// sup |DP[d_k]|: m max |first differences| along k. Mirror: `Net::first`.
float lod_first(LodNet net, int k, int edge) {
    int m = net.degree;
    int a = k, b = (k + 1) % 3;
    float best = 0.0;
    int count = m * (m + 1) / 2;
    for (int q = 0; q < count; ++q) {
        ivec3 g = lod_multi(m - 1, q);
        if (!lod_keep(g, edge)) {
            continue;
        }
        ivec3 ga = g, gb = g;
        ga[a] += 1;
        gb[b] += 1;
        best = max(best, length(lod_at(net, gb) - lod_at(net, ga)));
    }
    return float(m) * best;
}

// The patch at barycentric w: its Bernstein sum written out per degree (net.b in storage
// order). Mirror: `Net::eval`.
vec3 lod_eval(LodNet net, vec3 w) {
    float x = w.x, y = w.y, z = w.z;
    if (net.degree == 0) {
        return net.b[0];
    }
    if (net.degree == 1) {
        return net.b[0] * x + net.b[1] * y + net.b[2] * z;
    }
    if (net.degree == 2) {
        return net.b[0] * (x * x) + net.b[3] * (y * y) + net.b[5] * (z * z)
             + (net.b[1] * (x * y) + net.b[2] * (x * z) + net.b[4] * (y * z)) * 2.0;
    }
    return net.b[0] * (x * x * x) + net.b[6] * (y * y * y) + net.b[9] * (z * z * z)
         + (net.b[1] * (x * x * y) + net.b[2] * (x * x * z) + net.b[3] * (x * y * y)
            + net.b[5] * (x * z * z) + net.b[7] * (y * y * z) + net.b[8] * (y * z * z)) * 3.0
         + net.b[4] * (6.0 * x * y * z);
}

#include "lod_derivatives.glsl"

// A lower bound of |P| over one lattice cell with corners a, b, c (a segment: c = b) summing
// to s, the better of the largest corner length less `step` and the corners' least projection
// on their sum's direction less the interpolation error `e`. Mirror: `Net::sampled_min_length`.
float lod_cell_min_length(vec3 a, vec3 b, vec3 c, vec3 s, float step, float e) {
    float first = max(length(a), max(length(b), length(c))) - step;
    float l2 = dot(s, s);
    vec3 u = l2 > 0.0 ? s / sqrt(l2) : vec3(0.0);
    float second = min(dot3(a, u), min(dot3(b, u), dot3(c, u))) - e;
    return max(first, second);
}

// A lower bound of |P| on a lattice of g segments per side, cell by cell. Mirror:
// `Net::sampled_min_length`.
float lod_sampled_min_length(LodNet net, int edge, int g) {
    float fg = float(g);
    float h2 = 1.0 / (fg * fg);
    float m = 3.0e38;
    if (edge >= 0) {
        float step = lod_first(net, edge, edge) / fg;
        float e = LOD_EDGE_FACTOR * lod_second(net, edge, edge) * h2;
        for (int t = 0; t < g; ++t) {
            vec3 w0 = vec3(0.0), w1 = vec3(0.0);
            w0[edge] = float(g - t) / fg;
            w0[(edge + 1) % 3] = float(t) / fg;
            w1[edge] = float(g - t - 1) / fg;
            w1[(edge + 1) % 3] = float(t + 1) / fg;
            vec3 p0 = lod_eval(net, w0), p1 = lod_eval(net, w1);
            m = min(m, lod_cell_min_length(p0, p1, p1, p0 + p1, step, e));
        }
        return m;
    }
    float step = max(lod_first(net, 0, -1), max(lod_first(net, 1, -1), lod_first(net, 2, -1))) / fg;
    float worst = max(lod_second(net, 0, -1), max(lod_second(net, 1, -1), lod_second(net, 2, -1)));
    float e = LOD_ELEMENT_FACTOR * worst * h2;
    for (int j = 0; j < g; ++j) {
        for (int i = 0; i < g - j; ++i) {
            vec3 a = lod_eval(net, vec3(float(g - i - j), float(i), float(j)) / fg);
            vec3 b = lod_eval(net, vec3(float(g - i - 1 - j), float(i + 1), float(j)) / fg);
            vec3 c = lod_eval(net, vec3(float(g - i - j - 1), float(i), float(j + 1)) / fg);
            m = min(m, lod_cell_min_length(a, b, c, a + b + c, step, e));
            if (i + j + 1 < g) {
                vec3 d = lod_eval(net, vec3(float(g - i - j - 2), float(i + 1), float(j + 1)) / fg);
                m = min(m, lod_cell_min_length(b, d, c, b + d + c, step, e));
            }
        }
    }
    return m;
}

// A lower bound of |P| over the patch. Mirror: `Net::min_length`.
float lod_min_length(LodNet net, int edge) {
    int count = (net.degree + 1) * (net.degree + 2) / 2;
    vec3 mean = vec3(0.0);
    float big = 0.0;
    for (int q = 0; q < count; ++q) {
        ivec3 w = lod_multi(net.degree, q);
        if (lod_keep(w, edge)) {
            mean += lod_at(net, w);
            big = max(big, length(lod_at(net, w)));
        }
    }
    float low = -LOD_HUGE;
    for (int c = -1; c < count; ++c) {
        vec3 axis = c < 0 ? mean : net.b[max(c, 0)];
        if (c >= 0 && !lod_keep(lod_multi(net.degree, c), edge)) {
            continue;
        }
        float l2 = dot(axis, axis);
        axis = l2 > 0.0 ? axis / sqrt(l2) : vec3(0.0);
        float along = LOD_HUGE;
        for (int q = 0; q < count; ++q) {
            ivec3 w = lod_multi(net.degree, q);
            if (lod_keep(w, edge)) {
                along = min(along, dot3(lod_at(net, w), axis));
            }
        }
        low = max(low, along);
    }
    const int grids[3] = int[3](8, 32, 128);
    // The coarsest lattice always, the finer ones while the bound is below half the patch's
    // largest |P| at its corners (the edge's own corners for an edge).
    float enough = 0.0;
    for (int q = 0; q < count; ++q) {
        ivec3 w = lod_multi(net.degree, q);
        if (lod_keep(w, edge) && max(w.x, max(w.y, w.z)) == net.degree) {
            enough = max(enough, length(lod_at(net, w)));
        }
    }
    enough *= 0.5;
    for (int i = 0; i < 3 && (i == 0 || !(low >= enough)); ++i) {
        low = max(low, lod_sampled_min_length(net, edge, grids[i]));
    }
    return max(low - 16.0 * 1.1920929e-7 * big, 0.0);
}

// A sphere around the net's points (of edge `edge`'s curve when edge >= 0). Mirror:
// `Sphere::around` over `Net::hull`.
vec4 lod_sphere(LodNet net, int edge) {
    int count = (net.degree + 1) * (net.degree + 2) / 2;
    vec3 lo = vec3(LOD_HUGE), hi = vec3(-LOD_HUGE);
    for (int q = 0; q < count; ++q) {
        ivec3 w = lod_multi(net.degree, q);
        if (lod_keep(w, edge)) {
            lo = min(lo, lod_at(net, w));
            hi = max(hi, lod_at(net, w));
        }
    }
    vec3 centre = (lo + hi) * 0.5;
    float r = 0.0;
    for (int q = 0; q < count; ++q) {
        ivec3 w = lod_multi(net.degree, q);
        if (lod_keep(w, edge)) {
            r = max(r, length(lod_at(net, w) - centre));
        }
    }
    vec3 ac = abs(centre);
    float scale = max(max(ac.x, max(ac.y, ac.z)), r);
    return vec4(centre, r + scale * (8.0 * 1.1920929e-7));
}

// ---- Surfaces (src/lod/bound.rs `surface_net`, `direction_nets`) ----

vec3 lod_phong_normal(Corners c, int i, int e) {
    return c.seam_phong[e] ? c.g[i] : c.n[i];
}

// Whether a Phong element blends two normals at a corner (no polynomial net inside).
bool lod_phong_mixed(Corners c) {
    bool mixed = false;
    for (int i = 0; i < 3; ++i) {
        int j = (i + 1) % 3, k = (i + 2) % 3;
        mixed = mixed || lod_phong_normal(c, i, edge_of(i, j)) != lod_phong_normal(c, i, edge_of(i, k));
    }
    return mixed;
}

// The surface's Bézier net on canonical corners (surface: 0 flat, 1 phong, 2 pn).
LodNet lod_surface_net(uint surface, float alpha, Corners c) {
    LodNet net;
    for (int q = 0; q < 10; ++q) {
        net.b[q] = vec3(0.0);
    }
    if (surface == 0u) {
        net.degree = 1;
        net.b[0] = c.p[0];
        net.b[1] = c.p[1];
        net.b[2] = c.p[2];
    } else if (surface == 1u) {
        net.degree = 2;
        net.b[lod_index(2, ivec3(2, 0, 0))] = c.p[0];
        net.b[lod_index(2, ivec3(0, 2, 0))] = c.p[1];
        net.b[lod_index(2, ivec3(0, 0, 2))] = c.p[2];
        for (int i = 0; i < 3; ++i) {
            int j = (i + 1) % 3;
            int lo = min(i, j), hi = max(i, j);
            int e = edge_of(lo, hi);
            vec3 ai = lod_phong_normal(c, lo, e), aj = lod_phong_normal(c, hi, e);
            vec3 k = ai * dot3(c.p[hi] - c.p[lo], ai) + aj * dot3(c.p[lo] - c.p[hi], aj);
            ivec3 w = ivec3(0);
            w[lo] = 1;
            w[hi] = 1;
            net.b[lod_index(2, w)] = (c.p[lo] + c.p[hi]) * 0.5 - k * (0.5 * alpha);
        }
    } else {
        net.degree = 3;
        vec3 e[3][3];
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
                e[i][j] = i == j ? vec3(0.0) : pn_edge(c, i, j);
            }
        }
        vec3 sum = e[0][1] + e[1][0] + e[1][2] + e[2][1] + e[0][2] + e[2][0];
        vec3 mean_e = sum * PN_SIXTH;
        vec3 mean_v = (c.p[0] + c.p[1] + c.p[2]) * PN_THIRD;
        for (int q = 0; q < 10; ++q) {
            ivec3 w = lod_multi(3, q);
            int corner = w.x == 3 ? 0 : (w.y == 3 ? 1 : (w.z == 3 ? 2 : -1));
            int two = w.x == 2 ? 0 : (w.y == 2 ? 1 : (w.z == 2 ? 2 : -1));
            int one = w.x == 1 ? 0 : (w.y == 1 ? 1 : 2);
            net.b[q] = corner >= 0 ? c.p[corner]
                     : (two >= 0 ? e[two][one] : mean_e + (mean_e - mean_v) * 0.5);
        }
    }
    return net;
}

// The unnormalized direction field displacement moves along, on the geometry normals: pn's
// normal field `field` (NORMAL_FIELD_*), linear for the other surfaces.
LodNet lod_direction_net(uint surface, uint field, Corners c) {
    Corners cg = c;
    cg.n = c.g;
    LodNet net;
    for (int q = 0; q < 10; ++q) {
        net.b[q] = vec3(0.0);
    }
    if (surface != 2u || field == NORMAL_FIELD_LINEAR) {
        net.degree = 1;
        net.b[0] = cg.n[0];
        net.b[1] = cg.n[1];
        net.b[2] = cg.n[2];
    } else {
        net.degree = 2;
        net.b[lod_index(2, ivec3(2, 0, 0))] = cg.n[0];
        net.b[lod_index(2, ivec3(0, 2, 0))] = cg.n[1];
        net.b[lod_index(2, ivec3(0, 0, 2))] = cg.n[2];
        net.b[lod_index(2, ivec3(1, 1, 0))] = pn_field_control(field, cg, 0, 1) * 0.5;
        net.b[lod_index(2, ivec3(0, 1, 1))] = pn_field_control(field, cg, 1, 2) * 0.5;
        net.b[lod_index(2, ivec3(1, 0, 1))] = pn_field_control(field, cg, 2, 0) * 0.5;
    }
    return net;
}

// Whether displacement d (1 sine, 2 noise) moves any point: not without amplitude, nor a sine
// without frequency. Mirror: src/surface/params.rs `SurfaceParams::moves`.
bool lod_moves(uint d, vec4 params) {
    return d != 0u && params.y != 0.0 && !((d == 1u || d == 2u) && params.z == 0.0);
}

// Height bounds (max, gradient, Hessian) of displacement d (1 sine, 2 noise) over sphere s.
// params: (alpha, amplitude, frequency, octaves). Mirror: `sine_bound` in
// src/surface/displace.rs, `bound` in src/surface/noise.rs.
vec3 lod_height(uint d, vec4 params, vec3 origin, vec4 s) {
    float a = abs(params.y), f = params.z;
    if (!lod_moves(d, params)) {
        return vec3(0.0); // no displacement at all
    }
    if (d == 1u) {
        float r_min = length(s.xyz - origin) - s.w;
        float tangential = r_min > 0.0 ? f / r_min : LOD_HUGE;
        return vec3(a, a * f, a * max(f * f, tangential));
    }
    if (d == 2u) {
        uint o = max(uint(params.w), 1u);
        float amp_sum = 2.0 - 1.0 / float(1u << (o - 1u));
        return vec3(a * LOD_NOISE_MAX * amp_sum, a * f * float(o) * LOD_NOISE_GRAD,
                    a * f * f * float((1u << o) - 1u) * LOD_NOISE_HESS);
    }
    return vec3(0.0);
}

// The cone of the normals of a Bézier patch's drawn triangles (xyz axis, w cosine of the
// half-angle; zero when not within a half-space), oriented as the stored corners wind (flip:
// the net's corner order is an odd permutation of the stored one). Mirror: src/lod/cull.rs
// `normal_cone`.
vec3 lod_cone_product(LodNet net, int p, int q, bool flip) {
    int m = net.degree;
    ivec3 g = lod_multi(m - 1, p), h = lod_multi(m - 1, q);
    vec3 u = lod_at(net, g + ivec3(0, 1, 0)) - lod_at(net, g + ivec3(1, 0, 0));
    vec3 v = lod_at(net, h + ivec3(0, 0, 1)) - lod_at(net, h + ivec3(1, 0, 0));
    return cross(u, v) * (flip ? -1.0 : 1.0);
}

vec4 lod_normal_cone(LodNet net, bool flip) {
    int count = net.degree * (net.degree + 1) / 2;
    vec3 sum = vec3(0.0);
    for (int p = 0; p < count; ++p) {
        for (int q = 0; q < count; ++q) {
            vec3 c = lod_cone_product(net, p, q, flip);
            sum += c != vec3(0.0) ? normalize(c) : vec3(0.0);
        }
    }
    if (sum == vec3(0.0)) {
        return vec4(0.0);
    }
    vec3 axis = normalize(sum);
    float cs = 1.0;
    for (int p = 0; p < count; ++p) {
        for (int q = 0; q < count; ++q) {
            vec3 c = lod_cone_product(net, p, q, flip);
            cs = c != vec3(0.0) ? min(cs, dot(normalize(c), axis)) : cs;
        }
    }
    cs -= 1e-5;
    return cs > 0.0 ? vec4(axis, cs) : vec4(0.0);
}

// What an element (edge < 0) or canonical edge 0 (edge = 0) is bounded by.
struct LodBounds {
    vec2 chord;  // (c1, c2)
    vec4 sphere; // centre, radius
    vec3 second; // per canonical direction (element) or the curve's in x (edge)
    vec4 cone;   // axis, cosine of the half-angle (w <= 0: none)
    float cubic; // a polynomial patch's cubic term (LOD_HUGE: none)
};

// Bounds of a local surface (0 flat, 1 phong, 2 pn; pn with normal field `field`) with
// displacement d (0 none, 1 sine, 2 noise) on canonical corners c. Mirror: src/lod/bound.rs
// `Lod::local` (without `stpn` and the height map).
LodBounds lod_local(uint surface, uint field, uint d, vec4 params, vec3 origin, Corners c, int edge) {
    // Phong at alpha 0 is the flat triangle exactly, blended seam normals or not.
    bool exact = surface != 1u || edge >= 0 || params.x == 0.0 || !lod_phong_mixed(c);
    LodNet net = lod_surface_net(exact ? surface : 0u, params.x, c);
    vec4 sphere = lod_sphere(net, edge);
    if (!exact) {
        float longest = max(length(c.p[1] - c.p[0]), max(length(c.p[2] - c.p[1]), length(c.p[0] - c.p[2])));
        sphere.w += params.x * longest;
    }
    vec3 m = vec3(0.0);
    float grow = 0.0;
    for (int k = 0; k < 3; ++k) {
        if (edge >= 0 && k != edge) {
            continue;
        }
        m[k] = exact ? lod_second(net, k, edge) : LOD_HUGE;
    }
    if (d == 1u || d == 2u) {
        vec3 h = lod_height(d, params, origin, sphere);
        LodNet dn = lod_direction_net(surface, field, c);
        float rho = lod_min_length(dn, edge);
        vec3 firsts = vec3(0.0);
        for (int k = 0; k < 3; ++k) {
            if (edge < 0 || k == edge) {
                firsts[k] = lod_first_sup(net, k, edge);
            }
        }
        for (int k = 0; k < 3; ++k) {
            if (edge >= 0 && k != edge) {
                continue;
            }
            float v = firsts[k], mk = lod_second(net, k, edge);
            float h1 = h.y * v, h2 = h.z * v * v + h.y * mk;
            // The sine's height of the distance from its origin. Mirror: `radial_height`.
            float curve = abs(params.y) * params.z * params.z;
            float dist = length(sphere.xyz - origin);
            float r_min = dist - sphere.w, r_max = dist + sphere.w;
            if (d == 1u && h != vec3(0.0) && r_min > 0.0 && curve * r_min >= h.y) {
                float rate = min(lod_radial_first(net, k, edge, origin, r_max, firsts) / r_min, v);
                float second = curve * rate * rate + h.y * (v * v - rate * rate) / r_min + h.y * mk;
                h1 = min(h1, h.y * rate);
                h2 = min(h2, second);
            }
            float n1 = lod_first(dn, k, edge), n2 = lod_second(dn, k, edge);
            // Nothing moves (all three zero): nothing added, whatever the direction field.
            m[k] += h == vec3(0.0) ? 0.0
                  : rho > 0.0 ? h2 + 2.0 * h1 * n1 / rho + h.x * (n2 / rho + 2.0 * n1 * n1 / (rho * rho))
                  : LOD_HUGE;
        }
        grow = h.x;
    }
    float worst = min(max(m.x, max(m.y, m.z)), LOD_HUGE);
    LodBounds b;
    b.chord = vec2(0.0, worst < LOD_HUGE ? (edge >= 0 ? LOD_EDGE_FACTOR : LOD_ELEMENT_FACTOR) * worst : LOD_HUGE);
    b.sphere = vec4(sphere.xyz, sphere.w + grow);
    b.second = m;
    // Canonical order c.o an odd permutation of the stored corners: the orientation flips.
    bool odd = !((c.o[0] == 0 && c.o[1] == 1) || (c.o[0] == 1 && c.o[1] == 2) || (c.o[0] == 2 && c.o[1] == 0));
    b.cone = (edge < 0 && exact && !lod_moves(d, params)) ? lod_normal_cone(net, odd) : vec4(0.0);
    // Mirror: `Bounds::cubic` (src/lod/mod.rs, "A polynomial patch").
    b.cubic = (edge < 0 && exact && !lod_moves(d, params)) ? LOD_CUBIC_FACTOR * lod_third(net) : LOD_HUGE;
    return b;
}

// Element bounds of a corner record. Mirror: `Lod::element`.
LodBounds lod_element(uint surface, uint field, uint d, vec4 params, vec3 origin, CornerRecord r) {
    return lod_local(surface, field, d, params, origin, canonical(r, vec3(1.0 / 3.0)), -1);
}

// Bounds of stored edge e (corners e, e + 1): the same bits from both elements that have it.
// Mirror: `Lod::edge`.
LodBounds lod_edge(uint surface, uint field, uint d, vec4 params, vec3 origin, CornerRecord r, int e) {
    vec3 bary = vec3(0.5);
    bary[(e + 2) % 3] = 0.0;
    return lod_local(surface, field, d, params, origin, canonical(r, bary), 0);
}

#endif
