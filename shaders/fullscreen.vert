#version 330 core
// fullscreen.vert — one triangle covering the target, from gl_VertexID alone (draw 3 vertices
// with an empty vertex array bound; core profile needs one bound even without attributes).

// ---- inputs ----
// gl_VertexID in {0, 1, 2}.

// ---- outputs ----
out vec2 vUv; // texture coordinate of the target, [0, 1] across it

void main() {
    // (-1, -1), (3, -1), (-1, 3): the visible square is the lower-left quarter.
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    vUv = p * 0.5 + 0.5;
    gl_Position = vec4(p, 0.0, 1.0);
}
