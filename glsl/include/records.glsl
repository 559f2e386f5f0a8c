// GPU-side records, mirrored in Rust (src/surface/record.rs, src/render/frame.rs); a const
// assertion on each Rust struct pins sizes and offsets, and a GPU test reads sentinels back.
#ifndef RECORDS_GLSL
#define RECORDS_GLSL

// One coarse triangle (112 bytes, identical in std140 / std430 / push-constant layout).
struct CoarseTri {
    vec4 p[3];   // corner positions (xyz)
    vec4 n[3];   // corner normals (xyz)
    uvec4 idx;   // xyz: global position index of each corner (canonical order key); w: triangle index
};

// Per frame (set 0).
layout(set = SET_FRAME, binding = BINDING_FRAME, std140) uniform Frame {
    mat4 view_proj;
    vec4 eye;        // xyz: camera position (world)
    vec4 light_dir;  // xyz: direction towards the light (world)
    vec4 base_color; // rgb: surface colour
    vec4 options;    // reserved
} frame;

// Per draw: 128 bytes, the minimum every device offers.
layout(push_constant, std430) uniform Push {
    CoarseTri tri;   // `push` submission: the coarse triangle of this draw
    uvec4 draw;      // x: level N; y: first triangle of this draw (tess); z: pattern vertex count
} pc;

// What the CAPTURE variants write, one per evaluated vertex (64 bytes).
struct CapturedVertex {
    vec4 position;   // xyz; w = 1 once written
    vec4 normal;     // xyz
    vec4 coord;      // the sample as the driver produced it: pattern (w, u, v) or gl_TessCoord
    uvec4 id;        // x: coarse triangle; y: pattern vertex index (pattern) or ~0u (tess)
};

#ifdef CAPTURE
layout(set = SET_CAPTURE, binding = BINDING_CAPTURE, std430) writeonly buffer Capture {
    CapturedVertex captured[];
};
// Append counter (tess: the tessellator's vertices have no fixed index) and capacity.
layout(set = SET_CAPTURE, binding = BINDING_CAPTURE_COUNT, std430) buffer CaptureCount {
    uint capture_count;
    uint capture_capacity;
};
#endif

#endif
