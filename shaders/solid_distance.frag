#version 330 core
// solid_distance.frag — one pass of a windowed, separable Euclidean distance transform: the
// distance from each field texel to the nearest texel of an opaque shape, exact within the
// window, uFar beyond it. Pass 0 runs along rows over the solid mask (r = 1 in solids) and
// writes the distance to the nearest solid texel of the row; pass 1 runs along columns over
// pass 0's output and writes min over rows of sqrt(row distance^2 + row offset^2). Drawn as a
// full-screen triangle into a target of the mask's size (texel = fragment).

// ---- inputs ----
// gl_FragCoord.xy: the texel (the viewport covers the whole target).

// ---- uniforms ----
uniform sampler2D uSource; // pass 0: the solid mask; pass 1: pass 0's row distances (texels)
uniform int uPass;         // 0: along rows, 1: along columns
uniform int uTaps;         // taps on each side of the texel (1..32)
uniform int uStride;       // texels between taps (1 unless the reach is wide)
uniform float uFar;        // distance written when no solid is within reach (texels)

// ---- outputs ----
out float fragDistance; // pass 0: row distance, pass 1: distance (texels)

void main() {
    ivec2 size = textureSize(uSource, 0);
    ivec2 texel = ivec2(gl_FragCoord.xy);
    if (uPass == 0) {
        float best = uFar;
        for (int k = -uTaps; k <= uTaps; ++k) {
            int x = texel.x + k * uStride;
            if (x >= 0 && x < size.x && texelFetch(uSource, ivec2(x, texel.y), 0).r > 0.5) {
                best = min(best, float(abs(k * uStride)));
            }
        }
        fragDistance = best;
    } else {
        float best = uFar * uFar;
        for (int k = -uTaps; k <= uTaps; ++k) {
            int y = texel.y + k * uStride;
            if (y >= 0 && y < size.y) {
                float across = texelFetch(uSource, ivec2(texel.x, y), 0).r;
                float along = float(k * uStride);
                best = min(best, across * across + along * along);
            }
        }
        fragDistance = min(sqrt(best), uFar);
    }
}
