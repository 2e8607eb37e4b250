#version 330 core
// particle_disc.frag — disc coverage from the distance to the centre, one pixel of ramp.

// ---- inputs ----
in vec2 vLocal;        // offset from the particle (m)
flat in float vRadius; // disc radius (m)
flat in vec3 vColour;  // speed colour

// ---- uniforms ----
uniform float uPixel; // size of one target pixel (m)

// ---- outputs ----
out vec4 fragColour;

void main() {
    float coverage = clamp((vRadius - length(vLocal)) / uPixel + 0.5, 0.0, 1.0);
    if (coverage <= 0.0) {
        discard;
    }
    fragColour = vec4(vColour, coverage);
}
