// Ken Perlin's improved noise (2002 reference implementation) with its analytic gradient.
// Mirror: src/surface/noise.rs (the permutation table is Perlin's; a unit test checks it there, and
// the GPU tests compare every displaced vertex with the mirror).
#include "records.glsl"
#ifndef NOISE_GLSL
#define NOISE_GLSL

// Perlin's permutation table, four entries per vector (src/surface/noise.rs `PERM`, uploaded
// once by the renderer). A uniform block rather than a constant array: dynamically indexed
// constant arrays become branch trees in some compilers (lavapipe took a minute per pipeline).
layout(set = SET_FRAME, binding = BINDING_NOISE, std140) uniform NoisePerm {
    uvec4 noise_table[64];
};

uint noise_perm(uint i) {
    uint k = i & 255u;
    return noise_table[k >> 2][k & 3u];
}

// Perlin's grad(hash, x, y, z) is dot(noise_gradient(hash), (x, y, z)).
vec3 noise_gradient(uint hash) {
    uint h = hash & 15u;
    float u = (h & 1u) == 0u ? 1.0 : -1.0;
    float v = (h & 2u) == 0u ? 1.0 : -1.0;
    // u on x (h < 8) or y; v on y (h < 4), x (h = 12, 14) or z.
    vec3 g = vec3(0.0);
    if (h < 8u) g.x = u; else g.y = u;
    if (h < 4u) g.y += v; else if (h == 12u || h == 14u) g.x += v; else g.z += v;
    return g;
}

float noise_fade(float t) { precise float r = t * t * t * (t * (t * 6.0 - 15.0) + 10.0); return r; }
float noise_dfade(float t) { return 30.0 * t * t * (t * (t - 2.0) + 1.0); }
float noise_lerp(float t, float a, float b) { precise float r = a + t * (b - a); return r; }

float noise_corner(uint h, vec3 f, vec3 corner, out vec3 g) {
    g = noise_gradient(noise_perm(h));
    vec3 d = f - corner;
    precise float r = g.x * d.x + g.y * d.y + g.z * d.z;
    return r;
}

// Improved noise at p (in [-1, 1]); its gradient in grad.
float noise_grad(vec3 p, out vec3 grad) {
    vec3 fl = floor(p);
    uvec3 cell = uvec3(ivec3(fl));
    precise vec3 f = p - fl;
    float u = noise_fade(f.x), v = noise_fade(f.y), w = noise_fade(f.z);
    uint a = noise_perm(cell.x) + cell.y;
    uint aa = noise_perm(a) + cell.z;
    uint ab = noise_perm(a + 1u) + cell.z;
    uint b = noise_perm(cell.x + 1u) + cell.y;
    uint ba = noise_perm(b) + cell.z;
    uint bb = noise_perm(b + 1u) + cell.z;
    vec3 g000, g100, g010, g110, g001, g101, g011, g111;
    float n000 = noise_corner(aa, f, vec3(0, 0, 0), g000);
    float n100 = noise_corner(ba, f, vec3(1, 0, 0), g100);
    float n010 = noise_corner(ab, f, vec3(0, 1, 0), g010);
    float n110 = noise_corner(bb, f, vec3(1, 1, 0), g110);
    float n001 = noise_corner(aa + 1u, f, vec3(0, 0, 1), g001);
    float n101 = noise_corner(ba + 1u, f, vec3(1, 0, 1), g101);
    float n011 = noise_corner(ab + 1u, f, vec3(0, 1, 1), g011);
    float n111 = noise_corner(bb + 1u, f, vec3(1, 1, 1), g111);
    float value = noise_lerp(w, noise_lerp(v, noise_lerp(u, n000, n100), noise_lerp(u, n010, n110)),
                                noise_lerp(v, noise_lerp(u, n001, n101), noise_lerp(u, n011, n111)));
    float k1 = n100 - n000;
    float k2 = n010 - n000;
    float k3 = n001 - n000;
    float k4 = n000 - n100 - n010 + n110;
    float k5 = n000 - n010 - n001 + n011;
    float k6 = n000 - n100 - n001 + n101;
    float k7 = -n000 + n100 + n010 - n110 + n001 - n101 - n011 + n111;
    vec3 blend = g000 + (g100 - g000) * u + (g010 - g000) * v + (g001 - g000) * w
               + (g000 - g100 - g010 + g110) * (u * v) + (g000 - g010 - g001 + g011) * (v * w)
               + (g000 - g100 - g001 + g101) * (w * u)
               + (-g000 + g100 + g010 - g110 + g001 - g101 - g011 + g111) * (u * v * w);
    vec3 weights = vec3(noise_dfade(f.x) * (k1 + k4 * v + k6 * w + k7 * v * w),
                        noise_dfade(f.y) * (k2 + k4 * u + k5 * w + k7 * u * w),
                        noise_dfade(f.z) * (k3 + k5 * v + k6 * u + k7 * u * v));
    grad = blend + weights;
    return value;
}

#endif
