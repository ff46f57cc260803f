#version 450 core
// Depth-only pass of buildings and models (shadow maps): no colour output.
void main() {}
