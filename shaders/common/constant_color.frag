#version 450 core
// Writes one colour everywhere: clears, masks and tests.

layout(location = 0) out vec4 fragColor;

uniform vec4 uColor;

void main() {
    fragColor = uColor;
}
