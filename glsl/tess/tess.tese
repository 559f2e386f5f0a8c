#version 460
// `tess` driver, evaluation stage: evaluates the surface at gl_TessCoord. With equal spacing and
// an integer level N every tessellated vertex lies on the pattern lattice, so the coordinate is
// snapped to its lattice point (i, j) and the weights are made from integers, as the pattern's are:
// exact zeros on edges, identical weights on both sides of a shared edge (watertight).
// gl_PrimitiveID restarts in every draw; pc.draw.y is this draw's first triangle.
#include "records.glsl"
#include "surface.glsl"
#include "varyings.glsl"

layout(triangles, equal_spacing, ccw) in;

layout(set = SET_MESH, binding = BINDING_TRIS, std430) readonly buffer Tris { CoarseTri tris[]; };

void main() {
    uint n = pc.draw.x;
    CoarseTri t = tris[pc.draw.y + uint(gl_PrimitiveID)];
    // gl_TessCoord (x, y, z) weighs patch vertices (0, 1, 2), i.e. (w, u, v).
    uint i = uint(round(gl_TessCoord.y * float(n)));
    uint j = uint(round(gl_TessCoord.z * float(n)));
    vec3 bary = vec3(float(n - i - j), float(i), float(j)) / float(n);
    vec3 p, nrm;
    surface_eval(t, bary, p, nrm);
    v_position = p;
    v_normal = nrm;
    v_lattice = vec3(float(n - i - j), float(i), float(j));
    gl_Position = frame.view_proj * vec4(p, 1.0);
#ifdef CAPTURE
    // Same numbering as the pattern: row j, then i (src/pattern `lattice_index`).
    uint local = j * (n + 1u) - (j * (j > 0u ? j - 1u : 0u)) / 2u + i;
    captured[t.idx.w * pc.draw.z + local] = CapturedVertex(vec4(p, 1.0), vec4(nrm, 0.0));
#endif
}
