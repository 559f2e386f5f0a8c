#version 460
// The adaptive pattern driver's draws, from the elements' levels, without a readback
// (src/render/pattern/bins.rs `AdaptivePattern`): per element one VkDrawIndexedIndirectCommand (its
// inner level's index range; zero indices when culled) for the `push` and `ubo` submissions, and
// per chunk and level one bin (`instanced`): the command, its instance count, and the list of its
// elements in element order, read by the vertex stage as an instance-rate attribute. The order
// is the elements' own whatever the scheduling, so the draws are the same every frame (where
// the surface folds onto itself, drawn triangles tie in depth and the last drawn wins).
// Phases, a barrier after each: 0 the bins' commands with no instances; 1 each element's
// command; 2 per block of 64 elements of a chunk, each element's rank among the block's at its
// level and the block's count per level; 3 per bin, the blocks' counts turned into their
// offsets (an exclusive sum in block order) and the bin's instance count; 4 each element into
// its bin's list at its block's offset plus its rank.
layout(local_size_x = 64) in;

// This pass's own set: the mesh's whole levels buffer, the commands, the bins' element lists.
#undef SET_MESH
#define SET_MESH 0
#undef BINDING_LEVELS
#define BINDING_LEVELS 0
#define LEVELS_STORAGE
#include "levels.glsl"
#include "adaptive.glsl"

layout(set = 0, binding = 1, std430) buffer Commands {
    uint commands[]; // n elements' commands, then chunks x (L + 1) bins', 5 words each
};
layout(set = 0, binding = 2, std430) writeonly buffer Lists {
    uint lists[]; // level l, chunk c: from l n + c chunk
};
layout(set = 0, binding = 3, std430) buffer Ranks {
    uint ranks[]; // each element's rank among its block's at its level
};
layout(set = 0, binding = 4, std430) buffer Blocks {
    uint blocks[]; // block b of chunk c, level l: at (c blocks_per_chunk + b) levels + l
};

layout(push_constant, std430) uniform Push {
    uint phase;
    uint first;  // first bin (phases 0, 3), element (1, 4) or block (2) of this dispatch
    uint end;    // one past the last
    uint f;      // the largest level, 2^L
    uint n;      // elements in the mesh
    uint chunk;  // elements per chunk
    uint dyadic; // 1: the hierarchical patterns (levels 2^l, l = 0..L); 0: the integer
                 // patterns (levels 1..f, src/pattern/adaptive.rs `IntegerPatterns`)
    uint lo;     // the elements drawn: lo..hi
    uint hi;
    uint blocks_per_chunk;
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

// The bin of element k when drawn (its inner level's), or -1: culled or outside the range.
int drawn_bin(uint k) {
    if (k < pc.lo || k >= pc.hi) {
        return -1;
    }
    uint inner = adaptive_levels(fetch_levels(k), pc.f, pc.dyadic != 0u).w;
    return inner == 0u ? -1 : int(bin_of(inner));
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
    if (pc.phase == 1u) {
        uint inner = adaptive_levels(fetch_levels(k), pc.f, dyadic).w;
        uint o = 5u * k;
        // A culled element: level 1's range with no indices.
        write_command(o, max(inner, 1u));
        commands[o] = 3u * inner * inner;
        commands[o + 1u] = 1u;
        return;
    }
    if (pc.phase == 2u) {
        // Block k: its elements in order, each ranked among those before it at its level.
        uint c = k / pc.blocks_per_chunk, b = k % pc.blocks_per_chunk;
        uint base = k * levels;
        for (uint l = 0u; l < levels; ++l) {
            blocks[base + l] = 0u;
        }
        uint first = c * pc.chunk + 64u * b;
        uint last = min(min(first + 64u, (c + 1u) * pc.chunk), pc.n);
        for (uint e = first; e < last; ++e) {
            int l = drawn_bin(e);
            if (l >= 0) {
                ranks[e] = blocks[base + uint(l)];
                blocks[base + uint(l)] += 1u;
            }
        }
        return;
    }
    if (pc.phase == 3u) {
        // Bin k (chunk c, level l): its blocks' offsets, in block order, and its count.
        uint c = k / levels, l = k % levels;
        uint sum = 0u;
        for (uint b = 0u; b < pc.blocks_per_chunk; ++b) {
            uint at = (c * pc.blocks_per_chunk + b) * levels + l;
            uint count = blocks[at];
            blocks[at] = sum;
            sum += count;
        }
        commands[5u * (pc.n + k) + 1u] = sum;
        return;
    }
    int l = drawn_bin(k);
    if (l >= 0) {
        uint c = k / pc.chunk;
        uint b = (k - c * pc.chunk) / 64u;
        uint slot = blocks[(c * pc.blocks_per_chunk + b) * levels + uint(l)] + ranks[k];
        lists[uint(l) * pc.n + c * pc.chunk + slot] = k;
    }
}
