#version 330 core
// metaball_composite.frag — the liquid surface from the summed field: coverage where the
// field crosses the threshold (anti-aliased over one pixel), the materials' colours with a
// clean edge between materials 0 and 1, a lighter rim band just inside the surface and a faint
// highlight on the side facing the light.
// The pressure view uses it with uDark = 1: black liquid with a thin grey rim.
// Next to solids (opaque shapes) the surface level goes down to uSolidThreshold: particles rest
// up to about a spacing from a wall or a body, and the liquid must still touch it. The rim
// fades out there, so a wall does not get a light halo.

// ---- inputs ----
in vec2 vUv; // texture coordinate of the target

// ---- uniforms ----
uniform sampler2D uField;     // rgb = sum of colour x w, a = largest single w (bilinear)
uniform sampler2D uWeight;    // r = sum of w: the field; g, b = its parts from materials 0
                              // and 1 in their own colours (bilinear)
uniform vec3 uMaterialColour[2]; // materials 0 and 1's colours (linear RGB)
uniform float uDropletLevel;  // scale of the largest single w: every particle shows as a disc
uniform float uThreshold; // field level at the surface (1)
uniform float uRimWidth;  // width of the rim band inside the surface (px of the target)
uniform int uDark;        // 1: pressure view (black liquid, grey rim)
uniform sampler2D uSolidDistance; // r = distance to the nearest solid (its texels; bilinear)
uniform float uSolidReach;        // distance at which the level is back to uThreshold (texels
                                  // of uSolidDistance); 0: no solids, uSolidDistance not read
uniform float uSolidThreshold;    // field level at the surface where it touches a solid (1)

// ---- outputs ----
out vec4 fragColour; // straight alpha, blended over the background

void main() {
    vec4 field = texture(uField, vUv);
    vec4 weights = texture(uWeight, vUv);
    float sum = weights.r;
    // A lone particle's sum peaks below the threshold, and sparse ones (spray, a thin film, a
    // chain) dip below it between them: the largest single kernel, scaled, stands in, so every
    // particle shows at least as a disc of half a spacing (at the default threshold). Inside
    // the liquid and along dense edges the sum is larger and decides.
    float a = max(sum, uDropletLevel * field.a);
    // 1 at a solid, 0 from uSolidReach on; the surface level follows. The solid mask marks the
    // texels whose centre a solid covers, so a solid's edge may lie up to a texel closer than
    // the distance says: 0.7 texel of it counts as touching.
    float near = 0.0;
    if (uSolidReach > 0.0) {
        near = 1.0 - smoothstep(0.0, uSolidReach, texture(uSolidDistance, vUv).r - 0.7);
    }
    float level = a - mix(uThreshold, uSolidThreshold, near); // > 0 inside the liquid
    // Derivatives first: they must be taken before any fragment of the quad discards.
    vec2 gradient = vec2(dFdx(a), dFdy(a)); // field change per target pixel (lighting)
    vec2 levelGradient = vec2(dFdx(level), dFdy(level)); // the surface's (coverage, rim)
    // Three colour classes: material 0 and material 1 in their own colours, and the rest
    // (other materials, particles with a colour of their own), which mix as the field mixes
    // them. Each pixel takes the class whose weight leads, anti-aliased over about a pixel
    // where two meet: a clean edge between water and yoghurt instead of a blur a kernel wide.
    // The rest's weight is what the two materials leave of the sum; under 1% of it is the
    // half floats' rounding, not a class.
    float restWeight = sum - weights.g - weights.b;
    vec3 classes = vec3(weights.g, weights.b, restWeight > 0.01 * sum ? restWeight : 0.0);
    vec3 lead = classes - max(classes.yzx, classes.zxy);
    vec3 leadEdge = 0.7 * fwidth(lead) + 1e-4;
    vec3 present = step(vec3(1e-7), classes); // an absent class never takes a pixel
    float slope = length(levelGradient);
    float edge = 0.7 * (abs(levelGradient.x) + abs(levelGradient.y)) + 1e-4;
    float coverage = smoothstep(-edge, edge, level);
    if (coverage <= 0.0) {
        discard;
    }
    // Distance inside the surface (px), from the level's first-order expansion.
    float depth = level / max(slope, 1e-5);
    float rim = (1.0 - smoothstep(0.0, uRimWidth, depth)) * (1.0 - near);
    // Outward normal in the target's plane (the field grows inwards); light from the upper left.
    vec2 normal = -gradient / max(length(gradient), 1e-5);
    float facing = max(dot(normal, vec2(-0.6, 0.8)), 0.0);

    vec3 colour;
    if (uDark == 1) {
        colour = vec3(0.42) * rim;
    } else {
        // The classes' colours, each where it leads: the rest's is the field's colour sum less
        // the two materials' parts, over its weight.
        vec3 own = smoothstep(-leadEdge, leadEdge, lead) * present;
        own /= max(own.x + own.y + own.z, 1e-6);
        vec3 rest = max(field.rgb - uMaterialColour[0] * classes.x -
                        uMaterialColour[1] * classes.y, vec3(0.0)) / max(classes.z, 1e-6);
        vec3 base = own.x * uMaterialColour[0] + own.y * uMaterialColour[1] + own.z * rest;
        // Rim: lighter towards white, most on the lit side.
        vec3 light = mix(base, vec3(1.0), 0.45);
        colour = mix(base, light, rim * (0.45 + 0.55 * facing));
        // Faint highlight: a soft glow further in on the lit side, fading out by 6 rim widths.
        float glow = smoothstep(uRimWidth, 2.5 * uRimWidth, depth) *
                     (1.0 - smoothstep(3.0 * uRimWidth, 6.0 * uRimWidth, depth));
        colour += vec3(0.12) * (facing * facing * glow * (1.0 - near));
    }
    fragColour = vec4(colour, coverage);
}
