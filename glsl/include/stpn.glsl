// `stpn` surface: scalar-tagged PN triangles (Boubekeur, Reuter & Schlick 2005). The formulas and
// their derivation are in the mirror, src/surface/stpn.rs (same operation order).
#ifndef STPN_GLSL
#define STPN_GLSL
#include "pn.glsl"

// Every vertex's tags, three texels each: (tension, sharpness, bias, crease), (D, 0), (N, 0).
// Texels, not a storage buffer: read per vertex and per fragment (src/render/bindings.rs
// BINDING_ELEMENT_TEXELS says why).
layout(set = SET_MESH, binding = BINDING_TAGS) uniform samplerBuffer vertex_tags;

struct StTag {
    float tension;
    float sharpness;
    float bias;
    bool crease;
    vec3 direction;
    vec3 normal;
};

StTag stpn_tag(uint vertex) {
    int t = 3 * int(vertex);
    vec4 a = texelFetch(vertex_tags, t), b = texelFetch(vertex_tags, t + 1), n = texelFetch(vertex_tags, t + 2);
    return StTag(a.x, a.y, a.z, a.w != 0.0, b.xyz, n.xyz);
}

// The canonical corners' tags (o: the stored corner each canonical corner is).
void stpn_corner_tags(CornerRecord r, Corners c, out StTag t[3]) {
    uvec3 idx = r.idx.xyz;
    for (int i = 0; i < 3; ++i) {
        t[i] = stpn_tag(idx[c.o[i]]);
    }
}

vec3 stpn_safe_normalize(vec3 v) {
    return dot(v, v) > 0.0 ? normalize(v) : vec3(0.0);
}

// Mirror: `stpn::edge_point`.
vec3 stpn_edge(Corners c, StTag t[3], int i, int j) {
    precise vec3 d = c.p[i] + (c.p[j] - c.p[i]) * ((1.0 - t[i].tension) * PN_THIRD);
    if (t[i].crease) {
        vec3 n = t[i].normal;
        vec3 y = stpn_safe_normalize(n + t[i].direction * t[i].bias);
        precise vec3 b = d + y * -dot3(n, d - c.p[i]);
        return b;
    }
    vec3 n = c.n[i];
    precise vec3 b = d + n * -dot3(n, d - c.p[i]);
    return b;
}

// Mirror: `stpn::shading_normals`.
void stpn_shading_normals(inout Corners c, StTag t[3]) {
    precise vec3 mid = (c.p[0] + c.p[1] + c.p[2]) * PN_THIRD;
    vec3 p[3] = c.p;
    for (int i = 0; i < 3; ++i) {
        if (t[i].crease) {
            float side = dot3(mid - p[i], t[i].direction) >= 0.0 ? 1.0 : -1.0;
            c.n[i] = stpn_safe_normalize(t[i].normal + t[i].direction * (side * t[i].sharpness));
        }
    }
}

void stpn_eval(Corners c, StTag t[3], out vec3 position, out vec3 normal, out vec3 g[3]) {
    vec3 e01 = stpn_edge(c, t, 0, 1), e10 = stpn_edge(c, t, 1, 0), e12 = stpn_edge(c, t, 1, 2);
    vec3 e21 = stpn_edge(c, t, 2, 1), e02 = stpn_edge(c, t, 0, 2), e20 = stpn_edge(c, t, 2, 0);
    Corners shaded = c;
    stpn_shading_normals(shaded, t);
    pn_eval_edges(shaded, e01, e10, e12, e21, e02, e20, position, normal, g);
}

#endif
