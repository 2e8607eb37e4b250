#version 330 core
// pressure_square.vert — the seed report's pressure view: one translucent red square per
// particle (side = the material's spacing), more opaque under more pressure.

// ---- inputs ----
layout(location = 0) in vec2 aCorner;   // quad corner in [-1, 1]^2 (per vertex)
layout(location = 1) in float aX;       // particle position x (m, per instance)
layout(location = 2) in float aY;       // particle position y (m, per instance)
layout(location = 5) in float aPressure; // pressure (Pa, per instance)
layout(location = 6) in uint aMaterial;  // material index (per instance)

// ---- uniforms ----
uniform mat3 uWorldToClip;   // camera: world (m) to clip space
uniform float uSpacing[16];  // particle spacing per material (m)
uniform int uMaterialCount;  // styles in use (1..16)
uniform float uInvScale;     // 1 / pressure drawn fully opaque (1/Pa)

// ---- outputs ----
flat out float vAlpha;

void main() {
    int m = aMaterial < uint(uMaterialCount) ? int(aMaterial) : 0;
    vAlpha = 0.85 * clamp(aPressure * uInvScale, 0.0, 1.0);
    vec2 world = vec2(aX, aY) + aCorner * (0.5 * uSpacing[m]);
    // Squares too faint to see are moved outside the clip volume: no fill cost.
    gl_Position = vAlpha < 0.002 ? vec4(2.0, 2.0, 2.0, 1.0)
                                 : vec4((uWorldToClip * vec3(world, 1.0)).xy, 0.0, 1.0);
}
