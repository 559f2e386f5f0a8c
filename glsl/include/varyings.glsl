// Interface between every driver's last geometry stage and the fragment stage: the evaluated
// point and normal, and the sample itself (element and barycentric coordinates), so the fragment
// stage can evaluate a surface's normal field per fragment.
#ifndef VARYINGS_GLSL
#define VARYINGS_GLSL
#ifdef FRAGMENT_STAGE
#define VARYING in
// Multisampled, a pixel's fragment runs where it is covered (centroid), never at a pixel centre
// outside a sliver triangle that covers only some of its samples: there the interpolated sample
// (v_bary) lies outside its element, and a normal field evaluated from it (loop's tables near a
// vertex of high valence, above all) is extrapolated into speckles.
#define SMOOTH centroid in
#else
#define VARYING out
#define SMOOTH out
#endif
#ifdef XFB
// Transform-feedback variant: each output vertex is captured as (position, element, normal,
// sample), `XfbVertex` in src/render/mod.rs; the element and sample give an export its texture
// coordinates.
layout(xfb_buffer = 0, xfb_stride = 40) out;
layout(location = 0, xfb_buffer = 0, xfb_offset = 0) VARYING vec3 v_position;
layout(location = 1, xfb_buffer = 0, xfb_offset = 16) VARYING vec3 v_normal;
layout(location = 2) flat VARYING uint v_element;
layout(location = 3, xfb_buffer = 0, xfb_offset = 28) VARYING vec3 v_bary;
// The element among all elements (v_element counts within the bound chunk).
layout(location = 4, xfb_buffer = 0, xfb_offset = 12) flat VARYING uint v_xfb_element;
#else
layout(location = 0) SMOOTH vec3 v_position;  // world position
layout(location = 1) SMOOTH vec3 v_normal;    // world normal (unnormalized after interpolation)
layout(location = 2) flat VARYING uint v_element; // the element sampled, within the bound chunk
layout(location = 3) SMOOTH vec3 v_bary;         // the sample's (w, u, v) in that element
#endif
#endif
