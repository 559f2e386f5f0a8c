#version 460
// The cage overlay's colour: a light cyan that stands out on the surface colour and on both
// backgrounds.
layout(location = 0) out vec4 out_color;

void main() {
    out_color = vec4(0.45, 0.92, 1.0, 1.0);
}
