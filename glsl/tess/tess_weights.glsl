#ifndef TESS_WEIGHTS_GLSL
#define TESS_WEIGHTS_GLSL
// Weights of a tessellator sample (tess driver) with integer level outer[i] on the patch edge
// where tc[i] == 0 (gl_TessLevelOuter[i]) and inner level `inner` (at least every outer level).
// Points on the patch's outer edges lie on their edge's own lattice: their weights are rebuilt
// from integers, k/n and (n-k)/n with n the edge's level and an exact zero, as the pattern's are,
// so both triangles sharing the edge get the same weights. Interior points (every coordinate at
// least 1/inner) are used as the tessellator made them; an edge point has a coordinate of zero.
// With every level equal this is `tess_weights(tc, n)`, operation for operation.
// Mirror: src/render/tess.rs `tess_weights_levels`.
vec3 tess_weights_levels(vec3 tc, uvec3 outer, uint inner) {
    float half_step = 0.5 / float(inner);
    if (min(tc.x, min(tc.y, tc.z)) >= half_step) {
        return tc;
    }
    // The edge the sample lies on (a corner: the first of its two).
    float fn = float(tc.x < half_step ? outer.x : (tc.y < half_step ? outer.y : outer.z));
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

// Every level n (uniform drawing). Mirror: src/render/tess.rs `tess_weights`.
vec3 tess_weights(vec3 tc, uint n) {
    return tess_weights_levels(tc, uvec3(n), n);
}

#endif
