// Interface between every driver's last geometry stage and the fragment stage.
#ifndef VARYINGS_GLSL
#define VARYINGS_GLSL
#ifdef FRAGMENT_STAGE
#define VARYING in
#else
#define VARYING out
#endif
layout(location = 0) VARYING vec3 v_position;  // world position
layout(location = 1) VARYING vec3 v_normal;    // world normal (unnormalized after interpolation)
#endif
