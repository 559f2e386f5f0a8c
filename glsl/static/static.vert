#version 460
// `static` driver: the CPU refined the whole mesh (the 2005 paper's static-VBO baseline); this
// stage only transforms.
#include "records.glsl"
#include "varyings.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;

void main() {
    v_position = in_position;
    v_normal = in_normal;
    gl_Position = frame.view_proj * vec4(in_position, 1.0);
}
