// The height map and its mip pyramid, sampled by hand (bilinear within a level, linear between
// two levels, coordinates repeating) so that the CPU mirror computes the same arithmetic.
// Mirror: src/surface/heightmap.rs (layout: `Heightmap::gpu_header`, `Heightmap::gpu_texels`).
#ifndef HEIGHTMAP_GLSL
#define HEIGHTMAP_GLSL
#include "records.glsl"

layout(set = SET_MESH, binding = BINDING_HEIGHTMAP, std140) uniform HeightmapData {
    uvec4 hm_header;       // x: level count
    uvec4 hm_level[16];    // offset (texels), width, height, 0
};
// Every level's texels, level after level (a texel buffer: an 8192² pyramid is larger than a
// storage-buffer range may be). texelFetch returns the stored f32 exactly.
layout(set = SET_MESH, binding = BINDING_HEIGHTMAP_TEXELS) uniform samplerBuffer hm_texels;

float hm_texel(uint i) {
    return texelFetch(hm_texels, int(i)).r;
}

// Mirror: `Heightmap::bilinear`.
float heightmap_bilinear(uint l, vec2 uv, out vec2 grad) {
    uint w = hm_level[l].y, h = hm_level[l].z, base = hm_level[l].x;
    float fw = float(w), fh = float(h);
    precise float x = uv.x * fw - 0.5;
    precise float y = uv.y * fh - 0.5;
    float x0 = floor(x), y0 = floor(y);
    precise float fx = x - x0;
    precise float fy = y - y0;
    int iw = int(w), ih = int(h);
    uint ix0 = uint(((int(x0) % iw) + iw) % iw), iy0 = uint(((int(y0) % ih) + ih) % ih);
    uint ix1 = (ix0 + 1u) % w, iy1 = (iy0 + 1u) % h;
    float t00 = hm_texel(base + iy0 * w + ix0), t10 = hm_texel(base + iy0 * w + ix1);
    float t01 = hm_texel(base + iy1 * w + ix0), t11 = hm_texel(base + iy1 * w + ix1);
    precise float top = t00 + fx * (t10 - t00);
    precise float bottom = t01 + fx * (t11 - t01);
    precise float value = top + fy * (bottom - top);
    float dx = (t10 - t00) + fy * ((t11 - t01) - (t10 - t00));
    float dy = bottom - top;
    grad = vec2(dx * fw, dy * fh);
    return value;
}

// Height at uv read at pyramid level lod, and its derivative by uv. Mirror: `Heightmap::sample`.
float heightmap_sample(vec2 uv, float lod, out vec2 grad) {
    uint last = hm_header.x - 1u;
    float l = max(lod, 0.0);
    uint l0 = min(uint(floor(l)), last);
    uint l1 = min(l0 + 1u, last);
    float f = clamp(l - float(l0), 0.0, 1.0);
    vec2 ga;
    float a = heightmap_bilinear(l0, uv, ga);
    if (l1 == l0 || f == 0.0) {
        grad = ga;
        return a;
    }
    vec2 gb;
    float b = heightmap_bilinear(l1, uv, gb);
    grad = ga + (gb - ga) * f;
    precise float v = a + f * (b - a);
    return v;
}

#endif
