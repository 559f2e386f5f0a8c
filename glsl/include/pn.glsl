// `pn` surface: curved PN triangles as the 2005 paper's appendix A writes them; the derivation,
// the normal fields (paper, Vlachos et al.'s, linear) and how they differ are in
// src/surface/pn.rs (the mirror, same operation order).
#ifndef PN_GLSL
#define PN_GLSL
#include "corners.glsl"
#include "flat.glsl"

// The normal field of pn and stpn. Values: src/surface/pn.rs `NormalField`.
const uint NORMAL_FIELD_PAPER = 0u;
const uint NORMAL_FIELD_VLACHOS = 1u;
const uint NORMAL_FIELD_LINEAR = 2u;
layout(constant_id = SPEC_NORMAL_FIELD) const uint NORMAL_FIELD = NORMAL_FIELD_PAPER;

const float PN_THIRD = 1.0 / 3.0;
const float PN_SIXTH = 1.0 / 6.0;

// The edge point of edge (pi, pj) next to pi for normal n there: (2 P_i + P_j - s N) / 3.
// Mirror: src/surface/pn.rs `edge_point`.
vec3 pn_edge_point(vec3 pi, vec3 pj, vec3 n) {
    float s = dot3(pj - pi, n);
    precise vec3 e = (pi * 2.0 + pj - n * s) * PN_THIRD;
    return e;
}

// The edge point of edge ij next to corner i: with the position normal on a seam-flagged edge.
vec3 pn_edge(Corners c, int i, int j) {
    vec3 n = c.seam_pn[edge_of(i, j)] ? c.g[i] : c.n[i];
    return pn_edge_point(c.p[i], c.p[j], n);
}

// The paper's quadratic normal field's edge control point n_ij = N_i + N_j - t_ij (P_j - P_i).
vec3 pn_normal_control(Corners c, int i, int j) {
    vec3 d = c.p[j] - c.p[i];
    float len2 = dot3(d, d);
    vec3 s = c.n[i] + c.n[j];
    float t = len2 > 0.0 ? 4.0 * dot3(d, s) / len2 : 0.0;
    return s - d * t;
}

// Vlachos et al.'s edge control point h_ij / |h_ij|, h_ij = N_i + N_j - v_ij (P_j - P_i).
// Mirror: src/surface/pn.rs `vlachos_control`.
vec3 pn_vlachos_control(Corners c, int i, int j) {
    vec3 d = c.p[j] - c.p[i];
    float len2 = dot3(d, d);
    vec3 s = c.n[i] + c.n[j];
    float v = len2 > 0.0 ? 2.0 * dot3(d, s) / len2 : 0.0;
    vec3 h = s - d * v;
    float l2 = dot3(h, h);
    return l2 > 0.0 ? h / sqrt(l2) : vec3(0.0);
}

// The edge control point of quadratic field `field`. Mirror: `field_control`.
vec3 pn_field_control(uint field, Corners c, int i, int j) {
    return field == NORMAL_FIELD_VLACHOS ? pn_vlachos_control(c, i, j) : pn_normal_control(c, i, j);
}

// Normal field `field` at c.w, normalized. Mirror: src/surface/pn.rs `normal`.
vec3 pn_normal_field(uint field, Corners c) {
    if (field == NORMAL_FIELD_LINEAR) {
        return flat_normal(c);
    }
    vec3 w = c.w;
    vec3 n = c.n[0] * (w[0] * w[0]) + c.n[1] * (w[1] * w[1]) + c.n[2] * (w[2] * w[2])
           + pn_field_control(field, c, 0, 1) * (w[0] * w[1])
           + pn_field_control(field, c, 1, 2) * (w[1] * w[2])
           + pn_field_control(field, c, 2, 0) * (w[2] * w[0]);
    return unit_field(n, c);
}

// The chosen normal field (the NORMAL_FIELD specialization constant).
vec3 pn_normal(Corners c) {
    return pn_normal_field(NORMAL_FIELD, c);
}

// The cubic patch from its six edge points (e_ij: the one of edge ij next to corner i), the
// normal field on c.n. Mirror: src/surface/pn.rs `eval_with_edges`.
void pn_eval_edges(Corners c, vec3 e01, vec3 e10, vec3 e12, vec3 e21, vec3 e02, vec3 e20,
                   out vec3 position, out vec3 normal, out vec3 g[3]) {
    precise vec3 sum = e01 + e10 + e12 + e21 + e02 + e20;
    precise vec3 mean_e = sum * PN_SIXTH;
    precise vec3 mean_v = (c.p[0] + c.p[1] + c.p[2]) * PN_THIRD;
    precise vec3 centre = mean_e + (mean_e - mean_v) * 0.5;
    float w0 = c.w[0], w1 = c.w[1], w2 = c.w[2];
    precise vec3 corners = c.p[0] * (w0 * w0 * w0) + c.p[1] * (w1 * w1 * w1) + c.p[2] * (w2 * w2 * w2);
    precise vec3 edges = e01 * (w0 * w0 * w1) + e10 * (w0 * w1 * w1) + e12 * (w1 * w1 * w2)
                       + e21 * (w1 * w2 * w2) + e02 * (w0 * w0 * w2) + e20 * (w0 * w2 * w2);
    precise vec3 pos = corners + edges * 3.0 + centre * (w0 * w1 * w2 * 6.0);
    position = pos;
    normal = pn_normal(c);
    g[0] = c.p[0] * (3.0 * w0 * w0)
         + (e01 * (2.0 * w0 * w1) + e10 * (w1 * w1) + e02 * (2.0 * w0 * w2) + e20 * (w2 * w2)) * 3.0
         + centre * (6.0 * w1 * w2);
    g[1] = c.p[1] * (3.0 * w1 * w1)
         + (e01 * (w0 * w0) + e10 * (2.0 * w0 * w1) + e12 * (2.0 * w1 * w2) + e21 * (w2 * w2)) * 3.0
         + centre * (6.0 * w0 * w2);
    g[2] = c.p[2] * (3.0 * w2 * w2)
         + (e12 * (w1 * w1) + e21 * (2.0 * w1 * w2) + e02 * (w0 * w0) + e20 * (2.0 * w0 * w2)) * 3.0
         + centre * (6.0 * w0 * w1);
}

void pn_eval(Corners c, out vec3 position, out vec3 normal, out vec3 g[3]) {
    vec3 e01 = pn_edge(c, 0, 1), e10 = pn_edge(c, 1, 0), e12 = pn_edge(c, 1, 2);
    vec3 e21 = pn_edge(c, 2, 1), e02 = pn_edge(c, 0, 2), e20 = pn_edge(c, 2, 0);
    pn_eval_edges(c, e01, e10, e12, e21, e02, e20, position, normal, g);
}

#endif
