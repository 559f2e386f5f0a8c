#version 460
// The adaptive pattern driver's draws, from the elements' levels, without a readback
// (src/render/pattern/bins.rs `AdaptivePattern`): per element one VkDrawIndexedIndirectCommand (its
// inner level's index range; zero indices when culled) for the `push` and `ubo` submissions, and
// per chunk and level one bin (`instanced`): the command, its instance count by atomics, and the
// list of its elements, read by the vertex stage as an instance-rate attribute.
// Phase 0 writes the bins' commands with no instances; phase 1 (after a barrier) bins elements.
layout(local_size_x = 64) in;

// This pass's own set: the mesh's whole levels buffer, the commands, the bins' element lists.
#undef SET_MESH
#define SET_MESH 0
#undef BINDING_LEVELS
#define BINDING_LEVELS 0
#include "levels.glsl"
#include "adaptive.glsl"

layout(set = 0, binding = 1, std430) buffer Commands {
    uint commands[]; // n elements' commands, then chunks x (L + 1) bins', 5 words each
};
layout(set = 0, binding = 2, std430) writeonly buffer Lists {
    uint lists[]; // level l, chunk c: from l n + c chunk
};

layout(push_constant, std430) uniform Push {
    uint phase;
    uint first;  // first element (phase 1) or bin (phase 0) of this dispatch
    uint end;    // one past the last
    uint f;      // the largest level, 2^L
    uint n;      // elements in the mesh
    uint chunk;  // elements per chunk
    uint dyadic; // 1: the hierarchical patterns (levels 2^l, l = 0..L); 0: the integer
                 // patterns (levels 1..f, src/pattern/adaptive.rs `IntegerPatterns`)
} pc;

// Level n's command, instance count 0: its index range (and, integer, its vertex offset).
void write_command(uint o, uint n) {
    bool dyadic = pc.dyadic != 0u;
    uint l = dyadic ? uint(findMSB(n)) : 0u;
    commands[o] = 3u * n * n;
    commands[o + 1u] = 0u;
    commands[o + 2u] = dyadic ? (1u << (2u * l)) - 1u : (n - 1u) * n * (2u * n - 1u) / 2u;
    commands[o + 3u] = dyadic ? 0u : n * (n + 1u) * (n + 2u) / 6u - 1u;
    commands[o + 4u] = 0u;
}

// The bin of level n (n >= 1).
uint bin_of(uint n) {
    return pc.dyadic != 0u ? uint(findMSB(n)) : n - 1u;
}

void main() {
    uint k = pc.first + gl_GlobalInvocationID.x;
    if (k >= pc.end) {
        return;
    }
    bool dyadic = pc.dyadic != 0u;
    uint levels = dyadic ? uint(findMSB(pc.f)) + 1u : pc.f;
    if (pc.phase == 0u) {
        uint l = k % levels;
        write_command(5u * (pc.n + k), dyadic ? 1u << l : l + 1u);
        return;
    }
    uint inner = adaptive_levels(element_levels[k], pc.f, dyadic).w;
    uint o = 5u * k;
    // A culled element: level 1's range with no indices.
    write_command(o, max(inner, 1u));
    commands[o] = 3u * inner * inner;
    commands[o + 1u] = 1u;
    if (inner != 0u) {
        uint l = bin_of(inner);
        uint c = k / pc.chunk;
        uint slot = atomicAdd(commands[5u * (pc.n + c * levels + l) + 1u], 1u);
        lists[l * pc.n + c * pc.chunk + slot] = k;
    }
}
