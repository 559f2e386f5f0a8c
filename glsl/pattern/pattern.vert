#version 460
// `pattern` driver (Boubekeur & Schlick 2005, §3.2): the refinement pattern's vertices carry
// barycentric coordinates (w, u, v); this stage maps each onto the surface of the draw's element.
// The element's record comes from push constants, a window of a uniform buffer, or instance-rate
// vertex attributes, chosen by the SUBMIT specialization constant; the stage never looks inside
// it (surface.glsl does).
#include "records.glsl"
#include "surface.glsl"
#include "varyings.glsl"

layout(constant_id = SPEC_SUBMIT) const uint SUBMIT = 2; // 0 push, 1 ubo, 2 instanced

// `ubo` submission: a window of UBO_WINDOW records starting at a multiple of UBO_WINDOW, placed by
// the dynamic offset (src/render/pattern.rs); the draw's record is selected in it by index.
layout(set = SET_MESH, binding = BINDING_ELEMENT_UBO, std140) uniform RecordUbo { ElementRecord recs[UBO_WINDOW]; } rec_ubo;

layout(location = 0) in vec3 in_bary; // (w, u, v)
// `instanced`: the element's record as instance-rate attributes (no storage-buffer read per
// vertex; src/render/pattern.rs binds the records as vertex buffer 1).
layout(location = 1) in uvec4 in_rec[7];

void main() {
    ElementRecord rec;
    // The element in the mesh, and within the bound chunk of records (gl_InstanceIndex counts
    // from the first element of an instanced draw).
    uint element = SUBMIT == 2 ? uint(gl_InstanceIndex) : pc.draw.y + pc.draw.w;
    uint local = element - pc.draw.y;
    if (SUBMIT == 0) {
        rec = pc.rec;
    } else if (SUBMIT == 1) {
        rec = rec_ubo.recs[element % uint(UBO_WINDOW)];
    } else {
        rec = ElementRecord(in_rec);
    }
    SurfacePoint sp = evaluate(rec, Sample(local, in_bary));
    v_position = sp.position;
    v_normal = sp.normal;
    v_element = local;
    v_bary = in_bary;
    gl_Position = frame.view_proj * vec4(sp.position, 1.0);
#ifdef CAPTURE
    captured[(element - capture_first) * pc.draw.z + uint(gl_VertexIndex)] =
        CapturedVertex(vec4(sp.position, 1.0), vec4(sp.normal, 0.0), vec4(in_bary, 0.0),
                       uvec4(element, uint(gl_VertexIndex), 0u, 0u));
#endif
}
