#ifndef LEVELS_GLSL
#define LEVELS_GLSL
// Each element's levels for adaptive drawing (set 1, chunked like the records): its stored
// edges' continuous levels (edge k: corner k -> k + 1) and its inner level; inner 0: culled.
// The drawing stages read them as one RGBA32F texel an element (src/render/bindings.rs
// BINDING_ELEMENT_TEXELS says why); a compute pass that defines LEVELS_STORAGE binds the
// buffer as storage. Mirror: src/lod/levels.rs.
#ifdef LEVELS_STORAGE
layout(set = SET_MESH, binding = BINDING_LEVELS, std430) readonly buffer Levels {
    vec4 element_levels[];
};

vec4 fetch_levels(uint local) {
    return element_levels[local];
}
#else
layout(set = SET_MESH, binding = BINDING_LEVELS) uniform samplerBuffer level_texels;

vec4 fetch_levels(uint local) {
    return texelFetch(level_texels, int(local));
}
#endif

// The level a driver draws for a continuous level: its ceiling, a power of two for a dyadic
// driver, capped at max_level. Mirror: src/lod/levels.rs `drawn_level`.
uint drawn_level(float level, bool dyadic, uint max_level) {
    if (level <= 0.0) {
        return 0u;
    }
    uint n = level >= float(max_level) ? max_level : clamp(uint(ceil(level)), 1u, max_level);
    if (dyadic && n > 1u) {
        // The next power of two.
        n = 1u << (findMSB(n - 1u) + 1);
    }
    return min(n, max_level);
}

#endif
