#version 330 core
// solid_mask.frag — marks the texels an opaque shape (a wall, a body) covers, for the solid
// distance passes (solid_distance.frag). Drawn with shape.vert into an R8 target cleared to 0.

// ---- inputs ----
in vec4 vColour; // unused: every opaque shape is a solid, whatever its colour

// ---- outputs ----
out float fragSolid; // 1 inside a solid

void main() {
    fragSolid = 1.0;
}
