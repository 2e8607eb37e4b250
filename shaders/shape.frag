#version 330 core
// shape.frag — flat colour; the renderer blends it over the target with straight alpha.

// ---- inputs ----
in vec4 vColour;

// ---- outputs ----
out vec4 fragColour;

void main() {
    fragColour = vColour;
}
