// Tighter bounds of a Bézier net's derivatives than its hull: the derivative's net sampled on a
// small lattice plus that net's own chord bound (`lod_first_sup`), and the rate a distance from
// a point changes (`lod_radial_first`, what the sine's bound reads). Part of lod.glsl, included
// after the nets' differences and evaluation it uses. Mirror: src/lod/net.rs.
#ifndef LOD_DERIVATIVES_GLSL
#define LOD_DERIVATIVES_GLSL

// Segments a side of the lattice lod_first_sup samples a cubic's derivative on. Mirror:
// `FIRST_GRID`.
const int LOD_FIRST_GRID = 4;

// The derivative along direction k as a net of degree m - 1. Mirror: `Net::hodograph`.
LodNet lod_hodograph(LodNet net, int k) {
    int m = net.degree;
    int a = k, b = (k + 1) % 3;
    LodNet h;
    h.degree = m - 1;
    for (int q = 0; q < 10; ++q) {
        h.b[q] = vec3(0.0);
    }
    for (int q = 0; q < m * (m + 1) / 2; ++q) {
        ivec3 g = lod_multi(m - 1, q);
        ivec3 ga = g, gb = g;
        ga[a] += 1;
        gb[b] += 1;
        h.b[q] = (lod_at(net, gb) - lod_at(net, ga)) * float(m);
    }
    return h;
}

// The sample points of Net::sampled_sup: the lattice of LOD_FIRST_GRID segments a side (the
// edge's points with edge >= 0), point q of lod_sample_count.
int lod_sample_count(int edge) {
    int g = LOD_FIRST_GRID;
    return edge >= 0 ? g + 1 : (g + 1) * (g + 2) / 2;
}

vec3 lod_sample_point(int edge, int q) {
    int g = LOD_FIRST_GRID;
    float step = 1.0 / float(g);
    if (edge >= 0) {
        vec3 w = vec3(0.0);
        w[(edge + 1) % 3] = float(q) * step;
        w[edge] = float(g - q) * step;
        return w;
    }
    int i = 0;
    while (q > g - i) {
        q -= g - i + 1;
        i += 1;
    }
    return vec3(float(g - i - q) * step, float(i) * step, float(q) * step);
}

// The bound from the samples' largest value `best`, the second derivatives' `second` and the
// samples' rounding.
// Mirror: `Net::sampled_sup`.
float lod_sampled_sup(float best, float second, float rounding, int edge) {
    float step = 1.0 / float(LOD_FIRST_GRID);
    float factor = edge >= 0 ? LOD_EDGE_FACTOR : LOD_ELEMENT_FACTOR;
    return (best + rounding + factor * second * (step * step)) * (1.0 + 1.0 / 65536.0);
}

// f32's machine epsilon (Rust's f32::EPSILON).
const float LOD_EPSILON = 1.1920929e-7;

// The largest of a net's second-derivative bounds over the directions a bound runs over.
float lod_second_over(LodNet net, int edge) {
    return edge >= 0 ? lod_second(net, edge, edge)
                     : max(lod_second(net, 0, -1), max(lod_second(net, 1, -1), lod_second(net, 2, -1)));
}

// sup |DP[d_k]| as lod_first bounds it, or tighter for a cubic: the hodograph's largest value
// on the lattice plus its chord bound. Mirror: `Net::first_sup`.
float lod_first_sup(LodNet net, int k, int edge) {
    float hull = lod_first(net, k, edge);
    if (net.degree < 3) {
        return hull;
    }
    LodNet h = lod_hodograph(net, k);
    float best = 0.0;
    for (int q = 0; q < lod_sample_count(edge); ++q) {
        best = max(best, length(lod_eval(h, lod_sample_point(edge, q))));
    }
    float rounding = 8.0 * LOD_EPSILON * hull;
    return min(hull, lod_sampled_sup(best, lod_second_over(h, edge), rounding, edge));
}

// Point g + e_x + e_y of the net.
vec3 lod_at2(LodNet net, ivec3 g, int x, int y) {
    g[x] += 1;
    g[y] += 1;
    return lod_at(net, g);
}

// sup |D²P[d_k, d_{k+1}]|. Mirror: `Net::mixed`.
float lod_mixed(LodNet net, int k) {
    int m = net.degree;
    if (m < 2) {
        return 0.0;
    }
    int a = k, b = (k + 1) % 3, c = (k + 2) % 3;
    float best = 0.0;
    for (int q = 0; q < (m - 1) * m / 2; ++q) {
        ivec3 g = lod_multi(m - 2, q);
        vec3 d = (lod_at2(net, g, b, c) + lod_at2(net, g, a, b))
               - (lod_at2(net, g, b, b) + lod_at2(net, g, a, c));
        best = max(best, length(d));
    }
    return float(m * (m - 1)) * best;
}

// sup |(P - o) . DP[d_k]|, r_max >= |P - o|, firsts the lod_first_sup of each direction the
// bound runs over. Mirror: `Net::radial_first`.
float lod_radial_first(LodNet net, int k, int edge, vec3 o, float r_max, vec3 firsts) {
    float v = firsts[k];
    float plain = r_max * v;
    LodNet h = lod_hodograph(net, k);
    float second = 0.0;
    for (int j = 0; j < 3; ++j) {
        if (edge >= 0 && j != edge) {
            continue;
        }
        float across = j == k ? lod_second(net, k, edge)
                     : (j == (k + 1) % 3 ? lod_mixed(net, k) : lod_mixed(net, j));
        float t = r_max * lod_second(h, j, edge) + 2.0 * firsts[j] * across
                + lod_second(net, j, edge) * v;
        second = max(second, t);
    }
    float best = 0.0;
    for (int q = 0; q < lod_sample_count(edge); ++q) {
        vec3 w = lod_sample_point(edge, q);
        best = max(best, abs(dot(lod_eval(net, w) - o, lod_eval(h, w))));
    }
    float far = 0.0;
    for (int q = 0; q < (net.degree + 1) * (net.degree + 2) / 2; ++q) {
        if (lod_keep(lod_multi(net.degree, q), edge)) {
            far = max(far, length(net.b[q]));
        }
    }
    float rounding = 16.0 * LOD_EPSILON * (r_max + far) * lod_first(net, k, edge);
    return min(plain, lod_sampled_sup(best, second, rounding, edge));
}

#endif
