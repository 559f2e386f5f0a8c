// GPU-side records, mirrored in Rust (src/surface/record.rs, src/render/mod.rs); a const
// assertion on each Rust struct pins sizes and offsets, and a GPU test reads sentinels back.
#ifndef RECORDS_GLSL
#define RECORDS_GLSL

// One element's record, opaque to the drivers (112 bytes, identical in std140 / std430 /
// push-constant layout). Each surface decodes its own layout (corners.glsl: `corner_record`).
struct ElementRecord {
    uvec4 d[7];
};

// Per frame (set 0).
layout(set = SET_FRAME, binding = BINDING_FRAME, std140) uniform Frame {
    mat4 view_proj;
    vec4 eye;        // xyz: camera position (world)
    vec4 light_dir;  // xyz: direction towards the light (world); w: 1 on a closed surface wound outwards
    vec4 base_color; // rgb: surface colour
    vec4 params;     // surface and displacement: (alpha, amplitude, frequency, octaves)
    vec4 origin;     // xyz: the mesh's origin in drawn coordinates (displacement's frame)
    uint unused;     // keeps the offsets (the view is a specialization constant)
    float heightmap_bias;
    float heightmap_lod; // the height map pyramid level to read
    float level;     // the level every element is drawn at; 0: each its own (levels buffer)
} frame;

// What the fragment stage shows (src/render/mod.rs `View`: its specialization constant).
const uint VIEW_SHADED = 0u;
const uint VIEW_NORMALS = 1u;
const uint VIEW_LEVELS = 2u;
const uint VIEW_PLAIN = 3u;

// The elements' records (set 1), one chunk of them, as texels, seven an element: a view spans
// at most maxTexelBufferElements texels (src/render/gpu_mesh.rs `chunk_size`), so a large mesh
// is drawn chunk by chunk, the chunk's first record being element pc.draw.y. Drivers read the
// record of the element they sample; the fragment stage reads it to evaluate normal fields per
// fragment (v_element is the index within the chunk).
// src/render/bindings.rs BINDING_ELEMENT_TEXELS says why the stages read texels.
layout(set = SET_MESH, binding = BINDING_ELEMENT_TEXELS) uniform usamplerBuffer record_texels;

// Element `local` of the chunk's records, the bits the Rust side uploaded.
ElementRecord fetch_record(uint local) {
    ElementRecord r;
    for (int k = 0; k < 7; ++k) {
        r.d[k] = texelFetch(record_texels, int(local) * 7 + k);
    }
    return r;
}

// Each element's texture coordinates (stored corner order), same chunking as the records, two
// RGBA32F texels per element: (uv0, uv1), (uv2, 0).
layout(set = SET_MESH, binding = BINDING_UVS) uniform samplerBuffer uv_texels;

// Element `local`'s texture coordinates, in stored corner order.
void fetch_uvs(uint local, out vec2 t[3]) {
    vec4 a = texelFetch(uv_texels, int(2u * local));
    vec4 b = texelFetch(uv_texels, int(2u * local + 1u));
    t = vec2[3](a.xy, a.zw, b.xy);
}

#ifndef FRAGMENT_STAGE
// Per draw: 128 bytes, the minimum every device offers; geometry stages only.
layout(push_constant, std430) uniform Push {
    ElementRecord rec; // `push` submission: the element of this draw
    uvec4 draw;        // x: level N; y: the bound chunk's first element (fetch_record(0));
                       // z: pattern vertex count (tess: 1 when drawing adaptively); w: the element of this draw
                       // (`push`, `ubo`) or its first element (`instanced`, `tess`), in the chunk
} pc;
#endif

// What the CAPTURE variants write, one per evaluated vertex (64 bytes).
struct CapturedVertex {
    vec4 position;   // xyz; w = 1 once written
    vec4 normal;     // xyz
    vec4 coord;      // the sample as the driver produced it: pattern (w, u, v) or gl_TessCoord
    uvec4 id;        // x: element; y: pattern vertex index (pattern) or ~0u (tess)
};

#ifdef CAPTURE
layout(set = SET_CAPTURE, binding = BINDING_CAPTURE, std430) writeonly buffer Capture {
    CapturedVertex captured[];
};
// Append counter (tess: the tessellator's vertices have no fixed index; the adaptive pattern
// driver: vertices its packed capture had no room for), capacity, the first element of this
// capture pass (pattern slots count from it) and, for an adaptive pattern capture, the packed
// slot this pass's buffer starts at.
layout(set = SET_CAPTURE, binding = BINDING_CAPTURE_COUNT, std430) buffer CaptureCount {
    uint capture_count;
    uint capture_capacity;
    uint capture_first;
    uint capture_base;
};
// The adaptive pattern driver's packed capture: element e's vertices (its inner level's lattice)
// from slot capture_offsets[e] to capture_offsets[e + 1] (src/render/packed_capture.rs).
layout(set = SET_CAPTURE, binding = BINDING_CAPTURE_OFFSETS, std430) readonly buffer CaptureOffsets {
    uint capture_offsets[];
};
#endif

#endif
