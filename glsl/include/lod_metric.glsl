// The screen-space metric and the culling tests of src/lod (mod.rs, cull.rs), function for
// function, without any binding: included by lod.glsl (the bounds' twin) and by the level pass
// (glsl/lod/levels.comp).
#ifndef LOD_METRIC_GLSL
#define LOD_METRIC_GLSL

const float LOD_ELEMENT_FACTOR = 9.0 / 40.0;
// A polynomial patch's quadratic and cubic factors, and the tessellator's cubic term against
// the lattice's, (4/3)^3. Mirror: src/lod/mod.rs `QUADRATIC_FACTOR`, `CUBIC_FACTOR`,
// `TESS_CUBIC`.
const float LOD_QUADRATIC_FACTOR = 1.0 / 6.0;
const float LOD_CUBIC_FACTOR = 4.0 / 81.0;
const float LOD_TESS_CUBIC = 64.0 / 27.0;
// The quadratic factor over the general one, (1/6) / (9/40). Mirror: `POLYNOMIAL_SHARE`.
const float LOD_POLYNOMIAL_SHARE = 20.0 / 27.0;
// The tessellator's ring diagonals, (2/3)^2. Mirror: src/lod/mod.rs `RING_DIAGONAL`.
const float LOD_RING_DIAGONAL = 4.0 / 9.0;

// "No finite bound": src/lod uses infinity; shader compilers may assume there are no
// infinities, so the mirror uses the largest float it keeps finite instead.
const float LOD_HUGE = 3.0e38;

// ---- The metric (src/lod/mod.rs) ----

// A chord bound (c1, c2): within c1/N + c2/N^2 at N segments per edge. Mirror: `Chord::error`.
float lod_chord_error(vec2 chord, float n) {
    float x = 1.0 / n;
    return (chord.x + chord.y * x) * x;
}

// Level 1 without solving where its bound is this far below the tolerance (before the solver's
// c2 * tol can overflow). Mirror: `LEVEL_ONE_MARGIN`.
const float LOD_LEVEL_ONE_MARGIN = 1.0001;

// The smallest real N >= 1 with error(N) <= tol, uncapped. Mirror: `Chord::level_for`.
float lod_level_for(vec2 chord, float tol) {
    if (chord.x == 0.0 && chord.y == 0.0) {
        return 1.0;
    }
    if ((chord.x + chord.y) * LOD_LEVEL_ONE_MARGIN <= tol) {
        return 1.0;
    }
    float root = (chord.x + sqrt(chord.x * chord.x + 4.0 * chord.y * tol)) / (2.0 * tol);
    return max(root * (1.0 + 1.0 / 65536.0), 1.0);
}

// The camera as the metric sees it. Mirror: `View`.
struct LodView {
    vec3 eye;
    float k;           // H / (2 tan(fov_y / 2))
    float pixel_error; // pixels
    float max_level;   // segments per edge
};

// World distance allowed inside sphere s (xyz centre, w radius). Mirror: `View::tolerance`.
float lod_tolerance(LodView v, vec4 s) {
    float dist = length(s.xyz - v.eye) - s.w;
    return v.pixel_error * max(dist, 0.0) / v.k;
}

// lod_level at tolerance tol (a sphere's, computed once for the levels it gives). Mirror:
// src/lod/frame.rs `level_at`.
float lod_level_at(LodView v, vec2 chord, float tol) {
    if (tol > 0.0 && max(chord.x, chord.y) < LOD_HUGE) {
        return min(lod_level_for(chord, tol), v.max_level);
    }
    return (chord.x == 0.0 && chord.y == 0.0) ? 1.0 : v.max_level;
}

// The continuous level in [1, max_level]; its ceiling is the integer level. Mirror: `View::level`.
float lod_level(LodView v, vec2 chord, vec4 s) {
    return lod_level_at(v, chord, lod_tolerance(v, s));
}

// ---- Culling (src/lod/cull.rs) ----

// The six planes of a view-projection (Vulkan clip space). Mirror: `Frustum::from_view_proj`.
void lod_frustum(mat4 m, out vec4 planes[6]) {
    vec4 r0 = vec4(m[0][0], m[1][0], m[2][0], m[3][0]);
    vec4 r1 = vec4(m[0][1], m[1][1], m[2][1], m[3][1]);
    vec4 r2 = vec4(m[0][2], m[1][2], m[2][2], m[3][2]);
    vec4 r3 = vec4(m[0][3], m[1][3], m[2][3], m[3][3]);
    planes[0] = r3 + r0;
    planes[1] = r3 - r0;
    planes[2] = r3 + r1;
    planes[3] = r3 - r1;
    planes[4] = r2;
    planes[5] = r3 - r2;
    for (int i = 0; i < 6; ++i) {
        planes[i] /= length(planes[i].xyz);
    }
}

// Whether sphere s lies wholly outside one plane. Mirror: `Frustum::outside`.
bool lod_outside(vec4 planes[6], vec4 s) {
    bool out_ = false;
    for (int i = 0; i < 6; ++i) {
        out_ = out_ || dot(planes[i].xyz, s.xyz) + planes[i].w < -s.w;
    }
    return out_;
}

// Whether every triangle drawn inside sphere s with a normal in cone (xyz axis, w cosine of
// the half-angle; w <= 0: no cone) faces away from eye: the angles β (eye to axis), γ (the
// sphere's angular radius) and θ (the cone's) sum to below 90° less 1e-4, written with cosines
// and sines (a GPU's acos is not accurate enough to agree with the CPU). Mirror:
// `NormalCone::back_facing`.
const float LOD_BACK_FACING_MARGIN = 1e-4;

bool lod_back_facing(vec4 cone, vec4 s, vec3 eye) {
    vec3 v = s.xyz - eye;
    float d = length(v);
    if (cone.w <= 0.0 || d <= s.w) {
        return false;
    }
    float cb = clamp(dot(v, cone.xyz) / d, -1.0, 1.0);
    float sg = s.w / d;
    float ct = clamp(cone.w, -1.0, 1.0);
    float sb = sqrt(max(1.0 - cb * cb, 0.0));
    float cg = sqrt(max(1.0 - sg * sg, 0.0));
    float st = sqrt(max(1.0 - ct * ct, 0.0));
    float cp = cg * ct - sg * st;
    float sp = sg * ct + cg * st;
    return cb > 0.0 && cp > 0.0 && cb * cp - sb * sp > LOD_BACK_FACING_MARGIN;
}

#endif
