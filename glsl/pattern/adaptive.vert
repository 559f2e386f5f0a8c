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
// Geomorphing (docs/adaptivity.md): 1 morphs the vertices the finest drawn levels add.
layout(constant_id = SPEC_GEOMORPH) const uint GEOMORPH = 0;

// `ubo` submission, as in pattern.vert.
layout(set = SET_MESH, binding = BINDING_ELEMENT_UBO, std140) uniform RecordUbo { ElementRecord recs[UBO_WINDOW]; } rec_ubo;

layout(location = 0) in vec3 in_bary; // (w, u, v) of the finest level pc.draw.x
// `instanced`: the element of this instance, from its bin's list (bound at the bin's first
// entry, src/render/pattern.rs); the other modes ignore it.
layout(location = 8) in uint in_element;

// The weights of finest-lattice point ij (exact dyadic fractions).
vec3 lattice_weights(uvec2 ij, uint f) {
    int l = findMSB(f);
    return vec3(ldexp(float(f - ij.x - ij.y), -l), ldexp(float(ij.x), -l), ldexp(float(ij.y), -l));
}

vec3 point_at(ElementRecord rec, uint local, uvec2 ij, uint f) {
    return evaluate(rec, Sample(local, lattice_weights(ij, f))).position;
}

// A boundary point drawn: its snapped sample ij (on stored edge k, true position p), morphing
// with the edge's continuous level when the edge's drawn level adds it.
vec3 edge_drawn(ElementRecord rec, uint local, uvec2 ij, vec3 p, uint ne, float lambda, uint f) {
    uint s = f / ne;
    if (!morph_is_new(ij, s)) {
        return p;
    }
    float m = morph_factor(lambda, ne);
    if (m >= 1.0) {
        return p;
    }
    uvec2 a, b;
    morph_parents(ij, s, a, b);
    return morph(point_at(rec, local, a, f), point_at(rec, local, b, f), p, m);
}

// A parent's drawn position: snapped and morphing with its edge on the boundary, else true.
vec3 parent_drawn(ElementRecord rec, uint local, uvec2 q, uvec4 n, vec4 lv, uint f) {
    int k = morph_edge(q, f);
    if (k < 0) {
        return point_at(rec, local, q, f);
    }
    uvec2 qs = adaptive_snap(q, n, f);
    return edge_drawn(rec, local, qs, point_at(rec, local, qs, f), n[k], lv[k], f);
}

// Where the geomorphing driver draws finest-lattice point raw (before snapping; ij after, true
// position p). Mirror: adaptive::geomorph_position.
vec3 geomorph_position(ElementRecord rec, uint local, uvec2 raw, uvec2 ij, vec3 p, uvec4 n, vec4 lv,
                       uint f) {
    int k = morph_edge(raw, f);
    if (k >= 0) {
        return edge_drawn(rec, local, ij, p, n[k], lv[k], f);
    }
    uint s = f / n.w;
    if (!morph_is_new(raw, s)) {
        return p;
    }
    float m = morph_factor(max(lv.w, max(lv.x, max(lv.y, lv.z))), n.w);
    if (m >= 1.0) {
        return p;
    }
    uvec2 a, b;
    morph_parents(raw, s, a, b);
    return morph(parent_drawn(rec, local, a, n, lv, f), parent_drawn(rec, local, b, n, lv, f), p, m);
}

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
    uvec2 raw = uvec2(in_bary.y * float(f), in_bary.z * float(f));
    uvec2 ij = adaptive_snap(raw, n, f);
    vec3 bary = lattice_weights(ij, f);
    SurfacePoint sp = evaluate(rec, Sample(local, bary));
    if (GEOMORPH != 0u) {
        // The normal stays the true point's (docs/adaptivity.md, "Geomorphing").
        sp.position = geomorph_position(rec, local, raw, ij, sp.position, n, element_levels[local], f);
    }
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
