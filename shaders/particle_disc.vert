#version 330 core
// particle_disc.vert — one anti-aliased disc per particle (diameter 0.9 x spacing), coloured
// by speed on a blue - cyan - yellow - red ramp.

// ---- inputs ----
layout(location = 0) in vec2 aCorner;   // quad corner in [-1, 1]^2 (per vertex)
layout(location = 1) in float aX;       // particle position x (m, per instance)
layout(location = 2) in float aY;       // particle position y (m, per instance)
layout(location = 3) in float aVx;      // velocity x (m/s, per instance)
layout(location = 4) in float aVy;      // velocity y (m/s, per instance)
layout(location = 6) in uint aMaterial; // material index (per instance)

// ---- uniforms ----
uniform mat3 uWorldToClip;     // camera: world (m) to clip space
uniform float uSpacing[16];    // particle spacing per material (m)
uniform int uMaterialCount;    // styles in use (1..16)
uniform float uPixel;          // size of one target pixel (m)
uniform float uInvSpeedScale;  // 1 / speed at the red end (s/m)

// ---- outputs ----
out vec2 vLocal;         // offset from the particle (m)
flat out float vRadius;  // disc radius (m)
flat out vec3 vColour;   // speed colour

vec3 ramp(float t) {
    const vec3 blue = vec3(0.10, 0.25, 0.95);
    const vec3 cyan = vec3(0.05, 0.85, 0.95);
    const vec3 yellow = vec3(0.98, 0.90, 0.10);
    const vec3 red = vec3(0.95, 0.12, 0.08);
    t = clamp(t, 0.0, 1.0) * 3.0;
    if (t < 1.0) {
        return mix(blue, cyan, t);
    }
    if (t < 2.0) {
        return mix(cyan, yellow, t - 1.0);
    }
    return mix(yellow, red, t - 2.0);
}

void main() {
    int m = aMaterial < uint(uMaterialCount) ? int(aMaterial) : 0;
    vRadius = 0.45 * uSpacing[m];
    // One pixel of margin for the anti-aliased edge.
    vLocal = aCorner * (vRadius + uPixel);
    vColour = ramp(length(vec2(aVx, aVy)) * uInvSpeedScale);
    gl_Position = vec4((uWorldToClip * vec3(vec2(aX, aY) + vLocal, 1.0)).xy, 0.0, 1.0);
}
