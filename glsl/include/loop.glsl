// The `loop` surface (Holländer & Boubekeur 2010): Loop subdivision's limit surface over every
// M1 face from basis function tables, normals by subdivision shading. Elements are M1 faces;
// their records hold the face and the owners of its edges and corners (a sample on a shared edge
// or corner is evaluated by its owner, with the same weights on the same vertices, so both sides
// compute the very same call: watertight). Mirror: src/surface/loop.rs.
#ifndef LOOP_GLSL
#define LOOP_GLSL
#include "displace.glsl"

// Written by the Loop passes (glsl/loop), read here.
layout(set = SET_MESH, binding = BINDING_LOOP_P1) uniform samplerBuffer loop_p1_t;
layout(set = SET_MESH, binding = BINDING_LOOP_N1) uniform samplerBuffer loop_n1_t;
// Per M1 face: (its table's first row-map entry, control points K | the table's column pairs
// << 16, first control index, orientation: rotation in bits 0-1, bit 2 set where the face is its
// configuration's mirror image, the tables' level from bit 3: 2^level segments per edge).
layout(set = SET_MESH, binding = BINDING_LOOP_FACES) uniform usamplerBuffer loop_faces_t;
// Control points, four M1 vertex indices a texel: a face's K padded to K4, a multiple of four
// (the padding repeats its first control point, with weight zero).
layout(set = SET_MESH, binding = BINDING_LOOP_CONTROL) uniform usamplerBuffer loop_control4;
// The tables' distinct rows, four weights a texel, each row at least K4 weights (the padding
// zero) for every table that reads it. Read four at a time, as the control points: texel
// buffers, because lavapipe fetches texels as vector gathers but reads storage buffers lane by
// lane. Mirror: bft::Packed.
layout(set = SET_MESH, binding = BINDING_LOOP_TABLES) uniform samplerBuffer bft4;
// Every table's rows: the row's first texel in bft4 times two, plus one where the row is the
// mirror image of the stored one (a symmetric table's row across its axis: the weights of its
// column pairs swapped).
layout(set = SET_MESH, binding = BINDING_LOOP_ROWS) uniform usamplerBuffer bft_rows_t;
#define loop_p1_at(i) texelFetch(loop_p1_t, int(i))
#define loop_n1_at(i) texelFetch(loop_n1_t, int(i))
// What this stage sums: positions where it places vertices (and for displacement, which needs
// them in the fragment stage too); M1's normals (subdivision shading) except in the drawing
// stages when the fragment stage sums them (FRAGMENT_FIELD: loop at high levels, without
// displacement; src/render/mod.rs `DrawConfig::fragment_normal_field`), and always for the
// tests' captures.
#if defined(FRAGMENT_STAGE)
const bool LOOP_POSITIONS = DISPLACE != DISPLACE_NONE;
const bool LOOP_NORMALS = true;
#elif defined(CAPTURE) || defined(XFB)
const bool LOOP_POSITIONS = true;
const bool LOOP_NORMALS = true;
#else
const bool LOOP_POSITIONS = true;
const bool LOOP_NORMALS = FRAGMENT_FIELD == 0u;
#endif

// Row of lattice point (i, j) of a lattice of `seg` segments. Mirror: bft::Lattice::row.
uint bft_row(uint seg, uint i, uint j) {
    uint s = seg + 1u;
    return j * s - (j * (j > 0u ? j - 1u : 0u)) / 2u + i;
}

// Texel c (weights 4c .. 4c + 3) of a row at row-map entry `e`, of a table whose first `pe`
// columns are pairs. Mirror: bft::Packed::weight.
vec4 bft_weights(uint e, uint c, uint pe) {
    vec4 w = texelFetch(bft4, int((e >> 1u) + c));
    if ((e & 1u) != 0u) {
        uint s = 4u * c;
        w = s + 4u <= pe ? w.yxwz : (s + 2u <= pe ? w.yxzw : w);
    }
    return w;
}

// Which face evaluates sample `bary` of the face `rec`, with which weights on its corners.
// Mirror: loop_::owner.
uint loop_owner(ElementRecord rec, vec3 bary, out vec3 b) {
    uvec4 a = rec.d[0], c = rec.d[1];
    uint packed = c.w;
    b = vec3(0.0);
    uint zeros = uint(bary.x == 0.0) + uint(bary.y == 0.0) + uint(bary.z == 0.0);
    if (zeros >= 2u) {
        uint i = bary.x != 0.0 ? 0u : (bary.y != 0.0 ? 1u : 2u);
        b[(packed >> (12u + 2u * i)) & 3u] = bary[i];
        return i == 0u ? c.x : (i == 1u ? c.y : c.z);
    }
    if (zeros == 1u) {
        // Edge e joins corners e, e + 1; the third weight is the zero.
        uint e = bary.z == 0.0 ? 0u : (bary.x == 0.0 ? 1u : 2u);
        b[(packed >> (4u * e)) & 3u] = bary[e];
        b[(packed >> (4u * e + 2u)) & 3u] = bary[(e + 1u) % 3u];
        return e == 0u ? a.y : (e == 1u ? a.z : a.w);
    }
    b = bary;
    return a.x;
}

// The stored corner that is canonical corner i. Mirror: bft::Orient::stored.
uint loop_stored(uint orient, uint i) {
    uint rot = orient & 3u;
    return (orient & 4u) != 0u ? (rot + 3u - i) % 3u : (rot + i) % 3u;
}

// Where M1's normals cancel at the sample (a fold of the mesh): the normal of the control vertex
// weighing most (of those with a normal), the larger normal (x, then y, then z) on a tie; from
// the weights and normals alone, so that the two faces sharing an edge choose the same one there.
// Rows e0, e1, e2 blended by l as the sum blends them. Mirror: src/surface/loop.rs
// `heaviest_normal`.
vec3 loop_heaviest_normal(uint first, uint k4, uint pe, uint e0, uint e1, uint e2, vec3 l) {
    float best = -3.0e38;
    vec3 n = vec3(0.0, 0.0, 1.0);
    for (uint c = 0u; c < k4 / 4u; ++c) {
        uvec4 v = texelFetch(loop_control4, int(first / 4u + c));
        vec4 w = bft_weights(e0, c, pe) * l.x + bft_weights(e1, c, pe) * l.y + bft_weights(e2, c, pe) * l.z;
        for (uint e = 0u; e < 4u; ++e) {
            vec3 m = loop_n1_at(v[e]).xyz;
            bool tie = w[e] == best && (m.x != n.x ? m.x > n.x : (m.y != n.y ? m.y > n.y : m.z > n.z));
            if (m != vec3(0.0) && (w[e] > best || tie)) {
                best = w[e];
                n = m;
            }
        }
    }
    return n;
}

// Face g at weights b of its stored corners. Mirror: loop_::eval_face (and `cell`).
SurfacePoint loop_eval_face(uint g, vec3 b) {
    uvec4 f = texelFetch(loop_faces_t, int(g));
    uint base = f.x, k4 = ((f.y & 0xffffu) + 3u) & ~3u, pe = 2u * (f.y >> 16u), first = f.z, orient = f.w & 7u;
    uint seg = 1u << (f.w >> 3u);
    float s = float(seg);
    float x = b[loop_stored(orient, 1u)] * s;
    float y = b[loop_stored(orient, 2u)] * s;
    // A lattice point without displacement (which would need the tangents): one table row.
    // The general path below gives the very same bits there (weights 1, 0, 0 on the same row),
    // so the mirror, which always takes it, agrees exactly.
    if (DISPLACE == DISPLACE_NONE && x == floor(x) && y == floor(y)) {
        uint e = texelFetch(bft_rows_t, int(base + bft_row(seg, uint(x), uint(y)))).x;
        vec3 p = vec3(0.0), n = vec3(0.0);
        for (uint c = 0u; c < k4 / 4u; ++c) {
            uvec4 v = texelFetch(loop_control4, int(first / 4u + c));
            vec4 w = bft_weights(e, c, pe);
            for (uint e = 0u; e < 4u; ++e) {
                if (LOOP_POSITIONS) {
                    p += loop_p1_at(v[e]).xyz * w[e];
                }
                if (LOOP_NORMALS) {
                    n += loop_n1_at(v[e]).xyz * w[e];
                }
            }
        }
        float nl = length(n);
        vec3 normal = nl > 0.0 ? n / nl : vec3(0.0);
        if (LOOP_NORMALS && !(dot3(n, n) > FIELD_MIN2)) {
            normal = loop_heaviest_normal(first, k4, pe, e, e, e, vec3(1.0, 0.0, 0.0));
        }
        // Tangents are not used without displacement.
        return SurfacePoint(p, normal, normal, vec3(0.0), vec3(0.0), vec2(0.0), vec2(0.0), vec2(0.0));
    }
    float i0 = clamp(floor(x), 0.0, s);
    float j0 = clamp(floor(y), 0.0, s);
    float fx = x - i0;
    float fy = y - j0;
    if (i0 + j0 >= s) {
        if (i0 > 0.0) {
            i0 -= 1.0;
            fx += 1.0;
        } else {
            j0 -= 1.0;
            fy += 1.0;
        }
    }
    uint i = uint(i0), j = uint(j0);
    uint rows[3];
    vec3 l;
    bool upper = fx + fy > 1.0 && i + j + 2u <= seg;
    if (upper) {
        rows = uint[3](bft_row(seg, i + 1u, j + 1u), bft_row(seg, i, j + 1u), bft_row(seg, i + 1u, j));
        l = vec3(fx + fy - 1.0, 1.0 - fx, 1.0 - fy);
    } else {
        rows = uint[3](bft_row(seg, i, j), bft_row(seg, i + 1u, j), bft_row(seg, i, j + 1u));
        l = vec3(1.0 - fx - fy, fx, fy);
    }
    // The three rows' weights interpolated first, then one weighted sum (and two for the
    // tangents, the lattice triangle's edges, only where displacement uses them).
    vec3 p = vec3(0.0), ns = vec3(0.0), dx = vec3(0.0), dy = vec3(0.0);
    uint e0 = texelFetch(bft_rows_t, int(base + rows[0])).x, e1 = texelFetch(bft_rows_t, int(base + rows[1])).x,
         e2 = texelFetch(bft_rows_t, int(base + rows[2])).x;
    for (uint c = 0u; c < k4 / 4u; ++c) {
        uvec4 v = texelFetch(loop_control4, int(first / 4u + c));
        vec4 w0 = bft_weights(e0, c, pe), w1 = bft_weights(e1, c, pe), w2 = bft_weights(e2, c, pe);
        vec4 w = w0 * l.x + w1 * l.y + w2 * l.z;
        for (uint e = 0u; e < 4u; ++e) {
            vec3 pv = LOOP_POSITIONS ? loop_p1_at(v[e]).xyz : vec3(0.0);
            p += pv * w[e];
            if (LOOP_NORMALS) {
                ns += loop_n1_at(v[e]).xyz * w[e];
            }
            if (DISPLACE != DISPLACE_NONE) {
                dx += pv * (upper ? w0[e] - w1[e] : w1[e] - w0[e]);
                dy += pv * (upper ? w0[e] - w2[e] : w2[e] - w0[e]);
            }
        }
    }
    vec3 position = p;
    float nl = length(ns);
    vec3 normal = nl > 0.0 ? ns / nl : vec3(0.0);
    if (LOOP_NORMALS && !(dot3(ns, ns) > FIELD_MIN2)) {
        normal = loop_heaviest_normal(first, k4, pe, e0, e1, e2, l);
    }
    // Tangents per unit weight of canonical corners 1 and 2, back to the stored corners.
    dx *= s;
    dy *= s;
    vec3 canon[3] = vec3[3](vec3(0.0), dx, dy);
    vec3 grad[3];
    for (uint t = 0u; t < 3u; ++t) {
        grad[loop_stored(orient, t)] = canon[t];
    }
    return SurfacePoint(position, normal, normal, grad[1] - grad[0], grad[2] - grad[0], vec2(0.0), vec2(0.0),
                        vec2(0.0));
}

// Mirror: loop_::eval.
SurfacePoint loop_eval(ElementRecord rec, vec3 bary) {
    vec3 b;
    uint g = loop_owner(rec, bary, b);
    return loop_eval_face(g, b);
}

#endif
