// The adaptive pattern driver's levels and snapping, shared by its vertex stage
// (glsl/pattern/adaptive.vert) and its bins pass (glsl/pattern/bins.comp). Mirror:
// src/pattern/adaptive.rs. Needs drawn_level (glsl/include/levels.glsl).
#ifndef PATTERN_ADAPTIVE_GLSL
#define PATTERN_ADAPTIVE_GLSL

// The levels an element is drawn with at largest level f (a power of two): its three edges'
// and its inner level, powers of two where dyadic (the hierarchical patterns) else integers
// (the integer patterns); the inner level at least every edge's, an edge's at least 1.
// inner 0: culled. Mirror: adaptive::drawn_levels.
uvec4 adaptive_levels(vec4 levels, uint f, bool dyadic) {
    uint inner = drawn_level(levels.w, dyadic, f);
    if (inner == 0u) {
        return uvec4(0u);
    }
    uvec3 e = max(uvec3(drawn_level(levels.x, dyadic, f), drawn_level(levels.y, dyadic, f),
                        drawn_level(levels.z, dyadic, f)),
                  uvec3(1u));
    return uvec4(e, max(inner, max(e.x, max(e.y, e.z))));
}

// The sample of an edge drawn at level m that lattice parameter a/n (m <= n) snaps to, as
// snap_edge does for any integer levels: its index s, the sample being s/m. Mirror:
// adaptive::snap_sample.
uint snap_sample(uint a, uint m, uint n) {
    uint down = 2u * a <= n ? 1u : 0u;
    return (2u * a * m + n - down) / (2u * n);
}

// The weights the integer patterns draw lattice point ij of inner level n.w at: on stored
// edge k (edge 0: j = 0, from corner 0; edge 1: i + j = n, from corner 1; edge 2: i = 0, from
// corner 2) the sample s of the edge's level m it snaps to, (m - s)/m and s/m for corners k
// and k + 1, divided as written (both elements sharing the edge divide the same integers;
// the corners exactly 1 and 0);
// inside, the pattern's own weights `inside`. Mirror: adaptive::integer_bary.
vec3 integer_weights(uvec2 ij, uvec4 n, vec3 inside) {
    uint k, a;
    if (ij.y == 0u) {
        k = 0u;
        a = ij.x;
    } else if (ij.x + ij.y == n.w) {
        k = 1u;
        a = ij.y;
    } else if (ij.x == 0u) {
        k = 2u;
        a = n.w - ij.y;
    } else {
        return inside;
    }
    uint m = n[k];
    uint s = snap_sample(a, m, n.w);
    vec3 b = vec3(0.0);
    // The corners exactly (a device may divide m by m inexactly, and a corner's edges have
    // different levels in different elements).
    b[k] = s == 0u ? 1.0 : (s == m ? 0.0 : float(m - s) / float(m));
    b[(k + 1u) % 3u] = s == 0u ? 0.0 : (s == m ? 1.0 : float(s) / float(m));
    return b;
}

// Parameter a (units of 1/f) along an edge drawn at level n, snapped onto the edge's samples
// (multiples of f/n): the nearest, a tie toward the nearer corner (to the smaller at the
// middle), so that a point beside a corner (but the middle) snaps onto it. Mirror:
// adaptive::snap_edge.
uint snap_edge(uint a, uint n, uint f) {
    uint r = f / n;
    uint up = 2u * a > f ? r : r - 1u;
    return (2u * a + up) / (2u * r) * r;
}

// Lattice point (i, j) of level f moved onto its edge's samples where it lies on a stored edge
// (edge 0: j = 0, from corner 0; edge 1: i + j = f, from corner 1; edge 2: i = 0, from corner 2).
// Mirror: adaptive::snap.
uvec2 adaptive_snap(uvec2 ij, uvec4 n, uint f) {
    if (ij.y == 0u) {
        return uvec2(snap_edge(ij.x, n.x, f), 0u);
    }
    if (ij.x + ij.y == f) {
        uint j = snap_edge(ij.y, n.y, f);
        return uvec2(f - j, j);
    }
    if (ij.x == 0u) {
        return uvec2(0u, f - snap_edge(f - ij.y, n.z, f));
    }
    return ij;
}

// Geomorphing (docs/adaptivity.md, "Geomorphing"). The morph factor of a vertex that drawn
// level n adds to level n / 2, for continuous level lambda. Mirror: adaptive::morph_factor.
float morph_factor(float lambda, uint n) {
    if (n <= 1u) {
        return 1.0;
    }
    float x = float(n) / lambda;
    return clamp((4.0 - x * x) / 3.0, 0.0, 1.0);
}

// Between the parents' midpoint (m = 0) and the true position p (m = 1, exactly p); precise, so
// that every element computes an edge vertex with the same operations. Mirror: adaptive::morph.
vec3 morph(vec3 pa, vec3 pb, vec3 p, float m) {
    if (m >= 1.0) {
        return p;
    }
    precise vec3 mid = (pa + pb) * 0.5;
    precise vec3 r = mid + (p - mid) * m;
    return r;
}

// Whether lattice point ij is new at the level of step s. Mirror: adaptive::is_new.
bool morph_is_new(uvec2 ij, uint s) {
    return ((ij.x / s) & 1u) != 0u || ((ij.y / s) & 1u) != 0u;
}

// The two points of the level of step 2s whose midpoint is ij. Mirror: adaptive::parents.
void morph_parents(uvec2 ij, uint s, out uvec2 a, out uvec2 b) {
    bool oi = ((ij.x / s) & 1u) != 0u;
    bool oj = ((ij.y / s) & 1u) != 0u;
    if (oi && !oj) {
        a = uvec2(ij.x - s, ij.y);
        b = uvec2(ij.x + s, ij.y);
    } else if (oj && !oi) {
        a = uvec2(ij.x, ij.y - s);
        b = uvec2(ij.x, ij.y + s);
    } else {
        a = uvec2(ij.x - s, ij.y + s);
        b = uvec2(ij.x + s, ij.y - s);
    }
}

// The stored edge lattice point ij lies on, as adaptive_snap classifies it; -1 inside.
// Mirror: adaptive::edge_of.
int morph_edge(uvec2 ij, uint f) {
    if (ij.y == 0u) {
        return 0;
    }
    if (ij.x + ij.y == f) {
        return 1;
    }
    if (ij.x == 0u) {
        return 2;
    }
    return -1;
}

#endif
