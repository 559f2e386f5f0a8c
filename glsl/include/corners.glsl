// The local surfaces' record (a coarse triangle's corners) and its canonical corner order: what
// makes refinement watertight. Mirror: src/surface/mod.rs `canonical`, src/surface/record.rs.
//
// Corners are sorted by global vertex index, and zero-weight corners are moved last. A point on a
// coarse edge shared by two triangles is then evaluated from the same two corners, in the same
// order, with the same weights, in both triangles, and every term of the third corner carries its
// exact zero weight: bit-identical positions.
#ifndef CORNERS_GLSL
#define CORNERS_GLSL
#include "records.glsl"

// Layout of `CornerRecord` (src/surface/record.rs) inside an ElementRecord.
struct CornerRecord {
    vec3 p[3];   // corner positions
    vec3 n[3];   // corner unit normals (shading)
    vec3 g[3];   // position normals at split positions (closed seams), n elsewhere
    uvec4 idx;   // xyz: global position index of each corner (canonical order key); w: seam flags
};

// `w` of a position marking a corner whose geometry normal is its normal (src/surface/record.rs).
const float SMOOTH_CORNER = 2.0;

float sign_not_zero(float v) { return v >= 0.0 ? 1.0 : -1.0; }

// Unit vector of an octahedral encoding. Mirror: src/surface/record.rs `oct_decode`.
vec3 oct_decode(vec2 e) {
    vec3 v = vec3(e.x, e.y, 1.0 - abs(e.x) - abs(e.y));
    if (v.z < 0.0) {
        v.xy = vec2((1.0 - abs(v.y)) * sign_not_zero(v.x), (1.0 - abs(v.x)) * sign_not_zero(v.y));
    }
    return normalize(v);
}

CornerRecord corner_record(ElementRecord e) {
    CornerRecord r;
    for (int i = 0; i < 3; ++i) {
        r.p[i] = uintBitsToFloat(e.d[i].xyz);
        r.n[i] = uintBitsToFloat(e.d[3 + i].xyz);
        vec2 oct = vec2(uintBitsToFloat(e.d[i].w), uintBitsToFloat(e.d[3 + i].w));
        r.g[i] = oct.x == SMOOTH_CORNER ? r.n[i] : oct_decode(oct);
    }
    r.idx = e.d[6];
    return r;
}

struct Corners {
    vec3 p[3];
    vec3 n[3];   // shading normals
    vec3 g[3];   // position normals at split positions
    bool seam_pn[3];    // canonical edge e (corners e, e+1 mod 3) builds PN geometry from g
    bool seam_phong[3]; // ... Phong geometry
    vec3 w;      // weight of each corner, in canonical order
    int o[3];    // the stored corner each canonical corner is
};

// Dot product in a fixed operation order, without fused multiply-add (the built-in `dot` leaves
// both to the implementation). Mirror: src/surface/mod.rs `dot3`.
float dot3(vec3 a, vec3 b) {
    precise float d = a.x * b.x + a.y * b.y + a.z * b.z;
    return d;
}

// Below this squared length a normal field's value is taken to vanish (`unit_field`). Mirror:
// src/surface/mod.rs `FIELD_MIN2`.
const float FIELD_MIN2 = 1e-24;

// Whether corner i weighs more than corner j at the sample, the larger normal (compared x, then y,
// then z) on a tie. Mirror: src/surface/mod.rs `heavier`.
bool heavier(Corners c, int i, int j) {
    if (c.w[i] != c.w[j]) return c.w[i] > c.w[j];
    vec3 a = c.n[i], b = c.n[j];
    if (a.x != b.x) return a.x > b.x;
    if (a.y != b.y) return a.y > b.y;
    return a.z > b.z;
}

// A normal field's value v at the sample, made unit length. Where it vanishes (corner normals
// pointing opposite ways, as across a fold of the mesh), the normal of the corner weighing most:
// chosen from the corners' weights and normals alone, whatever their order, so that the two
// elements sharing an edge choose the same one there (displacement moves along it). Mirror:
// src/surface/mod.rs `unit_field`.
vec3 unit_field(vec3 v, Corners c) {
    if (dot3(v, v) > FIELD_MIN2) {
        return normalize(v);
    }
    int best = 0;
    for (int i = 1; i < 3; ++i) {
        if (heavier(c, i, best)) best = i;
    }
    return c.n[best];
}

// The edge (0: corners 0-1, 1: 1-2, 2: 2-0) joining corners i and j, either way round.
// Mirror: src/surface/mod.rs `edge_of`.
int edge_of(int i, int j) {
    return (i + 1) % 3 == j ? i : j;
}

uint canonical_key(uint index, float weight) {
    // Zero weights sort last; then by vertex index (indices are < 2^31, see mesh loading).
    return (weight == 0.0 ? 0x80000000u : 0u) | index;
}

Corners canonical(CornerRecord t, vec3 bary) {
    uint k[3] = uint[3](canonical_key(t.idx.x, bary.x), canonical_key(t.idx.y, bary.y),
                        canonical_key(t.idx.z, bary.z));
    int o[3] = int[3](0, 1, 2);
    // Three-element sorting network on the keys (ties keep the original order).
    if (k[o[1]] < k[o[0]]) { int s = o[0]; o[0] = o[1]; o[1] = s; }
    if (k[o[2]] < k[o[1]]) { int s = o[1]; o[1] = o[2]; o[2] = s; }
    if (k[o[1]] < k[o[0]]) { int s = o[0]; o[0] = o[1]; o[1] = s; }
    Corners c;
    for (int i = 0; i < 3; ++i) {
        c.p[i] = t.p[o[i]];
        c.n[i] = t.n[o[i]];
        c.g[i] = t.g[o[i]];
        // Seam flags (src/surface/record.rs `SeamFlags`) of canonical edge i, by its stored edge.
        int e = edge_of(o[i], o[(i + 1) % 3]);
        c.seam_pn[i] = ((t.idx.w >> uint(e)) & 1u) == 1u;
        c.seam_phong[i] = ((t.idx.w >> uint(3 + e)) & 1u) == 1u;
        c.w[i] = bary[o[i]];
        c.o[i] = o[i];
    }
    return c;
}

// The corners in stored order, for `flat` (src/surface/mod.rs `stored_order`: its two non-zero
// terms on a shared edge add the same in either order, `precise` keeps them unfused).
Corners stored_corners(CornerRecord t, vec3 bary) {
    Corners c;
    for (int i = 0; i < 3; ++i) {
        c.p[i] = t.p[i];
        c.n[i] = t.n[i];
        c.g[i] = t.g[i];
        int e = i;
        c.seam_pn[i] = ((t.idx.w >> uint(e)) & 1u) == 1u;
        c.seam_phong[i] = ((t.idx.w >> uint(3 + e)) & 1u) == 1u;
        c.w[i] = bary[i];
        c.o[i] = i;
    }
    return c;
}

#endif
