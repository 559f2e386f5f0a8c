#version 460
// `pattern` driver (Boubekeur & Schlick 2005, §3.2): the refinement pattern's vertices carry
// barycentric coordinates (w, u, v); this stage maps each onto the coarse triangle of the draw.
// The triangle's record comes from push constants, a dynamic uniform buffer or a storage buffer
// indexed by gl_InstanceIndex, chosen by the SUBMIT specialization constant.
#include "records.glsl"
#include "surface.glsl"
#include "varyings.glsl"

layout(constant_id = SPEC_SUBMIT) const uint SUBMIT = 2; // 0 push, 1 ubo, 2 instanced

layout(set = SET_MESH, binding = BINDING_TRIS, std430) readonly buffer Tris { CoarseTri tris[]; };
layout(set = SET_MESH, binding = BINDING_TRI_UBO, std140) uniform TriUbo { CoarseTri tri; } tri_ubo;

layout(location = 0) in vec3 in_bary; // (w, u, v)

void main() {
    CoarseTri t;
    if (SUBMIT == 0) {
        t = pc.tri;
    } else if (SUBMIT == 1) {
        t = tri_ubo.tri;
    } else {
        t = tris[gl_InstanceIndex];
    }
    vec3 p, n;
    surface_eval(t, in_bary, p, n);
    v_position = p;
    v_normal = n;
    gl_Position = frame.view_proj * vec4(p, 1.0);
#ifdef CAPTURE
    captured[t.idx.w * pc.draw.z + uint(gl_VertexIndex)] =
        CapturedVertex(vec4(p, 1.0), vec4(n, 0.0), vec4(in_bary, 0.0), uvec4(t.idx.w, uint(gl_VertexIndex), 0u, 0u));
#endif
}
