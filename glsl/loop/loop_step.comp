#version 460
// One Loop step M0 -> M1 on the GPU (Holländer & Boubekeur 2010, "computational entries"): every
// M1 vertex is a weighted sum of M0 vertices, with parents and weights built once per topology on
// the CPU (src/subdiv `stencils`, the mirror) and M0's positions uploaded every frame.
layout(local_size_x = 64) in;

// M1 vertex i sums entries[offsets[i] .. offsets[i + 1]): (parent, weight bits).
layout(set = 0, binding = LOOP_BINDING_OFFSETS, std430) readonly buffer Offsets { uint offsets[]; };
layout(set = 0, binding = LOOP_BINDING_ENTRIES, std430) readonly buffer Entries { uvec2 entries[]; };
layout(set = 0, binding = LOOP_BINDING_M0, std430) readonly buffer M0 { vec4 m0[]; };
layout(set = 0, binding = LOOP_BINDING_M1, std430) writeonly buffer M1 { vec4 m1[]; };

layout(push_constant, std430) uniform Push {
    uint count; // M1 vertices
} pc;

void main() {
    // A grid of rows of workgroups (a row may hold at most maxComputeWorkGroupCount[0]).
    uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
    if (i >= pc.count) {
        return;
    }
    vec3 p = vec3(0.0);
    for (uint k = offsets[i]; k < offsets[i + 1u]; ++k) {
        uvec2 e = entries[k];
        p += m0[e.x].xyz * uintBitsToFloat(e.y);
    }
    m1[i] = vec4(p, 1.0);
}
