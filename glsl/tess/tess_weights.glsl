#ifndef TESS_WEIGHTS_GLSL
#define TESS_WEIGHTS_GLSL
// Weights of a tessellator sample at integer level n (tess driver). Points on the patch's outer
// edges lie on the level-n lattice: their weights are rebuilt from integers, k/n and (n-k)/n with
// an exact zero, as the pattern's are, so both triangles sharing the edge get the same weights.
// Interior points (every coordinate >= 1/n) are used as the tessellator made them.
// Mirror: src/render/tess.rs `tess_weights`.
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
