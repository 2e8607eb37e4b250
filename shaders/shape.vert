#version 330 core
// shape.vert — filled shapes (walls, sensors, bodies, cursor) tessellated on the CPU.

// ---- inputs ----
layout(location = 0) in vec2 aPosition; // world position (m)
layout(location = 1) in vec4 aColour;   // colour, straight alpha

// ---- uniforms ----
uniform mat3 uWorldToClip; // camera: world (m) to clip space

// ---- outputs ----
out vec4 vColour;

void main() {
    gl_Position = vec4((uWorldToClip * vec3(aPosition, 1.0)).xy, 0.0, 1.0);
    vColour = aColour;
}
