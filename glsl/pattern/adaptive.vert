#version 460
// `pattern` driver, adaptive (docs/architecture.md, "Levels"; Schwarz et al. 2006): each element
// drawn at its own inner level from the hierarchical patterns (the finest level's vertices, one
// index range per dyadic level, src/pattern/adaptive.rs), its boundary vertices snapped onto
// their edge's level so that the two elements sharing an edge sample it identically. The draws
// are indirect: glsl/pattern/bins.comp chose each element's index range from its levels.
#include "records.glsl"
#include "surface.glsl"
#include "varyings.glsl"
#include "levels.glsl"
#include "adaptive.glsl"

layout(constant_id = SPEC_SUBMIT) const uint SUBMIT = 2; // 0 push, 1 ubo, 2 instanced

// `ubo` submission, as in pattern.vert.
layout(set = SET_MESH, binding = BINDING_ELEMENT_UBO, std140) uniform RecordUbo { ElementRecord recs[UBO_WINDOW]; } rec_ubo;

layout(location = 0) in vec3 in_bary; // (w, u, v) of the finest level pc.draw.x
// `instanced`: the element of this instance, from its bin's list (bound at the bin's first
// entry, src/render/pattern.rs); the other modes ignore it.
layout(location = 8) in uint in_element;

void main() {
    // pc.draw: x the largest level f (the vertices' lattice), y the chunk's first element,
    // z the finest pattern's vertex count (capture slots), w the element in the chunk (push, ubo).
    uint f = pc.draw.x;
    uint element = SUBMIT == 2 ? in_element : pc.draw.y + pc.draw.w;
    uint local = element - pc.draw.y;
    ElementRecord rec;
    if (SUBMIT == 0) {
        rec = pc.rec;
    } else if (SUBMIT == 1) {
        rec = rec_ubo.recs[element % uint(UBO_WINDOW)];
    } else {
        rec = records[local];
    }
    uvec4 n = adaptive_levels(element_levels[local], f);
    // The finest lattice's weights are exact multiples of 1/f: (i, j) back exactly.
    uvec2 ij = uvec2(in_bary.y * float(f), in_bary.z * float(f));
    ij = adaptive_snap(ij, n, f);
    int l = findMSB(f);
    vec3 bary = vec3(ldexp(float(f - ij.x - ij.y), -l), ldexp(float(ij.x), -l), ldexp(float(ij.y), -l));
    SurfacePoint sp = evaluate(rec, Sample(local, bary));
    v_position = sp.position;
    v_normal = sp.normal;
    v_element = local;
    v_bary = bary;
    gl_Position = frame.view_proj * vec4(sp.position, 1.0);
#ifdef CAPTURE
    // The finest pattern's slots; id.z the element's drawn inner level, id.w 1 (adaptive).
    captured[(element - capture_first) * pc.draw.z + uint(gl_VertexIndex)] =
        CapturedVertex(vec4(sp.position, 1.0), vec4(sp.normal, 0.0), vec4(bary, 0.0),
                       uvec4(element, uint(gl_VertexIndex), n.w, 1u));
#endif
}
