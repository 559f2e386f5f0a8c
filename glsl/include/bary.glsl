// Canonical corner order for a barycentric sample: what makes refinement watertight.
// Mirror: src/surface/mod.rs `canonical`.
//
// Corners are sorted by global vertex index, and zero-weight corners are moved last. A point on a
// coarse edge shared by two triangles is then evaluated from the same two corners, in the same
// order, with the same weights, in both triangles: bit-identical positions.
#ifndef BARY_GLSL
#define BARY_GLSL
#include "records.glsl"

struct Corners {
    vec3 p[3];
    vec3 n[3];
    vec3 w;      // weight of each corner, in canonical order
};

uint canonical_key(uint index, float weight) {
    // Zero weights sort last; then by vertex index (indices are < 2^31, see mesh loading).
    return (weight == 0.0 ? 0x80000000u : 0u) | index;
}

Corners canonical(CoarseTri t, vec3 bary) {
    uint k[3] = uint[3](canonical_key(t.idx.x, bary.x), canonical_key(t.idx.y, bary.y),
                        canonical_key(t.idx.z, bary.z));
    int o[3] = int[3](0, 1, 2);
    // Three-element sorting network on the keys (ties keep the original order).
    if (k[o[1]] < k[o[0]]) { int s = o[0]; o[0] = o[1]; o[1] = s; }
    if (k[o[2]] < k[o[1]]) { int s = o[1]; o[1] = o[2]; o[2] = s; }
    if (k[o[1]] < k[o[0]]) { int s = o[0]; o[0] = o[1]; o[1] = s; }
    Corners c;
    for (int i = 0; i < 3; ++i) {
        c.p[i] = t.p[o[i]].xyz;
        c.n[i] = t.n[o[i]].xyz;
        c.w[i] = bary[o[i]];
    }
    return c;
}

// Weights of a tessellator sample at integer level n (tess driver). Points on the patch's outer
// edges lie on the level-n lattice: their weights are rebuilt from integers, k/n and (n-k)/n with
// an exact zero, as the pattern's are, so both triangles sharing the edge get the same weights.
// Interior points (every coordinate >= 1/n) are used as the tessellator made them.
// Mirror: src/surface/mod.rs `tess_weights`.
vec3 tess_weights(vec3 tc, uint n) {
    float fn = float(n);
    float half_step = 0.5 / fn;
    if (min(tc.x, min(tc.y, tc.z)) >= half_step) {
        return tc;
    }
    vec3 k = round(tc * fn);
    if (tc.x < half_step) k.x = 0.0;
    if (tc.y < half_step) k.y = 0.0;
    if (tc.z < half_step) k.z = 0.0;
    // Two of the three are the edge's own; the third is zero. Renormalize the pair to sum to n.
    if (k.x == 0.0) k.y = fn - k.z;
    else if (k.y == 0.0) k.z = fn - k.x;
    else k.x = fn - k.y;
    return k / fn;
}

#endif
