#version 460
// `tess` driver, control stage. Uniform (pc.draw.z == 0): level N = pc.draw.x on every edge and
// inside, so the tessellator produces the same lattice as a level-N refinement pattern.
// Adaptive (pc.draw.z == 1): the element's own levels (levels.glsl), rounded by `drawn_level`
// and capped at N, the largest level of the draw. gl_TessLevelOuter[i] is the patch edge where
// gl_TessCoord[i] == 0, i.e. between patch vertices i + 1 and i + 2: stored edge (i + 1) mod 3
// (stored edge k joins corners k and k + 1). An inner level of 0 (culled) discards the patch.
// Geomorphing (GEOMORPH, docs/adaptivity.md): the pattern driver's dyadic levels at the largest
// power of two at most N (mirror: src/render/tess/morph.rs `morph_levels`); the tessellator
// draws every side at the inner level, and the evaluation stage snaps the outer ring onto each
// edge's own samples (tess_edges), as the pattern driver's boundary.
#include "records.glsl"
#include "levels.glsl"
#include "../pattern/adaptive.glsl"

layout(vertices = 3) out;

// The stored edges' drawn levels in gl_TessLevelOuter order (what the outer ring's samples are).
layout(location = 0) patch out uvec3 tess_edges;

layout(constant_id = SPEC_GEOMORPH) const uint GEOMORPH = 0;

void main() {
    if (gl_InvocationID == 0) {
        if (pc.draw.z != 0u) {
            uint max_level = pc.draw.x;
            vec4 l = fetch_levels(pc.draw.w + uint(gl_PrimitiveID));
            uint inner = drawn_level(l.w, false, max_level);
            uvec3 outer = uvec3(drawn_level(l.y, false, max_level), drawn_level(l.z, false, max_level),
                                drawn_level(l.x, false, max_level));
            tess_edges = outer;
            if (GEOMORPH != 0u) {
                uvec4 d = adaptive_levels(l, 1u << findMSB(max(max_level, 1u)), true);
                inner = d.w;
                tess_edges = d.yzx;
                outer = uvec3(inner);
            }
            if (inner == 0u) {
                gl_TessLevelOuter[0] = 0.0;
                gl_TessLevelOuter[1] = 0.0;
                gl_TessLevelOuter[2] = 0.0;
                gl_TessLevelInner[0] = 0.0;
            } else {
                gl_TessLevelOuter[0] = float(outer.x);
                gl_TessLevelOuter[1] = float(outer.y);
                gl_TessLevelOuter[2] = float(outer.z);
                gl_TessLevelInner[0] = float(inner);
            }
        } else {
            tess_edges = uvec3(pc.draw.x);
            float level = float(pc.draw.x);
            gl_TessLevelOuter[0] = level;
            gl_TessLevelOuter[1] = level;
            gl_TessLevelOuter[2] = level;
            gl_TessLevelInner[0] = level;
        }
    }
}
