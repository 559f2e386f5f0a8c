#version 460
// `tess` driver, evaluation stage: evaluates the surface at gl_TessCoord. Outer-edge samples are
// snapped to their edge's lattice (`tess_weights_levels`: the draw's level N, or adaptively each
// edge's own level as the control stage set it), so a shared coarse edge is evaluated from the
// same weights by both triangles (watertight). Interior samples are the tessellator's own; with
// equal spacing its rings hold N, N-2, N-4, ... segments, so it makes more triangles than a level-N
// pattern (src/render/tess.rs `triangle_count`).
// gl_PrimitiveID restarts in every draw; pc.draw.w is this draw's first element within the bound
// chunk of records, pc.draw.y the chunk's first element.
// Variants: CAPTURE (every evaluated vertex to a storage buffer, for the tests) and XFB
// (transform feedback of the tessellator's triangles, each vertex with its element and sample,
// for export).
#include "records.glsl"
#include "surface.glsl"
#include "varyings.glsl"
#include "tess_weights.glsl"
#include "levels.glsl"
#include "tess_morph.glsl"

// Geomorphing (docs/adaptivity.md): 1 glides the vertices the finest drawn levels add.
layout(constant_id = SPEC_GEOMORPH) const uint GEOMORPH = 0;

// `cw`: Vulkan's tessellation domain origin is upper-left, which flips the sense of the winding
// qualifier against OpenGL's; `cw` here emits triangles wound like the coarse triangle
// (counter-clockwise P0 P1 P2), as the export test checks against the normals.
layout(triangles, equal_spacing, cw) in;

// The stored edges' drawn levels in gl_TessLevelOuter order (tess.tesc): geomorphing, the
// tessellator draws every side at the inner level and the outer ring snaps onto these.
layout(location = 0) patch in uvec3 tess_edges;

void main() {
    uint n = pc.draw.x;
    uint local = pc.draw.w + uint(gl_PrimitiveID);
    uint element = pc.draw.y + local;
    // gl_TessCoord (x, y, z) weighs patch vertices (0, 1, 2), i.e. (w, u, v).
    vec3 bary;
    uint inner = uint(gl_TessLevelInner[0]);
    // The edges' levels: the control stage's outer levels, or geomorphing its tess_edges.
    uvec3 outer = GEOMORPH != 0u
        ? tess_edges
        : uvec3(gl_TessLevelOuter[0], gl_TessLevelOuter[1], gl_TessLevelOuter[2]);
    if (pc.draw.z != 0u) {
        // Adaptive: the levels the control stage set (integers, at most N).
        vec3 tc = GEOMORPH != 0u ? tess_snap(gl_TessCoord, outer, inner) : gl_TessCoord;
        bary = tess_weights_levels(tc, outer, inner);
    } else {
        bary = tess_weights(gl_TessCoord, n);
    }
    ElementRecord rec = fetch_record(local);
    SurfacePoint sp = evaluate(rec, Sample(local, bary));
    if (GEOMORPH != 0u && pc.draw.z != 0u) {
        // The normal stays the true point's (docs/adaptivity.md, "Geomorphing").
        sp.position = tess_geomorph_position(rec, local, gl_TessCoord, bary, sp.position, outer,
                                             inner, fetch_levels(local));
    }
    v_position = sp.position;
    v_normal = sp.normal;
    v_element = local;
    v_bary = bary;
    gl_Position = frame.view_proj * vec4(sp.position, 1.0);
#ifdef XFB
    v_xfb_element = element;
#endif
#ifdef CAPTURE
    uint slot = atomicAdd(capture_count, 1u);
    if (slot < capture_capacity) {
        captured[slot] = CapturedVertex(vec4(sp.position, 1.0), vec4(sp.normal, 0.0), vec4(gl_TessCoord, 0.0),
                                        uvec4(element, ~0u, 0u, 0u));
    }
#endif
}
