// `phong` surface: Phong tessellation (Boubekeur & Alexa 2008): the flat point p is projected on
// each corner's tangent plane, pi_i(q) = q - ((q - P_i)·N_i) N_i, and the projections are
// interpolated again: P = (1 - alpha) p + alpha Σ w_i pi_i(p). Normal: the normalized linear
// interpolation of the corner normals. Mirror: src/surface/phong.rs (same operation order).
#ifndef PHONG_GLSL
#define PHONG_GLSL
#include "flat.glsl"

vec3 phong_project(vec3 q, vec3 p, vec3 n) {
    precise vec3 r = q - n * dot3(q - p, n);
    return r;
}

// The normal corner i's tangent plane uses (seams blended inside the triangle, exactly one
// choice on an edge). Mirror: src/surface/phong.rs `corner_normal`.
vec3 phong_corner_normal(Corners c, int i) {
    int j = (i + 1) % 3, k = (i + 2) % 3;
    vec3 a_ij = c.seam_phong[edge_of(i, j)] ? c.g[i] : c.n[i];
    vec3 a_ik = c.seam_phong[edge_of(i, k)] ? c.g[i] : c.n[i];
    if (a_ij == a_ik || c.w[k] == 0.0) return a_ij;
    if (c.w[j] == 0.0) return a_ik;
    vec3 s = a_ij * c.w[j] + a_ik * c.w[k];
    // Opposite choices (a seam's two normals) blend to nothing halfway: the edge's first.
    return dot3(s, s) > FIELD_MIN2 ? normalize(s) : a_ij;
}

void phong_eval(Corners c, float alpha, out vec3 position, out vec3 normal, out vec3 g[3]) {
    vec3 p = flat_point(c);
    vec3 pi[3];
    vec3 cn[3];
    for (int i = 0; i < 3; ++i) {
        cn[i] = phong_corner_normal(c, i);
        pi[i] = phong_project(p, c.p[i], cn[i]);
    }
    precise vec3 curved = pi[0] * c.w[0] + pi[1] * c.w[1] + pi[2] * c.w[2];
    precise vec3 pos = p * (1.0 - alpha) + curved * alpha;
    position = pos;
    normal = flat_normal(c);
    for (int j = 0; j < 3; ++j) {
        vec3 pj = c.p[j];
        vec3 moved = vec3(0.0);
        for (int i = 0; i < 3; ++i) {
            moved += (pj - cn[i] * dot3(pj, cn[i])) * c.w[i];
        }
        g[j] = pj * (1.0 - alpha) + (pi[j] + moved) * alpha;
    }
}

#endif
