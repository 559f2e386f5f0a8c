// The seam between drivers and surfaces (docs/architecture.md, "The seam"). A driver hands
// `evaluate` the element's record, unopened, and a Sample; the surface chosen by the SURFACE specialization
// constant (values: src/surface/mod.rs `Surface`) decodes the record, puts the corners in
// canonical order and evaluates; displacement (DISPLACE) follows.
// Mirror: src/surface/mod.rs `eval`.
#ifndef SURFACE_GLSL
#define SURFACE_GLSL
#include "corners.glsl"
#include "flat.glsl"
#include "phong.glsl"
#include "pn.glsl"
#include "stpn.glsl"
#include "displace.glsl"
// Whether the fragment stage evaluates the surface's normal field (pn, stpn; loop at high
// levels, whose drawing stages then sum positions only).
layout(constant_id = SPEC_FRAGMENT_FIELD) const uint FRAGMENT_FIELD = 0;
#include "loop.glsl"

layout(constant_id = SPEC_SURFACE) const uint SURFACE = 0;
const uint SURFACE_FLAT = 0;
const uint SURFACE_PHONG = 1;
const uint SURFACE_PN = 2;
const uint SURFACE_STPN = 3;
const uint SURFACE_LOOP = 4;

struct Sample {
    uint local;    // the element's index in the bound chunk of records
    vec3 bary;     // (w, u, v): weights of the element's stored corners 0, 1, 2
};

// The surface's normal field on ordered corners (t: their scalar tags, for stpn).
// Mirror: src/surface/mod.rs `normal_field`.
vec3 surface_normal(Corners c, StTag t[3]) {
    if (SURFACE == SURFACE_STPN) {
        stpn_shading_normals(c, t);
        return pn_normal(c);
    }
    return SURFACE == SURFACE_PN ? pn_normal(c) : flat_normal(c);
}

// The surface without displacement.
SurfacePoint surface_eval(ElementRecord rec, Sample s) {
    CornerRecord r = corner_record(rec);
    Corners c = SURFACE == SURFACE_FLAT ? stored_corners(r, s.bary) : canonical(r, s.bary);
    StTag tags[3];
    if (SURFACE == SURFACE_STPN) {
        stpn_corner_tags(r, c, tags);
    }
    vec3 p, n, g[3];
    if (SURFACE == SURFACE_STPN) {
        stpn_eval(c, tags, p, n, g);
    } else if (SURFACE == SURFACE_PHONG) {
        phong_eval(c, frame.params.x, p, n, g);
    } else if (SURFACE == SURFACE_PN) {
        pn_eval(c, p, n, g);
    } else {
        flat_eval(c, p, n, g);
    }
    // Back from canonical to stored corner order: dP/du = ∂P/∂b1 - ∂P/∂b0, dP/dv = ∂P/∂b2 - ∂P/∂b0.
    vec3 gs[3];
    for (int i = 0; i < 3; ++i) {
        gs[c.o[i]] = g[i];
    }
    // Displacement direction: the normal field with the geometry normals (n itself unless a
    // corner is at a split normal with closed seams).
    vec3 dir = n;
    if (c.g[0] != c.n[0] || c.g[1] != c.n[1] || c.g[2] != c.n[2]) {
        Corners cg = c;
        cg.n = c.g;
        dir = surface_normal(cg, tags);
    }
    SurfacePoint sp = SurfacePoint(p, n, dir, gs[1] - gs[0], gs[2] - gs[0], vec2(0.0), vec2(0.0), vec2(0.0));
    if (DISPLACE == DISPLACE_HEIGHTMAP) {
        // Texture coordinates in canonical order (src/surface/mod.rs `eval_surface`).
        vec2 t[3];
        fetch_uvs(s.local, t);
        precise vec2 uv = t[c.o[0]] * c.w[0] + t[c.o[1]] * c.w[1] + t[c.o[2]] * c.w[2];
        sp.uv = uv;
        sp.duv_du = t[1] - t[0];
        sp.duv_dv = t[2] - t[0];
    }
    return sp;
}

// What every driver computes for every sample.
SurfacePoint evaluate(ElementRecord rec, Sample s) {
    if (SURFACE == SURFACE_LOOP) {
        return displace(loop_eval(rec, s.bary));
    }
    return displace(surface_eval(rec, s));
}

// The surface's normal field at barycentric `bary` of the element, for the fragment stage.
vec3 surface_normal_field(ElementRecord rec, vec3 bary) {
    if (SURFACE == SURFACE_LOOP) {
        return loop_eval(rec, bary).normal;
    }
    if (SURFACE == SURFACE_PN) {
        // Shading only, per fragment: the field is symmetric in its corners, so it is taken in
        // the stored order (the canonical one makes positions bit-identical across an edge;
        // here it would only move the last bit), from the positions and normals alone (PN's
        // field needs neither the geometry normals nor the seam flags).
        Corners c;
        for (int i = 0; i < 3; ++i) {
            c.p[i] = uintBitsToFloat(rec.d[i].xyz);
            c.n[i] = uintBitsToFloat(rec.d[3 + i].xyz);
        }
        c.w = bary;
        return pn_normal(c);
    }
    CornerRecord r = corner_record(rec);
    Corners c = canonical(r, bary);
    StTag tags[3];
    if (SURFACE == SURFACE_STPN) {
        stpn_corner_tags(r, c, tags);
    }
    return surface_normal(c, tags);
}

#endif
