// `flat` surface: linear interpolation of the coarse triangle (Boubekeur & Schlick 2005, §3.2:
// V = w·P0 + u·P1 + v·P2), normals interpolated the same way.
// Mirror: src/surface/flat.rs. `precise` forbids fused multiply-add, so the GPU computes the same
// bits as the CPU mirror (Vulkan rounds fp32 add and multiply correctly).
#ifndef FLAT_GLSL
#define FLAT_GLSL
#include "bary.glsl"

void flat_eval(Corners c, out vec3 position, out vec3 normal) {
    precise vec3 p = c.p[0] * c.w[0] + c.p[1] * c.w[1] + c.p[2] * c.w[2];
    vec3 n = c.n[0] * c.w[0] + c.n[1] * c.w[1] + c.n[2] * c.w[2];
    position = p;
    normal = normalize(n);
}

#endif
