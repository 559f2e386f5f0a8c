#version 460
// `static` driver: the CPU refined the whole mesh (the 2005 paper's static-VBO baseline: refined
// positions and normals); this stage only transforms. Normals are the refined vertices' own, so
// the fragment stage interpolates them (FRAGMENT_FIELD is off for this driver).
#include "records.glsl"
#include "varyings.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;

void main() {
    v_position = in_position;
    v_normal = in_normal;
    v_element = 0u;
    v_bary = vec3(1.0, 0.0, 0.0);
    gl_Position = frame.view_proj * vec4(in_position, 1.0);
}
