// Displacement along the surface point's unit normal, chosen by the DISPLACE specialization
// constant (values: src/surface/displace.rs `Displace`); parameters from frame.params.
// The formulas (sine, noise, Blinn's perturbed normal) are documented in the mirror,
// src/surface/displace.rs, which follows the same operation order.
#ifndef DISPLACE_GLSL
#define DISPLACE_GLSL
#include "corners.glsl"
#include "noise.glsl"
#include "heightmap.glsl"

layout(constant_id = SPEC_DISPLACE) const uint DISPLACE = 0;
const uint DISPLACE_NONE = 0;
const uint DISPLACE_SINE = 1;
const uint DISPLACE_NOISE = 2;
const uint DISPLACE_HEIGHTMAP = 3;

struct SurfacePoint {
    vec3 position;
    vec3 normal;   // unit
    vec3 direction; // unit: what displacement moves along (src/surface/mod.rs `SurfacePoint`)
    vec3 dpdu;     // tangents for the sample (w, u, v), w = 1 - u - v
    vec3 dpdv;
    vec2 uv;       // texture coordinates (heightmap only), and their derivatives by u and v
    vec2 duv_du;
    vec2 duv_dv;
};

// Height at p and its gradient.
float displace_height(vec3 p, out vec3 grad) {
    float a = frame.params.y;
    float f = frame.params.z;
    grad = vec3(0.0);
    if (DISPLACE == DISPLACE_SINE) {
        float r = sqrt(dot3(p, p));
        precise float h = a * sin(f * r);
        if (r > 0.0) {
            grad = p * (a * f * cos(f * r) / r);
        }
        return h;
    }
    if (DISPLACE == DISPLACE_NOISE) {
        uint octaves = uint(frame.params.w);
        precise float h = 0.0;
        float scale = 1.0;
        for (uint o = 0u; o < octaves; ++o) {
            vec3 g;
            precise vec3 q = p * (f * scale);
            float n = noise_grad(q, g);
            h += n / scale;
            grad += g * f;
            scale *= 2.0;
        }
        grad = grad * a;
        precise float ah = a * h;
        return ah;
    }
    return 0.0;
}

SurfacePoint displace(SurfacePoint sp) {
    if (DISPLACE == DISPLACE_NONE) {
        return sp;
    }
    float h, hu, hv;
    if (DISPLACE == DISPLACE_HEIGHTMAP) {
        vec2 g;
        float t = heightmap_sample(sp.uv, frame.heightmap_lod, g);
        float a = frame.params.y;
        precise float ht = a * (t - frame.heightmap_bias);
        h = ht;
        hu = a * (g.x * sp.duv_du.x + g.y * sp.duv_du.y);
        hv = a * (g.x * sp.duv_dv.x + g.y * sp.duv_dv.y);
    } else {
        vec3 grad;
        h = displace_height(sp.position - frame.origin.xyz, grad);
        hu = dot3(grad, sp.dpdu);
        hv = dot3(grad, sp.dpdv);
    }
    vec3 n = sp.normal;
    vec3 cr = cross(sp.dpdu, sp.dpdv);
    float area = length(cr);
    SurfacePoint r = sp;
    r.normal = n;
    if (area > 0.0) {
        float sigma = dot3(cr, n) < 0.0 ? -1.0 : 1.0;
        vec3 bump = (cross(n, sp.dpdv) * hu - cross(n, sp.dpdu) * hv) * (sigma / area);
        r.normal = normalize(n + bump);
    }
    vec3 dir = sp.direction;
    precise vec3 pos = sp.position + dir * h;
    r.position = pos;
    r.direction = dir;
    r.dpdu = sp.dpdu + dir * hu;
    r.dpdv = sp.dpdv + dir * hv;
    return r;
}

#endif
