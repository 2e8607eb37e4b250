#version 330 core
// metaball_field.vert — one instanced unit quad per particle, covering the support of its
// metaball kernel (radius R = fieldRadius x the material's spacing).

// ---- inputs ----
layout(location = 0) in vec2 aCorner;  // quad corner in [-1, 1]^2 (per vertex)
layout(location = 1) in float aX;      // particle position x (m, per instance)
layout(location = 2) in float aY;      // particle position y (m, per instance)
layout(location = 6) in uint aMaterial; // material index (per instance)
layout(location = 7) in vec4 aColour;   // particle colour, sRGB (per instance; alpha 0: none)

// ---- uniforms ----
uniform mat3 uWorldToClip;      // camera: world (m) to clip space
uniform float uSpacing[16];     // particle spacing per material (m)
uniform vec3 uColour[16];       // colour per material (linear RGB)
uniform int uMaterialCount;     // styles in use (1..16); unknown indices use style 0
uniform float uFieldRadius;     // R over spacing (1)
uniform float uWeight;          // field normalisation: interior of the liquid sums to ~1.2

// ---- outputs ----
out vec2 vLocal;                // position in the kernel, in units of R
flat out vec4 vContribution;    // (colour, 1) x uWeight
flat out vec2 vClass;           // (1, 0): material 0 in its own colour, (0, 1): material 1

void main() {
    int m = aMaterial < uint(uMaterialCount) ? int(aMaterial) : 0;
    float radius = uFieldRadius * uSpacing[m];
    vec2 world = vec2(aX, aY) + aCorner * radius;
    gl_Position = vec4((uWorldToClip * vec3(world, 1.0)).xy, 0.0, 1.0);
    vLocal = aCorner;
    // A particle's own colour (fluid::Colour, sRGB) replaces its material's, in linear RGB: the
    // field mixes them where colours meet as it mixes materials.
    vec3 colour = aColour.a > 0.0 ? pow(aColour.rgb, vec3(2.2)) : uColour[m];
    vContribution = vec4(colour, 1.0) * uWeight;
    // The composite draws a clean edge between materials 0 and 1 in their own colours (most
    // levels' water and yoghurt); particles of other materials or with their own colour mix.
    bool own = aColour.a <= 0.0;
    vClass = vec2(own && m == 0 ? 1.0 : 0.0, own && m == 1 ? 1.0 : 0.0);
}
