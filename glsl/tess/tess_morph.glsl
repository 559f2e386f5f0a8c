#ifndef TESS_MORPH_GLSL
#define TESS_MORPH_GLSL
// Geomorphing on the tessellator (docs/adaptivity.md, "Geomorphing"; the construction is in
// src/render/tess/morph.rs, this file's mirror): dyadic levels, and the vertices the finest drawn
// level adds glide from their parents' midpoint. Needs surface.glsl, levels.glsl.
#include "../pattern/adaptive.glsl"

// Where the geomorphing tess driver's tessellator vertex tc lies: a vertex of the outer ring
// (every side drawn at the inner level n) moved onto its edge's own samples (outer: the edges'
// levels) as the pattern driver's boundary is (snap_edge: the nearest, a tie toward the nearer
// corner, at the edge's middle toward the stored edge's first corner), the rest as the
// tessellator made them. Mirror: tess::morph::snap_ring.
vec3 tess_snap(vec3 tc, uvec3 outer, uint n) {
    float half_step = 0.5 / float(n);
    int edge = tc.x < half_step ? 0 : (tc.y < half_step ? 1 : (tc.z < half_step ? 2 : -1));
    if (edge < 0) {
        return tc;
    }
    uint a = uint(edge + 1) % 3u, b = uint(edge + 2) % 3u;
    uint s = snap_edge(uint(round(tc[b] * float(n))), outer[edge], n);
    vec3 r = vec3(0.0);
    r[a] = float(n - s) / float(n);
    r[b] = float(s) / float(n);
    return r;
}

// A point on patch edge `edge` at weights w (multiples of 1/ne): whether it is new at the edge's
// level and not yet in place; then its parents on the edge and its factor (continuous level
// lambda of the edge). Mirror: tess::morph::edge_parents.
bool tess_edge_parents(vec3 w, uint edge, uint ne, float lambda, out vec3 qa, out vec3 qb, out float m) {
    qa = vec3(0.0);
    qb = vec3(0.0);
    m = 1.0;
    if (ne <= 1u) {
        return false;
    }
    uint a = (edge + 1u) % 3u, b = (edge + 2u) % 3u;
    uint kb = uint(round(w[b] * float(ne)));
    if ((kb & 1u) == 0u) {
        return false;
    }
    m = morph_factor(lambda, ne);
    if (m >= 1.0) {
        return false;
    }
    qa[a] = float(ne - kb + 1u) / float(ne);
    qa[b] = float(kb - 1u) / float(ne);
    qb[a] = float(ne - kb - 1u) / float(ne);
    qb[b] = float(kb + 1u) / float(ne);
    return true;
}

// How an inside vertex at tc (inner level n, factor m of the element's largest level) morphs:
// false when it stays; else its parents, qa the outer one (on patch edge a_edge, snapped onto its
// samples, or -1 inside) and qb. Mirror: tess::morph::classify.
bool tess_inner_parents(vec3 tc, uvec3 outer, uint n, out vec3 qa, out int a_edge, out vec3 qb) {
    qa = vec3(0.0);
    qb = vec3(0.0);
    a_edge = -1;
    int s = 3 * int(n);
    ivec3 k = ivec3(round(tc * float(s)));
    ivec3 pa, pb;
    if (n == 2u) {
        // The centre: level 1 has no inside.
        pa = ivec3(0, 3, 3);
        pb = ivec3(6, 0, 0);
    } else {
        int kmin = min(k.x, min(k.y, k.z));
        int r = kmin / 2;
        if (2 * r == int(n)) {
            return false;
        }
        bvec3 at_min = equal(k, ivec3(kmin));
        int mins = int(at_min.x) + int(at_min.y) + int(at_min.z);
        int corner = -1;
        if (mins >= 2) {
            corner = k.x >= k.y && k.x >= k.z ? 0 : (k.y >= k.z ? 1 : 2);
        }
        int c = at_min.x ? 0 : (at_min.y ? 1 : 2);
        int ea = (c + 1) % 3, eb = (c + 2) % 3;
        int j = (k[eb] - kmin) / 3;
        ivec3 d = ivec3(0);
        if (r % 2 == 0) {
            if (corner >= 0 || j % 2 == 0) {
                return false;
            }
            d[ea] = -3;
            d[eb] = 3;
        } else if (corner >= 0) {
            d = ivec3(-2);
            d[corner] += 6;
        } else if (j % 2 == 0) {
            // A parallelogram's centre: the diagonal toward the nearer ring corner.
            d = ivec3(-2);
            d[2 * j < int(n) - 2 * r ? ea : eb] += 6;
        } else {
            d = ivec3(-1);
            d[c] += 3;
        }
        ivec3 p = k + d, q = k - d;
        bool p_outer = min(p.x, min(p.y, p.z)) <= min(q.x, min(q.y, q.z));
        pa = p_outer ? p : q;
        pb = p_outer ? q : p;
    }
    qb = vec3(pb) / float(s);
    a_edge = pa.x == 0 ? 0 : (pa.y == 0 ? 1 : (pa.z == 0 ? 2 : -1));
    if (a_edge < 0) {
        qa = vec3(pa) / float(s);
    } else {
        uint ea = uint(a_edge + 1) % 3u, eb = uint(a_edge + 2) % 3u;
        uint ne = outer[a_edge];
        uint kb = snap_edge(uint(pa[eb] / 3), ne, n) / (n / ne);
        qa[ea] = float(ne - kb) / float(ne);
        qa[eb] = float(kb) / float(ne);
    }
    return true;
}

// Where the geomorphing tess driver draws the vertex at tc (weights w, true position p) of an
// element drawn at (outer, inner) with continuous levels lv (stored edges x y z, inner w).
// Mirror: tess::morph::geomorph_position.
vec3 tess_geomorph_position(ElementRecord rec, uint local, vec3 tc, vec3 w, vec3 p, uvec3 outer,
                            uint inner, vec4 lv) {
    float half_step = 0.5 / float(inner);
    int edge = tc.x < half_step ? 0 : (tc.y < half_step ? 1 : (tc.z < half_step ? 2 : -1));
    vec3 qa = w, qb;
    vec3 pa = p;
    float mi = 1.0;
    if (edge < 0) {
        if (inner <= 1u) {
            return p;
        }
        mi = morph_factor(max(lv.w, max(lv.x, max(lv.y, lv.z))), inner);
        if (mi >= 1.0 || !tess_inner_parents(tc, outer, inner, qa, edge, qb)) {
            return p;
        }
        pa = evaluate(rec, Sample(local, qa)).position;
    }
    // The edge rule, for an edge vertex or an inside vertex's parent on an edge.
    if (edge >= 0) {
        vec3 ea, eb;
        float me;
        float lambda = edge == 0 ? lv.y : (edge == 1 ? lv.z : lv.x);
        if (tess_edge_parents(qa, uint(edge), outer[edge], lambda, ea, eb, me)) {
            pa = morph(evaluate(rec, Sample(local, ea)).position,
                       evaluate(rec, Sample(local, eb)).position, pa, me);
        }
    }
    if (mi >= 1.0) {
        return pa; // an edge vertex
    }
    return morph(pa, evaluate(rec, Sample(local, qb)).position, p, mi);
}

#endif
