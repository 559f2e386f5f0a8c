#version 460
// The level pass: each element's levels for this frame (its stored edges' continuous levels and
// its inner level; inner 0: culled) from its bounds, computed once (LodRecord), and the camera
// (push constants). One invocation per element, over the whole levels buffer. Where the view
// lifts edges (LIFT: at integer levels to save transitions, at gliding ones to the insides'
// needs), a second dispatch lifts them from what the first left of every element
// (src/lod/frame/lift.rs; where levels glide the first leaves only the insides' needs, and the
// second chooses every level), with a pipeline of its own (LIFTING: lavapipe would run the other
// dispatch's code too behind a uniform branch).
// Mirror, operation for operation: src/lod/frame.rs `frame_levels` (the proof of the
// transition triangles is in src/lod/frame/transitions.rs); tests/level_pass.rs compares the two.
layout(local_size_x = 64) in;

#include "lod_metric.glsl"

const uint CULL_FRUSTUM = 1u;
const uint CULL_BACK_FACES = 2u;
const uint DYADIC = 4u;
const uint LATTICE = 8u;
const uint LIFT = 16u;
// 1: the lift's dispatch; 0: the first.
layout(constant_id = SPEC_LIFTING) const uint LIFTING = 0u;

// The element's bounds (src/lod/frame.rs LodRecord, 480 bytes): 30 texels of a uniform texel
// buffer, at these offsets. The level pass reads them as texels, not from a storage buffer:
// lavapipe loads a storage buffer one invocation and one component at a time, a texel buffer
// with vector gathers, and the pass's time there is mostly its loads
// (docs/bench/level-pass-loads.md).
const int RECORD_TEXELS = 30;
const int RECORD_SPHERE = 0;
const int RECORD_CONE = 1;   // axis, cosine of the half-angle (0: none)
const int RECORD_CHORD = 2;  // (c1, c2), then the kink terms (k1, k2)
const int RECORD_SECOND = 3; // M_k per stored direction, then the cubic term (LOD_HUGE: none)
const int RECORD_MIXED = 4;  // B_k per stored pair of directions (k, k + 1)
// Each stored edge (LodEdge, 8 texels from RECORD_EDGES + 8 e): the edge curve's (c1, c2),
// then both elements' cubic terms (LOD_HUGE: none); each element's transition need (c1, c2)
// per rounding (tess snapped, integer, snapped, snapped integer: src/lod/frame.rs
// Rounding::ALL); the edge's sphere; its two elements' spheres.
const int RECORD_EDGES = 5;
const int EDGE_CURVE = 0;
const int EDGE_NEEDS = 1;
const int EDGE_SPHERE = 5;
const int EDGE_SPHERE_A = 6;
const int EDGE_SPHERE_B = 7;
// Its neighbours across its stored edges (`j * 4 + e'`, NO_NEIGHBOUR or SHARED_EDGE), read as
// unsigned integers through lod_neighbours.
const int RECORD_NEIGHBOURS = 29;
const uint NO_NEIGHBOUR = 0xffffffffu;
const uint SHARED_EDGE = 0xfffffffeu;

layout(set = 0, binding = LEVEL_BINDING_RECORDS) uniform samplerBuffer lod_records;

vec4 record(uint i, int texel) {
    return texelFetch(lod_records, int(i) * RECORD_TEXELS + texel);
}

layout(set = 0, binding = LEVEL_BINDING_NEIGHBOURS) uniform usamplerBuffer lod_neighbours;

// The mesh's levels buffer, whole (src/lod/levels.rs ElementLevels).
layout(set = 0, binding = LEVEL_BINDING_LEVELS, std430) buffer Levels {
    vec4 element_levels[];
};

// What the first dispatch leaves of each element for the lift (src/lod/frame/lift.rs `Before`:
// own, inner, failing, inside): this chunk's elements, and every element (the neighbours').
layout(set = 0, binding = LEVEL_BINDING_BEFORE, std430) buffer Before {
    vec4 before[];
};
layout(set = 0, binding = LEVEL_BINDING_BEFORE_ALL, std430) readonly buffer BeforeAll {
    vec4 before_all[];
};

// What a drawn element's levels read of its record (after culling, which reads only the
// sphere and the cone), and of each edge only the needs of this frame's rounding.
struct Element {
    vec4 sphere;
    vec4 chord;
    vec4 second;
    vec4 mixed;
};

struct Edge {
    vec4 curve;
    vec4 needs; // this frame's rounding's
    vec4 sphere;
    vec4 sphere_a;
    vec4 sphere_b;
};

// src/lod/frame.rs LodView.
layout(push_constant) uniform View {
    vec4 planes[6];
    vec4 eye_k;
    float pixel_error;
    uint max_level;
    uint flags;
    uint count;
} view;

// The metric as src/lod/frame.rs reads it from the view. Mirror: `tolerance`, `level`.
LodView metric() {
    return LodView(view.eye_k.xyz, view.eye_k.w, view.pixel_error, float(view.max_level));
}

float tolerance(vec4 s) {
    return lod_tolerance(metric(), s);
}

float level(vec2 c, vec4 s) {
    return lod_level(metric(), c, s);
}

// Mirror: `level_at` (a sphere's tolerance computed once for the levels it gives).
float level_at(vec2 c, float tol) {
    return lod_level_at(metric(), c, tol);
}

// Mirror: src/lod/bound.rs `second_along`.
float second_along(vec3 m, vec3 b, vec2 e) {
    float x = e.x, y = e.y;
    float w = x + y;
    float p = x * x * m[0] + y * y * m[2] + 2.0 * abs(x * y) * b[2];
    float q = w * w * m[0] + y * y * m[1] + 2.0 * abs(w * y) * b[0];
    float c = x * x * m[1] + w * w * m[2] + 2.0 * abs(x * w) * b[1];
    return min(min(p, q), c);
}

// Mirror: `own_chord` (the tessellator's ring diagonals, src/lod/mod.rs).
vec2 own_chord(Element r) {
    vec2 c = r.chord.xy;
    vec3 m = r.second.xyz;
    float mx = max(m.x, max(m.y, m.z));
    if ((view.flags & LATTICE) != 0u || c.x >= LOD_HUGE || c.y >= LOD_HUGE || mx >= LOD_HUGE) {
        return c;
    }
    vec3 b = r.mixed.xyz;
    float ring = max(max(second_along(m, b, vec2(1.0, 1.0)), second_along(m, b, vec2(2.0, -1.0))),
                     second_along(m, b, vec2(-1.0, 2.0))) * LOD_RING_DIAGONAL;
    float k1 = r.chord.z, k2 = r.chord.w;
    return vec2(c.x + k1 / 3.0, c.y + LOD_ELEMENT_FACTOR * max(ring - mx, 0.0) + (7.0 / 9.0) * k2);
}

// Mirror: `glide_factor` (src/lod/frame/inside.rs).
float glide_factor() {
    return (view.flags & DYADIC) != 0u ? 2.0 : 1.0;
}

// Mirror: `own_level_above` (a polynomial patch's tighter bound, src/lod/mod.rs; not computed
// where the general bound's level is at most `floor`).
float own_level_above(Element r, float floor_level) {
    float tol = tolerance(r.sphere);
    float general = level_at(own_chord(r), tol);
    if (general <= floor_level) {
        return floor_level;
    }
    vec3 m = r.second.xyz;
    float mx = max(m.x, max(m.y, m.z));
    float t = r.second.w;
    if (t >= LOD_HUGE || mx >= LOD_HUGE) {
        return general;
    }
    float q = mx;
    if ((view.flags & LATTICE) == 0u) {
        vec3 b = r.mixed.xyz;
        float ring = max(max(second_along(m, b, vec2(1.0, 1.0)), second_along(m, b, vec2(2.0, -1.0))),
                         second_along(m, b, vec2(-1.0, 2.0))) * LOD_RING_DIAGONAL;
        q = max(mx, ring);
        t *= LOD_TESS_CUBIC;
    }
    q *= LOD_QUADRATIC_FACTOR;
    float n0 = level_at(vec2(0.0, q), tol);
    float n1 = level_at(vec2(0.0, q + glide_factor() * t / n0), tol);
    return max(floor_level, min(general, n1));
}

// Mirror: `edge_need_level` (a polynomial patch's transition need, src/lod/frame/transitions.rs;
// at least `floor_level`, the polynomial bound not computed where the chord's level is at most it).
float edge_need_level(vec2 need, float t, float tol, float floor_level) {
    float general = level_at(need, tol);
    if (general <= floor_level) {
        return floor_level;
    }
    if (t >= LOD_HUGE || need.x != 0.0 || need.y >= LOD_HUGE) {
        return general;
    }
    float q = need.y * LOD_POLYNOMIAL_SHARE;
    // `need_extent_cubed`: 1 at snapped integer levels, (5/4)^3 gliding snapped, (1 + lambda)^3
    // beside the tessellator's rings.
    uint kind = view.flags & (DYADIC | LATTICE);
    t *= kind == LATTICE ? 1.0 : (kind == (DYADIC | LATTICE) ? 1.953125 : (kind == 0u ? 8.0 : 3.375));
    float n0 = level_at(vec2(0.0, q), tol);
    return max(floor_level, min(general, level_at(vec2(0.0, q + glide_factor() * t / n0), tol)));
}

// The index of this frame's rounding's needs in `LodEdge::needs`. Mirror: `Rounding::index`.
int needs_index() {
    uint kind = view.flags & (DYADIC | LATTICE);
    return kind == 0u ? 1 : (kind == DYADIC ? 0 : (kind == LATTICE ? 3 : 2));
}

Edge load_edge(uint i, int e) {
    int base = RECORD_EDGES + 8 * e;
    return Edge(record(i, base + EDGE_CURVE), record(i, base + EDGE_NEEDS + needs_index()),
                record(i, base + EDGE_SPHERE), record(i, base + EDGE_SPHERE_A),
                record(i, base + EDGE_SPHERE_B));
}

// Mirror: `edge_level`.
float edge_level(Edge e) {
    float own = level(e.curve.xy, e.sphere);
    float a = edge_need_level(e.needs.xy, e.curve.z, tolerance(e.sphere_a), own);
    return edge_need_level(e.needs.zw, e.curve.w, tolerance(e.sphere_b), a);
}

// Mirror: src/lod/levels.rs `drawn_level` (glsl/include/levels.glsl).
uint drawn(float level, bool dyadic, uint max_level) {
    if (level <= 0.0) {
        return 0u;
    }
    uint n = level >= float(max_level) ? max_level : clamp(uint(ceil(level)), 1u, max_level);
    if (dyadic && n > 1u) {
        n = 1u << (findMSB(n - 1u) + 1);
    }
    return min(n, max_level);
}

// Mirror: `twist`.
float twist(vec3 mixed, int e) {
    return 2.0 * max(mixed[e], mixed[(e + 2) % 3]);
}

// Mirror: `quadratic_level`.
float quadratic_level(float p, float q, float c, float tol, float mx) {
    if (c >= tol) {
        return mx;
    }
    if ((p + q + c) * LOD_LEVEL_ONE_MARGIN <= tol) {
        return 1.0;
    }
    float d = tol - c;
    float den = q + sqrt(q * q + 4.0 * p * d);
    if (den <= 0.0) {
        return 1.0;
    }
    float beta = 2.0 * d / den;
    return clamp((1.0 + 1.0 / 65536.0) / beta, 1.0, mx);
}

// Mirror: `cubic_level`: the cubic term t (e0 + e1 b)^3, ext = (e0, e1).
float cubic_bound(vec3 pqc, float t, vec2 ext, float b) {
    float s = ext.x + ext.y * b;
    return (pqc.x * b + pqc.y) * b + pqc.z + t * s * s * s;
}

float cubic_level(vec3 pqc, float t, vec2 ext, float a, float tol, float mx) {
    if (cubic_bound(pqc, t, ext, 0.0) >= tol) {
        return mx;
    }
    if (cubic_bound(pqc, t, ext, a) <= tol) {
        return clamp(1.0 / a, 1.0, mx);
    }
    float b = min(1.0 / quadratic_level(pqc.x, pqc.y, pqc.z, tol, mx), a);
    for (int it = 0; it < 4; ++it) {
        float s = ext.x + ext.y * b;
        float slope = 2.0 * pqc.x * b + pqc.y + 3.0 * t * ext.y * s * s;
        if (slope <= 0.0) {
            break;
        }
        b -= (cubic_bound(pqc, t, ext, b) - tol) / slope;
    }
    float ts = t * (ext.x + ext.y * clamp(b, 0.0, a));
    return quadratic_level(pqc.x + ts * ext.y * ext.y, pqc.y + 2.0 * ts * ext.x * ext.y,
                           pqc.z + ts * ext.x * ext.x, tol, mx);
}

// Mirror: `tess_side_coefficients`.
vec3 tess_side_coefficients(float me, float t, float mb) {
    return vec3(0.25 * me, (2.0 / 3.0) * me + t / 3.0, (4.0 / 9.0) * (me + t + mb));
}

// Mirror: `Strip` (src/lod/frame/transitions.rs): step 2's bound of the transition triangles
// along stored edge e drawn at a = 1/n_e beside an inside at beta, as quadratics (p, q, c) in
// beta, each with its triangles' sides' extent e0 + e1 beta (`ext`): the sides' and the bases'
// (none where the sides hold them), at a + beta, or where the lattice's boundary is snapped at
// a/2 + beta and at a; and a polynomial patch's cubic term t3 (`polynomial`).
struct Strip {
    vec3 quads[4];
    vec2 exts[4];
    int count;
    float a, t3;
    bool polynomial;
};

Strip strip_new(Element r, int e, float a) {
    vec3 m = r.second.xyz;
    float k1 = r.chord.z, k2 = r.chord.w;
    float t = twist(r.mixed.xyz, e);
    float mb = max(m[(e + 1) % 3], m[(e + 2) % 3]);
    uint kind = view.flags & (DYADIC | LATTICE);
    vec3 sides;
    float reach = a;
    if (kind == DYADIC) {
        // The tessellator's first ring beside a snapped outer ring.
        vec3 s = tess_side_coefficients(m[e], t, mb);
        sides = vec3(s.z, s.y * a, s.x * a * a);
    } else {
        float h = kind == 0u ? 1.0 : 0.5;
        sides = vec3(mb, h * a * t, h * h * a * a * m[e]);
        if ((kind & LATTICE) != 0u) {
            reach = 0.5 * a;
        }
    }
    bool has_bases = kind != 0u;
    Strip st;
    st.count = 0;
    for (int x = 0; x < (reach < a ? 2 : 1); ++x) {
        vec2 ext = x == 0 ? vec2(reach, 1.0) : vec2(a, 0.0);
        // The kink terms at extent e0 + e1 beta.
        vec3 kink = vec3(k2 * ext.y * ext.y, (k1 + 2.0 * k2 * ext.x) * ext.y,
                         (k1 + k2 * ext.x) * ext.x);
        for (int y = 0; y < (has_bases ? 2 : 1); ++y) {
            vec3 quad = y == 0 ? sides : vec3(0.0, 0.0, a * a * m[e]);
            st.quads[st.count] = LOD_ELEMENT_FACTOR * quad + kink;
            st.exts[st.count] = ext;
            st.count += 1;
        }
    }
    st.a = a;
    st.t3 = r.second.w;
    st.polynomial = st.t3 < LOD_HUGE && k1 == 0.0 && k2 == 0.0;
    return st;
}

// A quadratic's level, and where it needs more than `enough` the polynomial bound's (in
// `Strip::level`).
float strip_solve(Strip st, int i, float tol, float enough) {
    float mx = float(view.max_level);
    vec3 pqc = st.quads[i];
    float general = quadratic_level(pqc.x, pqc.y, pqc.z, tol, mx);
    if (st.polynomial && general > enough) {
        return min(general, cubic_level(LOD_POLYNOMIAL_SHARE * pqc, st.t3, st.exts[i], st.a, tol, mx));
    }
    return general;
}

// Mirror: `Strip::level`. `enough`: the level the caller compares with (the polynomial bound is
// solved only above it).
float strip_level(Strip st, float tol, float enough) {
    float level = 1.0;
    for (int i = 0; i < st.count; ++i) {
        level = max(level, strip_solve(st, i, tol, enough));
    }
    return level;
}

// Mirror: `Strip::fits`: the bounds at beta = (1 + 2^-16)/n, no square root or Newton's steps.
bool strip_fits(Strip st, float n, float tol) {
    float b = (1.0 + 1.0 / 65536.0) / n;
    for (int i = 0; i < st.count; ++i) {
        vec3 pqc = st.quads[i];
        float quad = (pqc.x * b + pqc.y) * b + pqc.z;
        float s = st.exts[i].x + st.exts[i].y * b;
        if (!(quad < tol || (st.polynomial && LOD_POLYNOMIAL_SHARE * quad + st.t3 * s * s * s < tol))) {
            return false;
        }
    }
    return true;
}

// Mirror: `outside` (`lod_outside`).
bool outside(vec4 s) {
    vec4 planes[6] = view.planes;
    return lod_outside(planes, s);
}

// Mirror: `raise_for_transitions` (with the edges whose triangles do not fit at the level it
// starts from, bit e of `failing`).
float raise_for_transitions(Element r, vec3 edges, float inner, out uint failing) {
    bool dyadic = (view.flags & DYADIC) != 0u;
    uint mx = view.max_level;
    failing = 0u;
    if (r.chord.y >= LOD_HUGE || r.chord.x >= LOD_HUGE) {
        return inner;
    }
    float tol = tolerance(r.sphere);
    uvec3 ne = uvec3(drawn(edges.x, dyadic, mx), drawn(edges.y, dyadic, mx),
                     drawn(edges.z, dyadic, mx));
    uint n = drawn(inner, dyadic, mx);
    bool raised = false;
    for (int it = 0; it < 4; ++it) {
        if (n >= mx) {
            break;
        }
        float need = 0.0;
        for (int e = 0; e < 3; ++e) {
            if (ne[e] < n) {
                // Solved only where the bound at n is not met.
                Strip st = strip_new(r, e, 1.0 / float(ne[e]));
                if (!strip_fits(st, float(n), tol)) {
                    need = max(need, strip_level(st, tol, float(n)));
                    if (it == 0) {
                        failing |= 1u << e;
                    }
                }
            }
        }
        if (need <= float(n)) {
            break;
        }
        n = drawn(need, dyadic, mx);
        raised = true;
    }
    return raised ? float(n) : inner;
}

Element load_element(uint i, vec4 sphere) {
    return Element(sphere, record(i, RECORD_CHORD), record(i, RECORD_SECOND),
                   record(i, RECORD_MIXED));
}

// The first dispatch. Mirror: `element_levels` (`first_levels`); where levels glide,
// `Before::inside`.
void first_levels(uint i) {
    vec4 sphere = record(i, RECORD_SPHERE);
    bool culled = ((view.flags & CULL_FRUSTUM) != 0u && outside(sphere))
        || ((view.flags & CULL_BACK_FACES) != 0u
            && lod_back_facing(record(i, RECORD_CONE), sphere, view.eye_k.xyz));
    bool lift = (view.flags & LIFT) != 0u;
    // A culled element draws nothing, and an edge's level is computed by each element that
    // draws it: no level is needed here.
    if (culled) {
        element_levels[i] = vec4(0.0);
    }
    // Where levels glide, the lift's dispatch chooses every level; this one leaves each
    // element's inside need (a culled one's too: its edges still take it) and whether it
    // draws. Mirror: `Before::inside`.
    if (lift && (view.flags & DYADIC) != 0u) {
        before[i] = vec4(0.0, culled ? 0.0 : 1.0, 0.0,
                         own_level_above(load_element(i, sphere), 0.0));
        return;
    }
    if (culled) {
        if (lift) {
            before[i] = vec4(0.0);
        }
        return;
    }
    Element r = load_element(i, sphere);
    vec3 edges = vec3(edge_level(load_edge(i, 0)), edge_level(load_edge(i, 1)),
                      edge_level(load_edge(i, 2)));
    float own = own_level_above(r, max(edges.x, max(edges.y, edges.z)));
    uint failing;
    float inner = raise_for_transitions(r, edges, own, failing);
    element_levels[i] = vec4(edges, inner);
    if (lift) {
        before[i] = vec4(own, inner, float(failing), 0.0);
    }
}

// The lift's dispatch where levels glide. Mirror: src/lod/frame/lift.rs `glided`.
void glide_levels(uint i, vec4 me) {
    vec3 edges = vec3(edge_level(load_edge(i, 0)), edge_level(load_edge(i, 1)),
                      edge_level(load_edge(i, 2)));
    uvec4 across = texelFetch(lod_neighbours, int(i) * RECORD_TEXELS + RECORD_NEIGHBOURS);
    for (int e = 0; e < 3; ++e) {
        uint a = across[e];
        if (a != SHARED_EDGE) {
            float other = a == NO_NEIGHBOUR ? me.w : before_all[a / 4u].w;
            // The same maximum from both sides (max is exact and commutative).
            edges[e] = max(edges[e], max(me.w, other));
        }
    }
    // own_level_above(r, largest), the same bits: the larger of the floor and the own need.
    float own = max(max(edges.x, max(edges.y, edges.z)), me.w);
    uint failing;
    float inner = raise_for_transitions(load_element(i, record(i, RECORD_SPHERE)), edges, own,
                                        failing);
    element_levels[i] = vec4(edges, inner);
}

// Mirror: `Before::proposal` (0: none).
uint proposal(vec4 b, uint slot, uint edge, vec4 other, bool has_other) {
    uint mx = view.max_level;
    uint n = drawn(b.x, false, mx);
    uint across = (has_other && other.y > 0.0) ? drawn(other.y, false, mx) : 0xffffffffu;
    return ((uint(b.z) >> slot) & 1u) != 0u && n > edge && n <= across ? n : 0u;
}

// The lift's dispatch. Mirror: src/lod/frame/lift.rs `lifted` (at integer levels), `glided`.
void lift_levels(uint i) {
    vec4 me = before[i];
    if (me.y <= 0.0) {
        return;
    }
    if ((view.flags & DYADIC) != 0u) {
        glide_levels(i, me);
        return;
    }
    uint mx = view.max_level;
    vec4 l = element_levels[i];
    vec3 edges = l.xyz;
    uvec4 across = texelFetch(lod_neighbours, int(i) * RECORD_TEXELS + RECORD_NEIGHBOURS);
    for (int e = 0; e < 3; ++e) {
        uint a = across[e];
        if (a == SHARED_EDGE) {
            continue;
        }
        uint drawn_edge = drawn(l[e], false, mx);
        bool has_other = a != NO_NEIGHBOUR;
        vec4 other = has_other ? before_all[a / 4u] : vec4(0.0);
        uint n = proposal(me, uint(e), drawn_edge, other, has_other);
        if (has_other && other.y > 0.0) {
            n = max(n, proposal(other, a % 4u, drawn_edge, me, true));
        }
        if (n > 0u) {
            edges[e] = float(n);
        }
    }
    if (edges == l.xyz) {
        return;
    }
    Element r = load_element(i, record(i, RECORD_SPHERE));
    float own = own_level_above(r, max(edges.x, max(edges.y, edges.z)));
    uint failing;
    float inner = raise_for_transitions(r, edges, own, failing);
    element_levels[i] = vec4(edges, inner);
}

void main() {
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u;
    if (i >= view.count) {
        return;
    }
    if (LIFTING != 0u) {
        lift_levels(i);
    } else {
        first_levels(i);
    }
}
