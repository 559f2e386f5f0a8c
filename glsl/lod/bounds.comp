#version 460
// Element and edge bounds of the local surfaces, one invocation per element: the first half of
// an adaptive level pass. Each element writes four bounds (itself, then its stored edges 0, 1,
// 2), three vec4 each: (c1, c2, cubic, 0) of its chord bound and cubic term, its sphere (centre, radius) and its
// normal cone (axis, cosine of the half-angle; zero for none and for edges). The
// surface, displacement and pn's normal field are pc.draw.x, pc.draw.y and pc.draw.z (0 flat,
// 1 phong, 2 pn; 0 none, 1 sine, 2 noise; NORMAL_FIELD_*), the parameters frame.params and
// frame.origin.
// Mirror: src/lod/bound.rs `Lod::element`, `Lod::edge` (glsl/include/lod.glsl); tests/lod_mirror.rs
// compares the two.
layout(local_size_x = 64) in;

#include "lod.glsl"

// The records, a storage buffer in this pass's set (tests/lod_mirror.rs binds it).
layout(set = SET_MESH, binding = BINDING_ELEMENTS, std430) readonly buffer Records {
    ElementRecord records[];
};

layout(set = SET_LOD, binding = BINDING_LOD_BOUNDS, std430) writeonly buffer Bounds {
    vec4 bounds[];
};

void put(uint slot, LodBounds b) {
    bounds[3u * slot] = vec4(b.chord, b.cubic, 0.0);
    bounds[3u * slot + 1u] = b.sphere;
    bounds[3u * slot + 2u] = b.cone;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(records.length())) {
        return;
    }
    CornerRecord r = corner_record(records[i]);
    vec3 origin = frame.origin.xyz;
    uint surface = pc.draw.x, displace = pc.draw.y, field = pc.draw.z;
    put(4u * i, lod_element(surface, field, displace, frame.params, origin, r));
    for (int e = 0; e < 3; ++e) {
        put(4u * i + 1u + uint(e), lod_edge(surface, field, displace, frame.params, origin, r, e));
    }
}
