#version 460
// `static` driver: the CPU refined the whole mesh (the 2005 paper's static-VBO baseline: refined
// positions and normals); this stage only transforms. The ELEMENT_ATTRIBUTES variant also takes
// each refined vertex's element and barycentric sample (a second vertex buffer, built only when
// the surface's normal field is evaluated per fragment), so the fragment stage shades `static`
// exactly as it shades the GPU drivers. Without it, an adaptive mesh drawn element by element
// names each draw's element in pc.draw.w (the levels view reads its levels); otherwise 0.
#include "records.glsl"
#include "varyings.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
#ifdef ELEMENT_ATTRIBUTES
layout(location = 2) in vec3 in_bary;
layout(location = 3) in uint in_element;
#endif

void main() {
    v_position = in_position;
    v_normal = in_normal;
#ifdef ELEMENT_ATTRIBUTES
    v_element = in_element - pc.draw.y; // within the bound chunk of records
    v_bary = in_bary;
#else
    v_element = pc.draw.w;
    v_bary = vec3(1.0, 0.0, 0.0);
#endif
    gl_Position = frame.view_proj * vec4(in_position, 1.0);
}
