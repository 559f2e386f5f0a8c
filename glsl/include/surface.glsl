// The one entry point every driver's evaluation stage calls: canonical corner order, then the
// surface chosen by the SURFACE specialization constant (values: src/surface/mod.rs `Surface`).
// Mirror: src/surface/mod.rs `eval`.
#ifndef SURFACE_GLSL
#define SURFACE_GLSL
#include "bary.glsl"
#include "flat.glsl"

layout(constant_id = SPEC_SURFACE) const uint SURFACE = 0;
const uint SURFACE_FLAT = 0;

void surface_eval(CoarseTri t, vec3 bary, out vec3 position, out vec3 normal) {
    Corners c = canonical(t, bary);
    // Later surfaces (phong, pn, stpn, loop) add a branch here; the constant folds it away.
    flat_eval(c, position, normal);
}

#endif
