#version 460
// The cage overlay: the coarse mesh's edges (the control mesh, for loop) as lines, on top of the
// refined surface, so element boundaries and the control net can be told from the refinement.
// src/render/cage.rs uploads the edges (two positions each) and draws them.
#include "records.glsl"

layout(location = 0) in vec3 in_position;

void main() {
    gl_Position = frame.view_proj * vec4(in_position, 1.0);
    // Pulled a little towards the camera (depth bias applies to polygons only, not to line
    // primitives), so the edges win the depth test where they lie on the surface (flat) and over
    // the refined wireframe, which is biased towards the camera too.
    gl_Position.z -= 1e-3 * gl_Position.w;
}
