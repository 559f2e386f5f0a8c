#version 460
// `tess` driver, vertex stage: nothing to do. Each coarse triangle is a 3-vertex patch drawn
// without vertex buffers; the evaluation stage reads the triangle's record itself.
void main() {}
