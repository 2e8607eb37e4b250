#version 330 core
// metaball_field.frag — adds one particle's weight to the field targets (blend ONE, ONE; the
// equation is ADD for rgb and MAX for alpha).
// w = (1 - r^2/R^2)^3: compact (exactly 0 at R) and smooth (C2), so the summed field and its
// threshold surface are smooth too. Attachment 0: rgb sums colour x w (the composite divides
// by the weight sum: a w-weighted mix of the materials' colours), alpha keeps the largest
// single w (lone droplets). Attachment 1: r = the sum of w, the field itself; g and b = the
// parts of it from materials 0 and 1 in their own colours (the composite's material edge).

// ---- inputs ----
in vec2 vLocal;             // position in the kernel, in units of R
flat in vec4 vContribution; // (colour, 1) x normalisation
flat in vec2 vClass;        // (1, 0) material 0, (0, 1) material 1, in their own colours

// ---- outputs ----
layout(location = 0) out vec4 fragColourField; // (colour x w x weight, w)
layout(location = 1) out vec4 fragField;       // (1, class) x w x weight

void main() {
    float w = max(1.0 - dot(vLocal, vLocal), 0.0);
    w = w * w * w;
    fragColourField = vec4(vContribution.rgb * w, w);
    fragField = vec4(1.0, vClass, 0.0) * (vContribution.a * w);
}
