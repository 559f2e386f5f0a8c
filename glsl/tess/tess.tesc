#version 460
// `tess` driver, control stage: uniform level N on every edge and inside, so the tessellator
// produces the same lattice as a level-N refinement pattern.
#include "records.glsl"

layout(vertices = 3) out;

void main() {
    if (gl_InvocationID == 0) {
        float level = float(pc.draw.x);
        gl_TessLevelOuter[0] = level;
        gl_TessLevelOuter[1] = level;
        gl_TessLevelOuter[2] = level;
        gl_TessLevelInner[0] = level;
    }
}
