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
// Geomorphing (docs/adaptivity.md): 1 morphs the vertices the finest drawn levels add, at
// dyadic levels from the hierarchical patterns; 0 draws integer levels from the integer
// patterns (non-nested levels cannot glide).
layout(constant_id = SPEC_GEOMORPH) const uint GEOMORPH = 0;

// `ubo` submission, as in pattern.vert.
layout(set = SET_MESH, binding = BINDING_ELEMENT_UBO, std140) uniform RecordUbo { ElementRecord recs[UBO_WINDOW]; } rec_ubo;

// (w, u, v) of the finest level pc.draw.x (GEOMORPH), of the element's inner level (integer
// patterns: the draw's vertex offset picks the level's vertices).
layout(location = 0) in vec3 in_bary;
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

// Where a lattice point q is drawn (the geomorph plan, without evaluating): its snapped sample
// qs (q itself inside) and, when that sample lies on stored edge k and the edge's drawn level
// adds it with a factor m below 1, its two parents on the edge (returns true).
bool edge_plan(uvec2 q, uvec4 n, vec4 lv, uint f, out uvec2 qs, out uvec2 a, out uvec2 b, out float m) {
    qs = q;
    a = q;
    b = q;
    m = 1.0;
    int k = morph_edge(q, f);
    if (k < 0) {
        return false;
    }
    qs = adaptive_snap(q, n, f);
    uint s = f / n[k];
    if (!morph_is_new(qs, s)) {
        return false;
    }
    m = morph_factor(lv[k], n[k]);
    if (m >= 1.0) {
        return false;
    }
    morph_parents(qs, s, a, b);
    return true;
}

// Where the geomorphing driver draws finest-lattice point raw (before snapping; its snapped
// sample's true position p). A boundary point is its snapped sample, morphing with its edge's
// level when that level adds it; an inside point new at the inner level morphs between its parents' drawn
// positions (a boundary parent snapped and morphing with its edge). The surface is evaluated at
// one call site in a loop whose trip count depends on the vertex, so that a costly surface
// (loop's table sums) is compiled once rather than inlined up to six times; the loop runs over
// the evaluations the vertex needs only (a SIMD batch of vertices runs the most any of them
// needs: usually 2, not 6; docs/bench/geomorph-cost.md). Mirror: adaptive::geomorph_position.
vec3 geomorph_position(ElementRecord rec, uint local, uvec2 raw, vec3 p, uvec4 n, vec4 lv, uint f) {
    bool edge = morph_edge(raw, f) >= 0;
    float mi = 1.0;
    uvec2 q0 = raw, q1 = raw;
    if (!edge) {
        uint s = f / n.w;
        if (!morph_is_new(raw, s)) {
            return p;
        }
        mi = morph_factor(max(lv.w, max(lv.x, max(lv.y, lv.z))), n.w);
        if (mi >= 1.0) {
            return p;
        }
        morph_parents(raw, s, q0, q1);
    }
    uvec2 s0, a0, b0, s1, a1, b1;
    float m0, m1;
    bool e0 = edge_plan(q0, n, lv, f, s0, a0, b0, m0);
    bool e1 = !edge && edge_plan(q1, n, lv, f, s1, a1, b1, m1);
    if (edge && !e0) {
        return p;
    }
    // Evaluations: 0 point 0, 1 and 2 its edge parents, 3 point 1, 4 and 5 its edge parents;
    // the j-th needed one is i: an edge point needs 1 and 2, an inside point 0 and 3, with 1 and
    // 2 when e0, 4 and 5 when e1.
    vec3 r0 = p, r1 = p, r2 = p, r3 = p, r4 = p, r5 = p;
    uint jobs = edge ? 2u : (e0 ? 3u : 1u) + (e1 ? 3u : 1u);
    for (uint j = 0u; j < jobs; j++) {
        uint i = edge ? j + 1u : ((e0 || j == 0u) ? j : j + 2u);
        uvec2 w = i == 0u ? s0 : (i == 1u ? a0 : (i == 2u ? b0 : (i == 3u ? s1 : (i == 4u ? a1 : b1))));
        vec3 r = point_at(rec, local, w, f);
        if (i == 0u) r0 = r;
        else if (i == 1u) r1 = r;
        else if (i == 2u) r2 = r;
        else if (i == 3u) r3 = r;
        else if (i == 4u) r4 = r;
        else r5 = r;
    }
    if (edge) {
        return morph(r1, r2, p, m0);
    }
    vec3 pa = e0 ? morph(r1, r2, r0, m0) : r0;
    vec3 pb = e1 ? morph(r4, r5, r3, m1) : r3;
    return morph(pa, pb, p, mi);
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
        rec = fetch_record(local);
    }
    vec4 levels = fetch_levels(local);
    uvec4 n = adaptive_levels(levels, f, GEOMORPH != 0u);
    vec3 bary;
    uvec2 raw;
    if (GEOMORPH != 0u) {
        // The finest lattice's weights are exact multiples of 1/f: (i, j) back exactly.
        raw = uvec2(in_bary.y * float(f), in_bary.z * float(f));
        bary = lattice_weights(adaptive_snap(raw, n, f), f);
    } else {
        // The inner level's weights i/n, j/n (n <= 1024): (i, j) back by rounding.
        raw = uvec2(round(in_bary.yz * float(n.w)));
        bary = integer_weights(raw, n, in_bary);
    }
    SurfacePoint sp = evaluate(rec, Sample(local, bary));
    if (GEOMORPH != 0u) {
        // The normal stays the true point's (docs/adaptivity.md, "Geomorphing").
        sp.position = geomorph_position(rec, local, raw, sp.position, n, levels, f);
    }
    v_position = sp.position;
    v_normal = sp.normal;
    v_element = local;
    v_bary = bary;
    gl_Position = frame.view_proj * vec4(sp.position, 1.0);
#ifdef CAPTURE
    // Packed (src/render/packed_capture.rs): the element's vertices at its inner level only,
    // point (i, j) of that level's own lattice at its lattice index (`bft_row`, the GLSL twin of
    // pattern::lattice_index) after the element's first slot; id.y the pattern's vertex (the
    // hierarchy's, or the integer patterns'), id.z the inner level, id.w 1 (adaptive). A vertex
    // outside the room the capture made for its element (a level other than the one it was
    // sized for) is counted, not written.
    uint s = GEOMORPH != 0u ? f / max(n.w, 1u) : 1u;
    uvec2 q = raw / s;
    uint slot = capture_offsets[element] + bft_row(n.w, q.x, q.y);
    bool lattice = all(equal(raw % s, uvec2(0u)));
    if (!lattice) {
        // Not a vertex of the inner level (never drawn: its triangles index none).
    } else if (n.w != 0u && slot < capture_offsets[element + 1u] && slot - capture_base < capture_capacity) {
        captured[slot - capture_base] =
            CapturedVertex(vec4(sp.position, 1.0), vec4(sp.normal, 0.0), vec4(bary, 0.0),
                           uvec4(element, uint(gl_VertexIndex), n.w, 1u));
    } else {
        atomicAdd(capture_count, 1u);
    }
#endif
}
