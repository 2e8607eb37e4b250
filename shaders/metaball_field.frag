#version 330 core
// metaball_field.frag — adds one particle's weight to the field targets (blend ONE, ONE; the
// equation is ADD for rgb and MAX for alpha).
// w = (1 - r^2/R^2)^3: compact (exactly 0 at R) and smooth (C2), so the summed field and its
// threshold surface are smooth too. Attachment 0: rgb sums colour x w (the composite divides
// by the weight sum: a w-weighted mix of the materials' colours), alpha keeps the largest
// single w (lone droplets). Attachment 1: the sum of w, the field itself.

// ---- inputs ----
in vec2 vLocal;             // position in the kernel, in units of R
flat in vec4 vContribution; // (colour, 1) x normalisation

// ---- outputs ----
layout(location = 0) out vec4 fragColourField; // (colour x w x weight, w)
layout(location = 1) out float fragField;      // w x weight

void main() {
    float w = max(1.0 - dot(vLocal, vLocal), 0.0);
    w = w * w * w;
    fragColourField = vec4(vContribution.rgb * w, w);
    fragField = vContribution.a * w;
}
