// Interface between every driver's last geometry stage and the fragment stage: the evaluated
// point and normal, and the sample itself (element and barycentric coordinates), so the fragment
// stage can evaluate a surface's normal field per fragment.
#ifndef VARYINGS_GLSL
#define VARYINGS_GLSL
#ifdef FRAGMENT_STAGE
#define VARYING in
#else
#define VARYING out
#endif
#ifdef XFB
// Transform-feedback variant: each output vertex is captured as (position, pad, normal, pad).
layout(xfb_buffer = 0, xfb_stride = 32) out;
layout(location = 0, xfb_buffer = 0, xfb_offset = 0) VARYING vec3 v_position;
layout(location = 1, xfb_buffer = 0, xfb_offset = 16) VARYING vec3 v_normal;
#else
layout(location = 0) VARYING vec3 v_position;  // world position
layout(location = 1) VARYING vec3 v_normal;    // world normal (unnormalized after interpolation)
#endif
layout(location = 2) flat VARYING uint v_element; // the element sampled, within the bound chunk
layout(location = 3) VARYING vec3 v_bary;         // the sample's (w, u, v) in that element
#endif
