#version 330 core
// pressure_square.frag — red with the pressure's opacity (straight alpha).

// ---- inputs ----
flat in float vAlpha;

// ---- outputs ----
out vec4 fragColour;

void main() {
    fragColour = vec4(0.95, 0.08, 0.06, vAlpha);
}
