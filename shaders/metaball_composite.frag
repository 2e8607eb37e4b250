#version 330 core
// metaball_composite.frag — the liquid surface from the summed field: coverage where the
// field crosses the threshold (anti-aliased over one pixel), the materials' weighted colour, a
// lighter rim band just inside the surface and a faint highlight on the side facing the light.
// The pressure view uses it with uDark = 1: black liquid with a thin grey rim.

// ---- inputs ----
in vec2 vUv; // texture coordinate of the target

// ---- uniforms ----
uniform sampler2D uField;     // rgb = sum of colour x w, a = largest single w (bilinear)
uniform sampler2D uWeight;    // r = sum of w: the field (bilinear)
uniform float uDropletLevel;  // scale of the largest single w (lone droplets stay visible)
uniform float uKernelWeight;  // one particle's weight in the sum (sum / max w for a lone one)
uniform float uThreshold; // field level at the surface (1)
uniform float uRimWidth;  // width of the rim band inside the surface (px of the target)
uniform int uDark;        // 1: pressure view (black liquid, grey rim)

// ---- outputs ----
out vec4 fragColour; // straight alpha, blended over the background

void main() {
    vec4 field = texture(uField, vUv);
    float sum = texture(uWeight, vUv).r;
    // A lone particle's sum peaks below the threshold: where a single kernel makes up nearly
    // all of the sum (isolated droplets, chains), the largest kernel, scaled, stands in. Rows
    // along the liquid's edge have neighbours (ratio ~1.9) and keep the smooth sum.
    float ratio = sum / max(field.a * uKernelWeight, 1e-6);
    float isolated = 1.0 - smoothstep(1.2, 1.5, ratio);
    float a = max(sum, uDropletLevel * field.a * isolated);
    // Derivatives first: they must be taken before any fragment of the quad discards.
    vec2 gradient = vec2(dFdx(a), dFdy(a)); // field change per target pixel
    float slope = length(gradient);
    float edge = 0.7 * (abs(gradient.x) + abs(gradient.y)) + 1e-4;
    float coverage = smoothstep(uThreshold - edge, uThreshold + edge, a);
    if (coverage <= 0.0) {
        discard;
    }
    // Distance inside the surface (px), from the field's first-order expansion.
    float depth = (a - uThreshold) / max(slope, 1e-5);
    float rim = 1.0 - smoothstep(0.0, uRimWidth, depth);
    // Outward normal in the target's plane (the field grows inwards); light from the upper left.
    vec2 normal = -gradient / max(slope, 1e-5);
    float facing = max(dot(normal, vec2(-0.6, 0.8)), 0.0);

    vec3 colour;
    if (uDark == 1) {
        colour = vec3(0.42) * rim;
    } else {
        // The w-weighted mix of the materials' colours.
        vec3 base = field.rgb / max(sum, 1e-6);
        // Rim: lighter towards white, most on the lit side.
        vec3 light = mix(base, vec3(1.0), 0.45);
        colour = mix(base, light, rim * (0.45 + 0.55 * facing));
        // Faint highlight: a soft glow further in on the lit side, fading out by 6 rim widths.
        float glow = smoothstep(uRimWidth, 2.5 * uRimWidth, depth) *
                     (1.0 - smoothstep(3.0 * uRimWidth, 6.0 * uRimWidth, depth));
        colour += vec3(0.12) * (facing * facing * glow);
    }
    fragColour = vec4(colour, coverage);
}
