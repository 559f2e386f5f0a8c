#version 460
// M1's vertex normals from their one-rings (Holländer & Boubekeur 2010: the one-ring indices,
// counter-clockwise, with a boundary flag): the normalized sum of the cross products of
// consecutive ring edges, the normals subdivision shading starts from. Runs after loop_step.comp.
// Mirror: src/subdiv/data.rs `LoopData::m1_normals`.
layout(local_size_x = 64) in;

// Vertex i's ring is rings[ring_offsets[i] .. ring_offsets[i + 1]) (bit 31 of the first: on
// the boundary, the ring then runs from one boundary neighbour to the other).
layout(set = 0, binding = LOOP_BINDING_RING_OFFSETS, std430) readonly buffer RingOffsets { uint ring_offsets[]; };
layout(set = 0, binding = LOOP_BINDING_RINGS, std430) readonly buffer Rings { uint rings[]; };
layout(set = 0, binding = LOOP_BINDING_M1, std430) readonly buffer M1 { vec4 m1[]; };
layout(set = 0, binding = LOOP_BINDING_N1, std430) writeonly buffer N1 { vec4 n1[]; };

layout(push_constant, std430) uniform Push {
    uint count; // M1 vertices
} pc;

const uint RING_BOUNDARY = 0x80000000u;

void main() {
    // A grid of rows of workgroups (a row may hold at most maxComputeWorkGroupCount[0]).
    uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
    if (i >= pc.count) {
        return;
    }
    uint start = ring_offsets[i] & ~RING_BOUNDARY;
    uint end = ring_offsets[i + 1u] & ~RING_BOUNDARY;
    bool boundary = (ring_offsets[i] & RING_BOUNDARY) != 0u;
    uint n = end - start;
    uint pairs = boundary ? max(n, 1u) - 1u : n;
    vec3 c = m1[i].xyz;
    vec3 s = vec3(0.0);
    for (uint k = 0u; k < pairs; ++k) {
        vec3 a = m1[rings[start + k]].xyz - c;
        vec3 b = m1[rings[start + (k + 1u) % n]].xyz - c;
        s += cross(a, b);
    }
    float l = length(s);
    n1[i] = vec4(l > 0.0 ? s / l : vec3(0.0), 0.0);
}
