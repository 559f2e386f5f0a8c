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

void phong_eval(Corners c, float alpha, out vec3 position, out vec3 normal, out vec3 g[3]) {
    vec3 p = flat_point(c);
    vec3 pi[3];
    for (int i = 0; i < 3; ++i) {
        pi[i] = phong_project(p, c.p[i], c.n[i]);
    }
    precise vec3 curved = pi[0] * c.w[0] + pi[1] * c.w[1] + pi[2] * c.w[2];
    precise vec3 pos = p * (1.0 - alpha) + curved * alpha;
    position = pos;
    normal = flat_normal(c);
    for (int j = 0; j < 3; ++j) {
        vec3 pj = c.p[j];
        vec3 moved = vec3(0.0);
        for (int i = 0; i < 3; ++i) {
            moved += (pj - c.n[i] * dot3(pj, c.n[i])) * c.w[i];
        }
        g[j] = pj * (1.0 - alpha) + (pi[j] + moved) * alpha;
    }
}

#endif
