#version 460
// `static` driver: the CPU refined the whole mesh (the 2005 paper's static-VBO baseline); this
// stage only transforms. The lattice coordinate for the wireframe view is looked up in the pattern.
#include "records.glsl"
#include "varyings.glsl"

layout(set = SET_MESH, binding = BINDING_PATTERN, std430) readonly buffer PatternBary { float pattern_bary[]; };

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;

void main() {
    uint local = uint(gl_VertexIndex) % pc.draw.z;
    vec3 bary = vec3(pattern_bary[3 * local], pattern_bary[3 * local + 1], pattern_bary[3 * local + 2]);
    v_position = in_position;
    v_normal = in_normal;
    v_lattice = bary * float(pc.draw.x);
    gl_Position = frame.view_proj * vec4(in_position, 1.0);
}
