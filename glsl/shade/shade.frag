#version 460
// Fragment stage shared by every driver: two-sided Blinn-Phong lighting. Where the surface has a
// normal field of its own (pn: FRAGMENT_FIELD), the normal is evaluated at this fragment's
// barycentric coordinates (the field, or with displacement the displaced normal), so highlights
// do not depend on the refinement level; otherwise the interpolated vertex normal. The WIRE variant (a second
// pass in polygon mode LINE) draws the refined triangles' edges, darker than the surface. VIEW
// (a specialization constant: each view's pipelines do its own work alone, which a software
// rasteriser would otherwise pay for per fragment behind a uniform branch): VIEW_NORMALS shows
// normals, VIEW_LEVELS the lit surface coloured by the level its element is drawn at,
// VIEW_PLAIN the surface colour alone (nothing evaluated, nothing lit, no varying read).
#define FRAGMENT_STAGE
#include "records.glsl"
#include "surface.glsl"
#include "varyings.glsl"
#include "levels.glsl"

layout(constant_id = SPEC_WIRE) const uint WIRE = 0;
layout(constant_id = SPEC_VIEW) const uint VIEW = VIEW_SHADED;

layout(location = 0) out vec4 out_color;

// A colour per level, by its power of two: blue at 1, through cyan, green, yellow, to red at
// 256 and beyond; levels between two powers of two fall between their colours.
vec3 level_color(float level) {
    const vec3 ramp[5] = vec3[5](vec3(0.20, 0.35, 0.95), vec3(0.15, 0.80, 0.85), vec3(0.30, 0.85, 0.30),
                                 vec3(0.95, 0.85, 0.20), vec3(0.95, 0.25, 0.20));
    float t = clamp(log2(max(level, 1.0)) / 2.0, 0.0, 3.999);
    return mix(ramp[int(t)], ramp[int(t) + 1], fract(t));
}

void main() {
    if (VIEW == VIEW_PLAIN) {
        out_color = vec4(frame.base_color.rgb * (WIRE != 0 ? 0.6 : 1.0), 1.0);
        return;
    }
    vec3 n;
    if (FRAGMENT_FIELD == 0) {
        n = normalize(v_normal);
    } else if (DISPLACE == DISPLACE_NONE) {
        n = surface_normal_field(fetch_record(v_element), v_bary);
    } else {
        // The displaced normal at this fragment's sample: the whole evaluation, per fragment.
        n = evaluate(fetch_record(v_element), Sample(v_element, v_bary)).normal;
    }
    if (VIEW == VIEW_NORMALS) {
        out_color = vec4((n * 0.5 + 0.5) * (WIRE != 0 ? 0.6 : 1.0), 1.0);
        return;
    }
    vec3 v = normalize(frame.eye.xyz - v_position);
    // Two-sided: a shading normal facing away from the eye is turned toward it (the inside of
    // an open surface), unless the drawn triangle itself says the normal is on the side the eye
    // sees (the triangle's normal from the position's screen derivatives, whatever the
    // winding): near a silhouette a smooth normal field may turn slightly away from the eye
    // while the triangle still faces it, and turning it there drew a dark band along the
    // outline. The derivatives alone decide nothing (across tiny or sliver triangles they are
    // noise, which would speckle faces turned toward the eye), and nothing where they are
    // degenerate: along a line of the wireframe pass, where both run along the line, the old
    // rule stands (a line on a silhouette keeps the band, in the lines' darker colour). On a
    // closed surface wound outwards (frame.light_dir.w) the rasteriser's own side of the
    // triangle decides, exactly: a front face shows the outside, whose normal is kept; a back
    // face the inside (an eye within the surface), whose normal is turned. There the
    // derivatives' sign, on a face seen nearly edge-on, flipped in a speckled pattern and lit
    // single pixels.
    vec3 dx = dFdx(v_position), dy = dFdy(v_position);
    vec3 g = cross(dx, dy);
    bool trusted = length(g) > 1.0e-3 * length(dx) * length(dy);
    bool seen_side = frame.light_dir.w > 0.5
        ? gl_FrontFacing
        : trusted && (dot(n, g) > 0.0) == (dot(g, v) > 0.0);
    if (dot(n, v) < 0.0 && !seen_side) {
        n = -n;
    }
    vec3 l = normalize(frame.light_dir.xyz);
    vec3 h = normalize(l + v);
    float diffuse = max(dot(n, l), 0.0);
    float specular = pow(max(dot(n, h), 0.0), 48.0);
    vec3 base = frame.base_color.rgb;
    if (VIEW == VIEW_LEVELS) {
        base = level_color(frame.level > 0.0 ? frame.level : fetch_levels(v_element).w);
    }
    vec3 color = base * (0.18 + 0.82 * diffuse) + vec3(0.22 * specular);
    // The refined edges: the lit colour, darkened, so the lines fade into the shading instead
    // of turning a fine mesh black (the cage overlay draws the coarse edges in a bright colour).
    out_color = vec4(WIRE != 0 ? color * 0.6 : color, 1.0);
}
