#version 450 core
// Depth-only fragment stage of the shadow casters (terrain): the shadow map keeps the
// rasterised depth; nothing else is written.
void main() {}
