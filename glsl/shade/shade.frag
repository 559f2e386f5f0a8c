#version 460
// Fragment stage shared by every driver: two-sided Blinn-Phong lighting of the interpolated
// surface normal, with an optional wireframe of the refined triangles drawn from the lattice
// coordinate (integer along every refined edge), so all drivers show the same lines.
#define FRAGMENT_STAGE
#include "records.glsl"
#include "varyings.glsl"

layout(location = 0) out vec4 out_color;

void main() {
    vec3 n = normalize(v_normal);
    vec3 v = normalize(frame.eye.xyz - v_position);
    if (dot(n, v) < 0.0) {
        n = -n;
    }
    vec3 l = normalize(frame.light_dir.xyz);
    vec3 h = normalize(l + v);
    float diffuse = max(dot(n, l), 0.0);
    float specular = pow(max(dot(n, h), 0.0), 48.0);
    vec3 color = frame.base_color.rgb * (0.18 + 0.82 * diffuse) + vec3(0.22 * specular);
    if (frame.options.x > 0.5) {
        vec3 dist = abs(fract(v_lattice + 0.5) - 0.5);      // distance to the nearest refined edge
        vec3 px = dist / max(fwidth(v_lattice), vec3(1e-6)); // ... in pixels
        float d = min(min(px.x, px.y), px.z);
        float line = 1.0 - smoothstep(0.5 * frame.options.y - 0.5, 0.5 * frame.options.y + 0.5, d);
        color = mix(color, vec3(0.04, 0.05, 0.08), line * 0.85);
    }
    out_color = vec4(color, 1.0);
}
