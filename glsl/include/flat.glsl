// `flat` surface: linear interpolation of the coarse triangle (Boubekeur & Schlick 2005, §3.2:
// V = w·P0 + u·P1 + v·P2), normals interpolated the same way.
// Mirror: src/surface/flat.rs. `precise` forbids fused multiply-add, so the GPU computes the same
// bits as the CPU mirror (Vulkan rounds fp32 add and multiply correctly).
#ifndef FLAT_GLSL
#define FLAT_GLSL
#include "corners.glsl"

vec3 flat_point(Corners c) {
    precise vec3 p = c.p[0] * c.w[0] + c.p[1] * c.w[1] + c.p[2] * c.w[2];
    return p;
}

vec3 flat_normal(Corners c) {
    // `precise` too: flat evaluates in stored order, and on a shared edge both sides must add
    // the same two unfused products (the normal is what displacement moves along).
    precise vec3 n = c.n[0] * c.w[0] + c.n[1] * c.w[1] + c.n[2] * c.w[2];
    return unit_field(n, c);
}

// ∂P/∂b_i of each canonical corner in g.
void flat_eval(Corners c, out vec3 position, out vec3 normal, out vec3 g[3]) {
    position = flat_point(c);
    normal = flat_normal(c);
    g = c.p;
}

#endif
