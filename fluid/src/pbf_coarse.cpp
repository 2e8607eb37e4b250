// fluid — the position-based solver's coarse-level density correction.
//
// A Jacobi sweep of the density constraint carries pressure about one support radius, so the
// deep, slow compression modes (a tank's hydrostatic column) need many sweeps. Before the sweeps
// of a sub-step, this pass removes the large-scale part of the compression on a coarse grid
// [Kugelstadt et al. 2019 project densities on a grid in the same way]:
//   fill      each node's fill F = sum V_i N(x_i) / H^2 of particles (rest areas V, bilinear
//             weights N) plus the same of boundary samples; 1 is the rest lattice
//   types     air (F < 1/2: the potential is 0 beyond it, a free surface placed where F
//             crosses 1/2 between a fluid node and its air neighbour), solid (samples fill more
//             than particles: no flux through it), fluid (the unknowns)
//   solve     -lap psi = max(F - 1 - tolerance, 0) H^2 on the fluid nodes, conjugate gradients
//             preconditioned by a multigrid V-cycle (coarse_multigrid.h)
//   move      each particle by -share grad psi (bilinear), at most kCoarseMaxMove of its support
//   bodies    rigid bodies of boundary plugins (WorldState::bodies) are unknowns of the same
//             solve [Batty, Bertails & Bridson 2007]: the operator gains G M^-1 G^T, G the flux
//             a body's displacement (x, y) drives into the nodes (its fill's derivative: the
//             integral of the bilinear gradients over its inside, with the potential extended
//             into it linearly, so G^T psi is the -integral of grad psi that would move the water
//             in its place), and each body moves by share M^-1 G^T psi
//             (docs/position_based.md, "Bodies in the coarse solve")
// The displacement divergence -div u = lap psi removes the compression to first order. The grid
// work runs serially in a fixed order and the particles' moves are independent of each other,
// so results do not depend on the number of workers.
#include "pbf_loops.h"
#include "pbf_tuning.h"

#include "parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

namespace fluid::detail {

namespace {

constexpr uint8_t kAir = 0, kFluid = 1, kSolid = 2;
// Most nodes the grid may have; a world spread wider skips the pass that sub-step.
constexpr size_t kMaxNodes = size_t(1) << 22;
// Lattice points per cell side at which a body's inside test is read for its fill.
constexpr int kSubcells = 4;
// Most lattice points one body's outline is read at per sub-step.
constexpr int kMaxLattice = 1 << 18;
// Particles per task of the move.
constexpr uint32_t kMoveGrain = 2048;

// Interleaved partial sums of the coarse solve's dot products (count; see the solve).
constexpr size_t kDotLanes = 8;

// The partial sums combined pairwise in a fixed order.
double combineLanes(const double (&lanes)[kDotLanes]) {
    return ((lanes[0] + lanes[1]) + (lanes[2] + lanes[3])) +
           ((lanes[4] + lanes[5]) + (lanes[6] + lanes[7]));
}

// x.y over `count` (a multiple of kDotLanes) floats, in double, in kDotLanes partial sums.
double laneDot(const float* x, const float* y, size_t count) {
    double lanes[kDotLanes] = {};
    for (size_t a0 = 0; a0 < count; a0 += kDotLanes) {
        for (size_t l = 0; l < kDotLanes; ++l) {
            lanes[l] += double(x[a0 + l]) * double(y[a0 + l]);
        }
    }
    return combineLanes(lanes);
}

using Layout = CoarseLayout;

// `amount` spread over the four nodes of the cell whose lower-left node is k (rows `stride`
// nodes long) with bilinear fractions (fx, fy).
void splatAt(std::vector<float>& fill, size_t stride, size_t k, float fx, float fy, float amount) {
    fill[k] += amount * (1.0f - fx) * (1.0f - fy);
    fill[k + 1] += amount * fx * (1.0f - fy);
    fill[k + stride] += amount * (1.0f - fx) * fy;
    fill[k + stride + 1] += amount * fx * fy;
}

void splat(std::vector<float>& fill, const Layout& g, float x, float y, float amount) {
    int i = 0, j = 0;
    float fx = 0, fy = 0;
    g.cell(x, y, i, j, fx, fy);
    splatAt(fill, size_t(g.nx), size_t(j) * size_t(g.nx) + size_t(i), fx, fy, amount);
}

// Particle i's coarse move: share times minus the bilinear gradient of the node values (in its
// cell, with its fractions, as the fill found them at index `filledAs`), at most kCoarseMaxMove
// of its support, into the correction (cx, cy) and onto its position; share times the
// potential there into coarseP (the pressure's coarse part).
void moveParticle(Particles& p, PositionBasedScratch& x, const CoarseGrid& cg, const Layout& g,
                  const float* value, float share, uint32_t i, uint32_t filledAs) {
    const float fx = cg.fx[filledAs], fy = cg.fy[filledAs];
    const size_t k = cg.cell[filledAs];
    const float v00 = value[k], v10 = value[k + 1];
    const float v01 = value[k + size_t(g.nx)], v11 = value[k + size_t(g.nx) + 1];
    float ux = -share * ((1.0f - fy) * (v10 - v00) + fy * (v11 - v01)) * g.invH;
    float uy = -share * ((1.0f - fx) * (v01 - v00) + fx * (v11 - v10)) * g.invH;
    if (!cg.moveScale.empty()) {
        const float scale = cg.moveScale[p.material[i]];
        ux *= scale;
        uy *= scale;
    }
    const float limit = tuning::kCoarseMaxMove * p.h[i];
    const float len2 = ux * ux + uy * uy;
    if (!(len2 <= limit * limit)) {
        const float scale = std::isfinite(len2) ? limit / std::sqrt(len2) : 0.0f;
        ux = std::isfinite(len2) ? ux * scale : 0.0f;
        uy = std::isfinite(len2) ? uy * scale : 0.0f;
    }
    x.cx[i] = ux;
    x.cy[i] = uy;
    x.coarseP[i] = share * ((1.0f - fy) * ((1.0f - fx) * v00 + fx * v10) +
                            fy * ((1.0f - fx) * v01 + fx * v11));
    p.px[i] = x.ox[i] + ux;
    p.py[i] = x.oy[i] + uy;
}

// G^T v: per body, the sums of its faces' fluxes times v (x, y), in face order (the faces are
// in unknown order: the same sums on every run).
void bodyForce(const CoarseGrid& cg, const float* v, std::vector<double>& sum) {
    std::fill(sum.begin(), sum.end(), 0.0);
    for (const CoarseGrid::BodyFace& f : cg.bodyFaces) {
        const double x = v[f.unknown];
        sum[2 * f.body] += double(f.gx) * x;
        sum[2 * f.body + 1] += double(f.gy) * x;
    }
}

// Each body's samples on the grid, in sorted order: body b's are order[start[b]..start[b+1])
// (a counting sort of the samples by body). Those beyond the grid are left out, as the splat
// leaves them out: the grid spans the particles only, and its clamped cells would pile a body
// above the liquid into its top row (4.5 cm crates resting on water were read as solid rows over
// full nodes, and pushed out of it at 1 m/s).
void sortBodySamples(const WorldState& s, const Layout& g, std::vector<uint32_t>& start,
                     std::vector<uint32_t>& order) {
    const Samples& w = s.samples;
    const size_t count = s.bodies.size();
    const float x1 = g.x0 + float(g.nx - 1) / g.invH, y1 = g.y0 + float(g.ny - 1) / g.invH;
    const auto onGrid = [&](uint32_t k) {
        return w.body[k] >= 0 && w.px[k] >= g.x0 && w.px[k] <= x1 && w.py[k] >= g.y0 &&
               w.py[k] <= y1;
    };
    start.assign(count + 1, 0);
    for (uint32_t k = 0; k < w.body.size(); ++k) {
        if (onGrid(k)) {
            ++start[size_t(w.body[k]) + 1];
        }
    }
    for (size_t b = 0; b < count; ++b) {
        start[b + 1] += start[b];
    }
    order.resize(start[count]);
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (uint32_t k = 0; k < w.body.size(); ++k) {
        if (onGrid(k)) {
            order[fill[size_t(w.body[k])]++] = k;
        }
    }
}

// One body's box of nodes [i0, i1] x [j0, j1] and its samples' fill of it (cg.ownFill, rows
// i1 - i0 + 1 long): the cells of its samples, one node more each side (the outline lies up to
// half a spacing outside the samples). False when it has no sample on the grid.
struct NodeBox {
    int i0 = 0, j0 = 0, i1 = 0, j1 = 0;
    size_t stride() const { return size_t(i1 - i0 + 1); }
};
bool sampleFill(CoarseGrid& cg, const Samples& w, const Layout& g, float amount,
                std::span<const uint32_t> samples, NodeBox& box) {
    if (samples.empty()) {
        return false;
    }
    // Each sample's cell and fractions, as the world grid's splat found them.
    struct Cell {
        int i, j;
        float fx, fy;
    };
    std::vector<Cell> cells(samples.size());
    box = NodeBox{g.nx, g.ny, -1, -1};
    for (size_t o = 0; o < samples.size(); ++o) {
        Cell& c = cells[o];
        g.cell(w.px[samples[o]], w.py[samples[o]], c.i, c.j, c.fx, c.fy);
        box.i0 = std::min(box.i0, c.i);
        box.j0 = std::min(box.j0, c.j);
        box.i1 = std::max(box.i1, c.i + 1);
        box.j1 = std::max(box.j1, c.j + 1);
    }
    box.i0 = std::max(box.i0 - 1, 0);
    box.j0 = std::max(box.j0 - 1, 0);
    box.i1 = std::min(box.i1 + 1, g.nx - 1);
    box.j1 = std::min(box.j1 + 1, g.ny - 1);
    cg.ownFill.assign(box.stride() * size_t(box.j1 - box.j0 + 1), 0.0f);
    for (const Cell& c : cells) {
        const size_t k = size_t(c.j - box.j0) * box.stride() + size_t(c.i - box.i0);
        splatAt(cg.ownFill, box.stride(), k, c.fx, c.fy, amount);
    }
    return true;
}

// The inside test on a lattice of kSubcells x kSubcells points per cell over the box, into
// cg.inside (rows (i1 - i0) kSubcells long); returns how many points lie inside. None for a box
// too large for the lattice (the body keeps its samples' fill).
template <class Contains>
uint32_t readOutline(CoarseGrid& cg, const Layout& g, const NodeBox& box, float shiftX,
                     float shiftY, Contains&& contains) {
    const double points = double(box.i1 - box.i0) * double(box.j1 - box.j0) * kSubcells * kSubcells;
    const bool tooLarge = points > double(kMaxLattice);
    const int fnx = tooLarge ? 0 : (box.i1 - box.i0) * kSubcells;
    const int fny = tooLarge ? 0 : (box.j1 - box.j0) * kSubcells;
    const float cell = 1.0f / g.invH;
    const float x0 = g.x0 + float(box.i0) * cell, y0 = g.y0 + float(box.j0) * cell;
    cg.inside.assign(size_t(fnx) * size_t(fny), 0);
    uint32_t inside = 0;
    for (int q = 0; q < fny; ++q) {
        for (int r = 0; r < fnx; ++r) {
            if (contains(x0 + shiftX + (float(r) + 0.5f) * cell / float(kSubcells),
                         y0 + shiftY + (float(q) + 0.5f) * cell / float(kSubcells))) {
                cg.inside[size_t(q) * size_t(fnx) + size_t(r)] = 1;
                ++inside;
            }
        }
    }
    return inside;
}

// Body `body`'s fill and gradient weights from its outline's lattice (cg.inside over `box`,
// shifted by (shiftX, shiftY) < one lattice step): each inside point of area (H / kSubcells)^2
// is splatted bilinearly like a particle of water (its fill, box-relative, into
// cg.ownFill) and gives each corner of its cell that area times the corner's bilinear gradient
// there (CoarseGrid::NodeWeight, appended to cg.bodyGradient in node order). The lattice moves
// with the body, so both change smoothly with its position: the gradient weights are the fill's
// derivative with respect to the body's translation.
void outlineSplat(CoarseGrid& cg, const Layout& g, const NodeBox& box, float shiftX, float shiftY,
                  uint32_t body) {
    const int fnx = (box.i1 - box.i0) * kSubcells, fny = (box.j1 - box.j0) * kSubcells;
    const size_t stride = box.stride();
    const size_t rows = size_t(box.j1 - box.j0 + 1);
    cg.boxGradient.assign(2 * stride * rows, 0.0f);
    cg.ownFill.assign(stride * rows, 0.0f);
    float* w = cg.boxGradient.data();
    const float step = 1.0f / float(kSubcells); // lattice step in cells
    const float sx = shiftX * g.invH, sy = shiftY * g.invH;
    // Area over H (the bilinear gradient is 1/H times the fractions below), and area over H^2.
    const float a = 1.0f / (g.invH * float(kSubcells * kSubcells));
    const float fillArea = 1.0f / float(kSubcells * kSubcells);
    for (int q = 0; q < fny; ++q) {
        const float gy = sy + (float(q) + 0.5f) * step;
        const int cj = int(std::floor(gy));
        if (cj < 0 || cj >= box.j1 - box.j0) {
            continue;
        }
        const float fy = gy - float(cj);
        for (int r = 0; r < fnx; ++r) {
            if (cg.inside[size_t(q) * size_t(fnx) + size_t(r)] == 0) {
                continue;
            }
            const float gx = sx + (float(r) + 0.5f) * step;
            const int ci = int(std::floor(gx));
            if (ci < 0 || ci >= box.i1 - box.i0) {
                continue;
            }
            const float fx = gx - float(ci);
            const size_t k = size_t(cj) * stride + size_t(ci);
            splatAt(cg.ownFill, stride, k, fx, fy, fillArea);
            w[2 * k] -= a * (1.0f - fy);
            w[2 * k + 1] -= a * (1.0f - fx);
            w[2 * (k + 1)] += a * (1.0f - fy);
            w[2 * (k + 1) + 1] -= a * fx;
            w[2 * (k + stride)] -= a * fy;
            w[2 * (k + stride) + 1] += a * (1.0f - fx);
            w[2 * (k + stride + 1)] += a * fy;
            w[2 * (k + stride + 1) + 1] += a * fx;
        }
    }
    for (size_t j = 0; j < rows; ++j) {
        for (size_t i = 0; i < stride; ++i) {
            const size_t k = j * stride + i;
            if (w[2 * k] != 0.0f || w[2 * k + 1] != 0.0f) {
                const size_t node = (size_t(box.j0) + j) * size_t(g.nx) + size_t(box.i0) + i;
                cg.bodyGradient.push_back({uint32_t(node), body, w[2 * k], w[2 * k + 1]});
            }
        }
    }
}

// Which body fills each node (cg.owner): b for a node whose cell body b's outline fills to
// kCoarseBodyOwn or more (its inside test at the pose its samples stand at, on the lattice), -1
// elsewhere. Each body's fill of the nodes in its box comes from
// its outline, in place of its samples' splat (cg.solid; cg.bodyFill keeps the bodies' part): a
// body's own samples must never fill a node outside it and push it (a 4.5 cm crate whose samples
// overfilled the node under it climbed to the lid at 2.4 m/s). A plugin without an inside test,
// or a body too large for the lattice, keeps its samples' fill, and the nodes they fill most are
// its own.
void markOwners(WorldState& s, const Layout& g, float amount, float time) {
    CoarseGrid& cg = s.coarse;
    const size_t nodes = size_t(g.nx) * size_t(g.ny);
    cg.owner.assign(nodes, -1);
    cg.bodyFill.assign(nodes, 0.0f);
    cg.bodyGradient.clear();
    cg.outlined.assign(s.bodies.size(), 0);
    std::vector<uint32_t> start, order;
    sortBodySamples(s, g, start, order);
    const float cell = 1.0f / g.invH;
    for (size_t b = 0; b < s.bodies.size(); ++b) {
        NodeBox box;
        const std::span<const uint32_t> samples(order.data() + start[b], start[b + 1] - start[b]);
        if (!sampleFill(cg, s.samples, g, amount, samples, box)) {
            continue;
        }
        // The body's own inside test, where its samples stand (its own sweep at `time`, which
        // the coarse corrections so far have moved).
        const BodyState& body = s.bodies[b];
        const BoundaryPlugin& plugin = *s.boundaries[body.plugin];
        const float offX = body.dvx * time + body.ox, offY = body.dvy * time + body.oy;
        const auto contains = [&](float x, float y) {
            return plugin.bodyContains(body.index, glm::vec2(x - offX, y - offY), time);
        };
        // The lattice is anchored to the body (its first sample, where it stands now), so the
        // same points stay inside it as it moves and its fill follows it smoothly.
        const BoundarySamples& own = plugin.samples();
        const size_t first = body.sampleBegin - s.samples.pluginBegin[body.plugin];
        const float step = cell / float(kSubcells);
        const float anchorX = own.px[first] + own.vx[first] * time + offX;
        const float anchorY = own.py[first] + own.vy[first] * time + offY;
        const float boxX = g.x0 + float(box.i0) * cell, boxY = g.y0 + float(box.j0) * cell;
        const float shiftX = (anchorX - boxX) - step * std::floor((anchorX - boxX) / step);
        const float shiftY = (anchorY - boxY) - step * std::floor((anchorY - boxY) / step);
        const uint32_t inside = readOutline(cg, g, box, shiftX, shiftY, contains);
        cg.samplesFill.swap(cg.ownFill); // the samples' fill, kept while the outline's is made
        if (inside > 0) {
            cg.outlined[b] = 1;
            outlineSplat(cg, g, box, shiftX, shiftY, uint32_t(b));
        }
        for (int j = box.j0; j <= box.j1; ++j) {
            for (int i = box.i0; i <= box.i1; ++i) {
                const size_t k = size_t(j) * size_t(g.nx) + size_t(i);
                const size_t local = size_t(j - box.j0) * box.stride() + size_t(i - box.i0);
                const float sampled = cg.samplesFill[local];
                if (inside == 0) {
                    if (sampled > 0.0f && sampled >= 0.5f * cg.solid[k]) {
                        cg.owner[k] = int32_t(b); // no inside test: the nodes its samples fill
                    }
                    continue;
                }
                const float geometric = cg.ownFill[local];
                cg.solid[k] = std::max(cg.solid[k] - sampled, 0.0f) + geometric;
                cg.bodyFill[k] += geometric;
                if (geometric >= tuning::kCoarseBodyOwn) {
                    cg.owner[k] = int32_t(b);
                }
            }
        }
    }
}

// The rest density of the liquid the bodies float in: the particles' mean, weighted by their
// rest area (one material: its own). The world has particles (pbfCoarseFill returns before
// otherwise).
double fluidDensity(const WorldState& s) {
    const Particles& p = s.particles;
    double mass = 0.0, area = 0.0;
    std::vector<uint32_t> counts(s.materials.size(), 0);
    for (const uint16_t m : p.material) {
        ++counts[m];
    }
    for (size_t m = 0; m < counts.size(); ++m) {
        const double v = double(counts[m]) * double(particleArea(s.materials[m], s.def.depth));
        mass += v * double(s.materials[m].restDensity);
        area += v;
    }
    return mass / area;
}

// True when every material some particle has shares one rest density.
bool oneRestDensity(const WorldState& s) {
    float first = 0.0f;
    for (size_t m = 0; m < s.materials.size(); ++m) {
        if (!s.isPresent(m)) {
            continue;
        }
        const float rho0 = s.materials[m].restDensity;
        if (first != 0.0f && rho0 != first) {
            return false;
        }
        first = rho0;
    }
    return true;
}

// cg.moveScale: per material, how far its particles move per unit of the solve's displacement,
// rho / rho0 with rho the density the solve is made for (fluidDensity): the displacement is
// -dt^2 grad p / rho0, so a denser particle moves less, as the sweeps move a heavier particle
// less. Without it the correction held a yoghurt lump (1,050 kg/m^3) in water as if it were
// water: it sank at 1 mm/s in the game preset, 1.6 cm/s in the precise one (docs/yield_stress.md,
// "A lump in water"). Empty (every scale exactly 1) when the particles share one rest density.
void setMoveScale(CoarseGrid& cg, const WorldState& s, bool oneDensity, double rho) {
    cg.moveScale.clear();
    if (oneDensity) {
        return;
    }
    cg.moveScale.resize(s.materials.size());
    for (size_t m = 0; m < s.materials.size(); ++m) {
        cg.moveScale[m] = float(rho / double(s.materials[m].restDensity));
    }
}

// Each node's type (air, fluid, solid) and right-hand side: a fluid node's compression above
// `tolerance`, times h2. Returns true when some node is compressed.
bool classifyNodes(CoarseGrid& cg, size_t nodes, float tolerance, float h2, bool bodies) {
    cg.type.assign(nodes, kAir);
    cg.rhs.assign(nodes, 0.0f);
    if (bodies) {
        cg.open.resize(nodes);
        for (size_t k = 0; k < nodes; ++k) {
            cg.open[k] = std::clamp(
                (tuning::kCoarseBodyOwn - cg.bodyFill[k]) / tuning::kCoarseBodyFade, 0.0f, 1.0f);
        }
    }
    bool any = false;
    for (size_t k = 0; k < nodes; ++k) {
        const float f = cg.fluid[k], sf = cg.solid[k];
        // Solid: inside a body, or filled more by other solids' samples than by particles.
        const float fixed = bodies ? sf - cg.bodyFill[k] : sf;
        if ((bodies && cg.owner[k] >= 0) || (fixed > f && fixed >= 0.25f)) {
            cg.type[k] = kSolid;
        } else if (f + sf >= 0.5f) {
            cg.type[k] = kFluid;
            float e = f + sf - 1.0f - tolerance;
            if (bodies) {
                // Gone where the node would be a body's (kCoarseBodyOwn), so the source does
                // not step when it becomes one.
                e *= cg.open[k];
            }
            if (e > 0.0f) {
                cg.rhs[k] = e * h2;
                any = true;
            }
        }
    }
    return any;
}

// The operator's coefficient of a face between a fluid node of fill `inside` and an air node
// of fill `outside` (fills of particles and samples, 1 full): the potential's zero, the free
// surface, lies where the fill crosses 1/2 between them, at theta of the cell from the fluid
// node, and the face's flux takes the potential's slope over that distance (1/theta; the
// ghost-fluid free surface of Gibou et al. 2002 and Enright et al. 2003). With the zero on the
// air node itself floaters read too deep a pressure (docs/position_based.md, "Bodies in the
// coarse solve").
float surfaceCoefficient(float inside, float outside) {
    const float theta = (inside - 0.5f) / std::max(inside - outside, 1e-6f);
    return 1.0f / std::clamp(theta, tuning::kCoarseSurfaceMin, 1.0f);
}

// The unknowns in compact order (cg.active: their nodes), each with its diagonal and its fluid
// neighbours' compact indices; a missing neighbour points at slot `count` (the unknowns' count),
// which the vectors the operator reads keep at 0 (the same sums as skipping it, without a
// branch). A face between an unknown and a node inside a body is also a row of the bodies'
// Jacobian (cg.bodyFaces): the body's displacement D drives the flux H n . D out of the
// unknown's cell through it (n from the unknown to the body's node). Only translation: a
// rotation's flux through the grid's faces (the staircase of the outline, not its normals) gave
// a 4.5 cm crate a torque that spun it to 15 rad/s; the sweeps' forces on its samples turn it
// instead.
void buildOperator(CoarseGrid& cg, const Layout& g, float cellSize, bool bodies) {
    const int nx = g.nx, ny = g.ny;
    const size_t nodes = size_t(nx) * size_t(ny);
    cg.active.clear();
    cg.slot.assign(nodes, -1);
    for (size_t k = 0; k < nodes; ++k) {
        if (cg.type[k] == kFluid) {
            cg.slot[k] = int32_t(cg.active.size());
            cg.active.push_back(uint32_t(k));
        }
    }
    const size_t count = cg.active.size();
    const auto none = int32_t(count);
    cg.diagonal.assign(count, tuning::kCoarseShift);
    cg.neighbours.assign(4 * count, none);
    cg.faceWeight.assign(bodies ? 4 * count : 0, 0.0f);
    cg.bodyFaces.clear();
    for (size_t a = 0; a < count; ++a) {
        const uint32_t k = cg.active[a];
        const int i = int(k % uint32_t(nx)), j = int(k / uint32_t(nx));
        const int di[4] = {-1, 1, 0, 0}, dj[4] = {0, 0, -1, 1};
        // Its open share (1 without bodies: a coefficient times it is the coefficient exactly).
        const float openK = bodies ? cg.open[k] : 1.0f;
        for (int e = 0; e < 4; ++e) {
            const int ii = i + di[e], jj = j + dj[e];
            if (ii < 0 || jj < 0 || ii >= nx || jj >= ny) {
                // Outside the grid: air, the surface where the fill crosses 1/2 on the way.
                cg.diagonal[a] += surfaceCoefficient(cg.fluid[k] + cg.solid[k], 0.0f) * openK;
                continue;
            }
            const size_t m = size_t(jj) * size_t(nx) + size_t(ii);
            if (cg.type[m] != kSolid) { // no flux through solids
                const bool air = cg.type[m] == kAir;
                const float c =
                    air ? surfaceCoefficient(cg.fluid[k] + cg.solid[k], cg.fluid[m] + cg.solid[m])
                        : 1.0f;
                // Next to a body a face is as open as the less open of its two nodes (air
                // beyond: the fluid node's share), so a node the body covers closes by degrees.
                const float open = air || !bodies ? openK : std::min(openK, cg.open[m]);
                cg.diagonal[a] += c * open;
                if (cg.slot[m] >= 0) {
                    cg.neighbours[4 * a + size_t(e)] = cg.slot[m];
                    if (bodies) {
                        cg.faceWeight[4 * a + size_t(e)] = open;
                    }
                }
            } else if (bodies && cg.owner[m] >= 0 && cg.outlined[size_t(cg.owner[m])] == 0) {
                cg.bodyFaces.push_back({uint32_t(a), uint32_t(cg.owner[m]), cellSize * float(di[e]),
                                        cellSize * float(dj[e])});
            }
        }
    }
}

// The unknowns of node k's fluid neighbours (left, right, below, above; at most 4) into
// `slots`; returns how many. A solid node's value is their potential's mean.
int fluidNeighbours(const CoarseGrid& cg, int nx, int ny, size_t k, uint32_t (&slots)[4]) {
    const int i = int(k % size_t(nx)), j = int(k / size_t(nx));
    const int di[4] = {-1, 1, 0, 0}, dj[4] = {0, 0, -1, 1};
    int count = 0;
    for (int e = 0; e < 4; ++e) {
        const int ii = i + di[e], jj = j + dj[e];
        if (ii < 0 || jj < 0 || ii >= nx || jj >= ny) {
            continue;
        }
        const size_t m = size_t(jj) * size_t(nx) + size_t(ii);
        if (cg.type[m] == kFluid) {
            slots[count++] = uint32_t(cg.slot[m]);
        }
    }
    return count;
}

// The node values inside the bodies with an outline as combinations of the unknowns
// (CoarseGrid::extStart, extTerms), and the same for the fluid nodes a body partly covers (open
// below 1: gradientRows blends the two): a node with open fluid neighbours takes the mean, each
// weighted by its open share o_a, of the values extrapolated linearly to it from each
// (psi_a + o_b (psi_a - psi_b), b the next node beyond a: 2 psi_a - psi_b through open water,
// psi_a alone when b is solid, 2 psi_a when b is air), so the potential's hydrostatic slope runs
// on into the body, as it would run on into the water the body displaces, and a neighbour the
// body is closing counts less and less; a node beside air and no open fluid holds 0 (a dry
// top); one deeper inside takes the mean of its neighbours' extrapolations, or 0.
void extendIntoBodies(CoarseGrid& cg, const Layout& g) {
    const int nx = g.nx, ny = g.ny;
    const size_t nodes = size_t(nx) * size_t(ny);
    cg.extStart.assign(2 * nodes, 0);
    cg.extTerms.clear();
    const int di[4] = {-1, 1, 0, 0}, dj[4] = {0, 0, -1, 1};
    const auto inBody = [&](size_t k) {
        return (cg.type[k] == kSolid && cg.owner[k] >= 0 &&
                cg.outlined[size_t(cg.owner[k])] != 0) ||
               (cg.type[k] == kFluid && cg.open[k] < 1.0f);
    };
    const auto node = [&](int i, int j) -> int64_t {
        return i < 0 || j < 0 || i >= nx || j >= ny ? -1 : int64_t(j) * nx + i;
    };
    std::vector<uint32_t> deeper;
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            const auto k = size_t(j) * size_t(nx) + size_t(i);
            if (!inBody(k)) {
                continue;
            }
            const auto begin = uint32_t(cg.extTerms.size());
            float open = 0.0f;
            bool air = false;
            for (int e = 0; e < 4; ++e) {
                const int64_t a = node(i + di[e], j + dj[e]);
                open += a >= 0 && cg.type[size_t(a)] == kFluid ? cg.open[size_t(a)] : 0.0f;
                air = air || a < 0 || cg.type[size_t(a)] == kAir;
            }
            if (open > 0.0f) {
                for (int e = 0; e < 4; ++e) {
                    const int64_t a = node(i + di[e], j + dj[e]);
                    if (a < 0 || cg.type[size_t(a)] != kFluid) {
                        continue;
                    }
                    const float share = cg.open[size_t(a)] / open;
                    const int64_t b = node(i + 2 * di[e], j + 2 * dj[e]);
                    const auto ua = uint32_t(cg.slot[size_t(a)]);
                    if (b >= 0 && cg.type[size_t(b)] == kFluid) {
                        const float ob = cg.open[size_t(b)];
                        cg.extTerms.push_back({ua, (1.0f + ob) * share});
                        cg.extTerms.push_back({uint32_t(cg.slot[size_t(b)]), -ob * share});
                    } else if (b < 0 || cg.type[size_t(b)] == kAir) {
                        cg.extTerms.push_back({ua, 2.0f * share});
                    } else {
                        cg.extTerms.push_back({ua, share});
                    }
                }
            } else if (!air) {
                deeper.push_back(uint32_t(k));
            }
            cg.extStart[2 * k] = begin;
            cg.extStart[2 * k + 1] = uint32_t(cg.extTerms.size());
        }
    }
    // Deeper nodes: the mean of their neighbours' extrapolations (read before any is added).
    for (const uint32_t k : deeper) {
        const int i = int(k % uint32_t(nx)), j = int(k / uint32_t(nx));
        int count = 0;
        for (int e = 0; e < 4; ++e) {
            const int64_t a = node(i + di[e], j + dj[e]);
            count += a >= 0 && cg.extStart[2 * size_t(a) + 1] > cg.extStart[2 * size_t(a)] &&
                             inBody(size_t(a))
                         ? 1
                         : 0;
        }
        const auto begin = uint32_t(cg.extTerms.size());
        for (int e = 0; e < 4 && count > 0; ++e) {
            const int64_t a = node(i + di[e], j + dj[e]);
            if (a < 0 || !inBody(size_t(a))) {
                continue;
            }
            const uint32_t b0 = cg.extStart[2 * size_t(a)], b1 = cg.extStart[2 * size_t(a) + 1];
            if (b1 <= b0 || b1 > begin) { // none, or a deeper node's own
                continue;
            }
            for (uint32_t t = b0; t < b1; ++t) {
                const CoarseGrid::ExtTerm term = cg.extTerms[t];
                cg.extTerms.push_back({term.unknown, term.weight / float(count)});
            }
        }
        cg.extStart[2 * size_t(k)] = begin;
        cg.extStart[2 * size_t(k) + 1] = uint32_t(cg.extTerms.size());
    }
}

// The bodies' Jacobian rows from their gradient weights: node k's weight (wx, wy) times each
// unknown's share of k's value (fluid: itself, or where a body partly covers it, its open share
// o of itself and 1 - o of its extension, so its part moves smoothly to the extension it has
// once it is the body's; inside a body: its extension; a wall's node: the mean of its fluid
// neighbours, as nodeValues reads it; air: none), negated (-integral of grad psi), appended to
// cg.bodyFaces in the weights' order.
void gradientRows(CoarseGrid& cg, const Layout& g) {
    for (const CoarseGrid::NodeWeight& w : cg.bodyGradient) {
        const size_t k = w.node;
        const auto add = [&](uint32_t unknown, float share) {
            cg.bodyFaces.push_back({unknown, w.body, -w.wx * share, -w.wy * share});
        };
        if (cg.type[k] == kFluid && cg.open[k] < 1.0f) {
            const float open = cg.open[k];
            add(uint32_t(cg.slot[k]), open);
            for (uint32_t t = cg.extStart[2 * k]; t < cg.extStart[2 * k + 1]; ++t) {
                add(cg.extTerms[t].unknown, cg.extTerms[t].weight * (1.0f - open));
            }
        } else if (cg.type[k] == kFluid) {
            add(uint32_t(cg.slot[k]), 1.0f);
        } else if (cg.type[k] == kSolid && cg.owner[k] >= 0 &&
                   cg.outlined[size_t(cg.owner[k])] != 0) {
            for (uint32_t t = cg.extStart[2 * k]; t < cg.extStart[2 * k + 1]; ++t) {
                add(cg.extTerms[t].unknown, cg.extTerms[t].weight);
            }
        } else if (cg.type[k] == kSolid) {
            uint32_t found[4];
            const int count = fluidNeighbours(cg, g.nx, g.ny, k, found);
            for (int c = 0; c < count; ++c) {
                add(found[c], 1.0f / float(count));
            }
        }
    }
}

// Per body, how far the solve moves it per unit of G^T psi: rho0 depth / mass (1/m^2), rho0
// the liquid's density (fluidDensity).
std::vector<double> bodyMobility(const WorldState& s, double rho) {
    std::vector<double> mobility(s.bodies.size());
    for (size_t b = 0; b < s.bodies.size(); ++b) {
        mobility[b] = rho * double(s.def.depth) / double(s.bodies[b].mass);
    }
    return mobility;
}

// q += G M^-1 G^T d: the flux of the bodies' displacement under d's pressure (bodySum is
// scratch, two per body).
void addBodyFlux(const CoarseGrid& cg, const std::vector<double>& mobility, const float* d,
                 float* q, std::vector<double>& bodySum) {
    bodyForce(cg, d, bodySum);
    for (size_t k = 0; k < bodySum.size(); ++k) {
        bodySum[k] *= mobility[k / 2];
    }
    for (const CoarseGrid::BodyFace& f : cg.bodyFaces) {
        q[f.unknown] +=
            float(double(f.gx) * bodySum[2 * f.body] + double(f.gy) * bodySum[2 * f.body + 1]);
    }
}

// The bodies' share of the solve: each moves by share M^-1 G^T psi (rho0 depth over its mass), at
// most kCoarseBodyMaxMove of a coarse cell per sub-step, taken as a velocity change from the
// sub-step's start (placeSamples offsets its samples from then on) and an impulse, its mass times
// its move added to `momentum` (kg m). Returns true when some body moved.
bool moveBodies(WorldState& s, const CoarseGrid& cg, const std::vector<double>& mobility,
                std::vector<double>& bodySum, const CoarseSettings& settings, const float* psi,
                double momentum[2]) {
    bodyForce(cg, psi, bodySum);
    const double span = double(settings.endTime) - double(settings.startTime);
    if (!(span > 0.0)) {
        return false;
    }
    const double limit = double(tuning::kCoarseBodyMaxMove) * double(settings.cellSize);
    bool moved = false;
    for (size_t b = 0; b < s.bodies.size(); ++b) {
        BodyState& body = s.bodies[b];
        double dx = double(settings.share) * mobility[b] * bodySum[2 * b];
        double dy = double(settings.share) * mobility[b] * bodySum[2 * b + 1];
        const double len = std::sqrt(dx * dx + dy * dy);
        if (!std::isfinite(len) || len == 0.0) {
            continue;
        }
        if (len > limit) {
            dx *= limit / len;
            dy *= limit / len;
        }
        const double dvx = dx / span, dvy = dy / span;
        body.dvx += float(dvx);
        body.dvy += float(dvy);
        body.ox -= float(dvx * double(settings.startTime));
        body.oy -= float(dvy * double(settings.startTime));
        body.impulseX += double(body.mass) * dvx;
        body.impulseY += double(body.mass) * dvy;
        momentum[0] += double(body.mass) * dx;
        momentum[1] += double(body.mass) * dy;
        moved = true;
    }
    return moved;
}

// True when node k holds some fill of a boundary's samples other than the bodies' (more than a
// thousandth of a node: the bodies' part is a difference of float sums): liquid there touches
// a wall, which takes its share of the coarse solve's impulse.
bool wallFilled(const CoarseGrid& cg, size_t k, bool bodies) {
    return cg.solid[k] - (bodies ? cg.bodyFill[k] : 0.0f) > 1e-3f;
}

// True when some fluid node touches a wall (wallFilled).
bool touchesWall(const CoarseGrid& cg, bool bodies) {
    return std::any_of(cg.active.begin(), cg.active.end(),
                       [&](uint32_t k) { return wallFilled(cg, k, bodies); });
}

// Where no wall is in reach, the coarse moves keep the momentum: the particles' moves (mass
// times move) and the bodies' (`bodies`, kg m) sum to zero once the mass-weighted mean is taken
// off every particle's move. The moves are a bilinear gradient read at the particles, which near
// a free surface does not sum to zero by itself (docs/position_based_method.md, "Coarse
// correction").
void keepMomentum(WorldState& s, const double bodies[2]) {
    Particles& p = s.particles;
    PositionBasedScratch& x = s.pbfScratch;
    struct Sum {
        double mx, my, m;
    };
    const Sum sum = blockReduce<Sum>(
        s.tasks, p.size(), Sum{0.0, 0.0, 0.0},
        [&](uint32_t b, uint32_t e) {
            Sum r{0.0, 0.0, 0.0};
            for (uint32_t i = b; i < e; ++i) {
                r.mx += double(p.mass[i]) * double(x.cx[i]);
                r.my += double(p.mass[i]) * double(x.cy[i]);
                r.m += double(p.mass[i]);
            }
            return r;
        },
        [](Sum a, const Sum& b) {
            return Sum{a.mx + b.mx, a.my + b.my, a.m + b.m};
        });
    if (!(sum.m > 0.0)) {
        return;
    }
    const auto dx = float((sum.mx + bodies[0]) / sum.m), dy = float((sum.my + bodies[1]) / sum.m);
    if (!std::isfinite(dx) || !std::isfinite(dy) || (dx == 0.0f && dy == 0.0f)) {
        return;
    }
    parallelFor(s.tasks, p.size(), kMoveGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            x.cx[i] -= dx;
            x.cy[i] -= dy;
            p.px[i] = x.ox[i] + x.cx[i];
            p.py[i] = x.oy[i] + x.cy[i];
        }
    });
}

// The regions of cg.region and cg.regionWalled (see CoarseGrid): each unknown not yet labelled
// starts a region, which a search through the fluid neighbours fills, in unknown order.
void labelRegions(CoarseGrid& cg) {
    const size_t count = cg.active.size();
    const auto none = int32_t(count);
    cg.region.assign(count, -1);
    cg.regionWalled.clear();
    std::vector<uint32_t>& stack = cg.regionStack;
    for (size_t a = 0; a < count; ++a) {
        if (cg.region[a] >= 0) {
            continue;
        }
        const auto id = int32_t(cg.regionWalled.size());
        uint8_t walled = 0;
        cg.region[a] = id;
        stack.assign(1, uint32_t(a));
        while (!stack.empty()) {
            const uint32_t u = stack.back();
            stack.pop_back();
            walled |= wallFilled(cg, cg.active[u], false) ? 1 : 0;
            for (int e = 0; e < 4; ++e) {
                const int32_t v = cg.neighbours[4 * size_t(u) + size_t(e)];
                if (v != none && cg.region[size_t(v)] < 0) {
                    cg.region[size_t(v)] = id;
                    stack.push_back(uint32_t(v));
                }
            }
        }
        cg.regionWalled.push_back(walled);
    }
}

// keepMomentum for each region away from walls on its own (worlds without bodies): a region's
// particles (those whose cell's first fluid corner lies in it) sum their moves' momentum, and
// its mass-weighted mean comes off each of their moves. Kept for the whole world at once, the
// means of two drops' moves (each a bilinear gradient that does not sum to zero near its free
// surface) mixed, and two 8 cm drops at rest in zero gravity pushed each other apart, 1.2 cm
// each in 5 s. Blocks of kReduceBlock particles sum their runs of one region; the blocks' sums
// are added in block order, so the result does not depend on the number of workers.
void keepRegionMomentum(WorldState& s, std::span<const uint32_t> order) {
    CoarseGrid& cg = s.coarse;
    const size_t regions = cg.regionWalled.size();
    if (std::find(cg.regionWalled.begin(), cg.regionWalled.end(), uint8_t(0)) ==
        cg.regionWalled.end()) {
        return; // every region touches a wall, which takes its share
    }
    Particles& p = s.particles;
    PositionBasedScratch& x = s.pbfScratch;
    const uint32_t n = p.size();
    const Layout& g = cg.layout;
    cg.particleRegion.resize(n);
    using Run = CoarseGrid::RegionRun;
    const uint32_t blocks = (n + kReduceBlock - 1) / kReduceBlock;
    std::vector<std::vector<Run>>& runs = cg.regionRuns;
    if (runs.size() < blocks) {
        runs.resize(blocks);
    }
    parallelFor(s.tasks, blocks, 1, [&](uint32_t b0, uint32_t b1, uint32_t) {
        for (uint32_t b = b0; b < b1; ++b) {
            std::vector<Run>& out = runs[b];
            out.clear();
            const uint32_t end = std::min(n, (b + 1) * kReduceBlock);
            for (uint32_t i = b * kReduceBlock; i < end; ++i) {
                const size_t k = cg.cell[order.empty() ? i : order[i]];
                const size_t corner[4] = {k, k + 1, k + size_t(g.nx), k + size_t(g.nx) + 1};
                int32_t r = -1;
                for (int c = 0; c < 4 && r < 0; ++c) {
                    const int32_t slot = cg.slot[corner[c]];
                    r = slot >= 0 ? cg.region[size_t(slot)] : -1;
                }
                cg.particleRegion[i] = r;
                if (r < 0 || cg.regionWalled[size_t(r)] != 0) {
                    continue;
                }
                if (out.empty() || out.back().region != r) {
                    out.push_back(Run{r, 0.0, 0.0, 0.0});
                }
                Run& run = out.back();
                run.mx += double(p.mass[i]) * double(x.cx[i]);
                run.my += double(p.mass[i]) * double(x.cy[i]);
                run.m += double(p.mass[i]);
            }
        }
    });
    std::vector<double>& sum = cg.regionSum;
    sum.assign(3 * regions, 0.0);
    for (uint32_t b = 0; b < blocks; ++b) {
        for (const Run& run : runs[b]) {
            sum[3 * size_t(run.region) + 0] += run.mx;
            sum[3 * size_t(run.region) + 1] += run.my;
            sum[3 * size_t(run.region) + 2] += run.m;
        }
    }
    // Per region the mean move (x, y), 0 where none is taken off.
    std::vector<float>& mean = cg.regionMean;
    mean.assign(2 * regions, 0.0f);
    bool any = false;
    for (size_t r = 0; r < regions; ++r) {
        const double m = sum[3 * r + 2];
        if (cg.regionWalled[r] != 0 || !(m > 0.0)) {
            continue;
        }
        const auto dx = float(sum[3 * r] / m), dy = float(sum[3 * r + 1] / m);
        if (std::isfinite(dx) && std::isfinite(dy)) {
            mean[2 * r] = dx;
            mean[2 * r + 1] = dy;
            any = any || dx != 0.0f || dy != 0.0f;
        }
    }
    if (!any) {
        return;
    }
    parallelFor(s.tasks, n, kMoveGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            const int32_t r = cg.particleRegion[i];
            if (r < 0) {
                continue;
            }
            x.cx[i] -= mean[2 * size_t(r)];
            x.cy[i] -= mean[2 * size_t(r) + 1];
            p.px[i] = x.ox[i] + x.cx[i];
            p.py[i] = x.oy[i] + x.cy[i];
        }
    });
}

} // namespace

// The coarse grid over the particles' bounds, a cell beyond them on every side; false when it
// would hold more than kMaxNodes.
bool coarseLayout(const WorldState& s, float cellSize, Layout& g) {
    const Particles& p = s.particles;
    const uint32_t n = p.size();
    struct Bounds {
        float lx, hx, ly, hy;
    };
    const float inf = std::numeric_limits<float>::infinity();
    const Bounds bounds = blockReduce<Bounds>(
        s.tasks, n, Bounds{inf, -inf, inf, -inf},
        [&](uint32_t b, uint32_t e) {
            Bounds r{inf, -inf, inf, -inf};
            for (uint32_t i = b; i < e; ++i) {
                r.lx = std::min(r.lx, p.px[i]);
                r.hx = std::max(r.hx, p.px[i]);
                r.ly = std::min(r.ly, p.py[i]);
                r.hy = std::max(r.hy, p.py[i]);
            }
            return r;
        },
        [](Bounds a, const Bounds& b) {
            return Bounds{std::min(a.lx, b.lx), std::max(a.hx, b.hx), std::min(a.ly, b.ly),
                          std::max(a.hy, b.hy)};
        });
    float lx = bounds.lx, hx = bounds.hx, ly = bounds.ly, hy = bounds.hy;
    // The bodies' samples widen it, up to kCoarseBodyReach cells beyond the particles: a body
    // the grid cut would lose the fill of its part beyond the cut, and the cut moves with the
    // particles' top.
    const float reach = tuning::kCoarseBodyReach * cellSize;
    const float rx0 = lx - reach, rx1 = hx + reach, ry0 = ly - reach, ry1 = hy + reach;
    for (const BodyState& body : s.bodies) {
        for (uint32_t k = body.sampleBegin; k < body.sampleEnd; ++k) {
            const float x = std::clamp(s.samples.px[k], rx0, rx1);
            const float y = std::clamp(s.samples.py[k], ry0, ry1);
            lx = std::min(lx, x);
            hx = std::max(hx, x);
            ly = std::min(ly, y);
            hy = std::max(hy, y);
        }
    }
    g.invH = 1.0f / cellSize;
    g.x0 = lx - cellSize;
    g.y0 = ly - cellSize;
    const double spanX = double(hx - lx) / cellSize + 3.0, spanY = double(hy - ly) / cellSize + 3.0;
    if (!(spanX * spanY < double(kMaxNodes))) {
        return false;
    }
    g.nx = int(spanX);
    g.ny = int(spanY);
    return true;
}

// The particles' volume splatted bilinearly onto the nodes (cg.fluid), with each particle's
// cell and fractions kept for the move.
void fillFluid(WorldState& s, const Layout& g) {
    Particles& p = s.particles;
    const uint32_t n = p.size();
    CoarseGrid& cg = s.coarse;
    const float invArea = g.invH * g.invH;
    // Each particle's cell and bilinear fractions (the move below reads them too: the positions
    // do not change in between), then the fill band by band of node rows: a band adds the
    // particles that reach its rows in index order, so each node sums in the same order
    // whatever the bands.
    cg.cell.resize(n);
    cg.fx.resize(n);
    cg.fy.resize(n);
    parallelFor(s.tasks, n, kMoveGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            int ci = 0, cj = 0;
            g.cell(p.px[i], p.py[i], ci, cj, cg.fx[i], cg.fy[i]);
            cg.cell[i] = uint32_t(cj) * uint32_t(g.nx) + uint32_t(ci);
        }
    });
    const uint32_t bands = std::clamp(s.threads(), 1u, uint32_t(g.ny));
    parallelFor(s.tasks, bands, 1, [&](uint32_t b0, uint32_t b1, uint32_t) {
        for (uint32_t band = b0; band < b1; ++band) {
            const size_t lo = size_t(g.ny) * band / bands * size_t(g.nx);
            const size_t hi = size_t(g.ny) * (band + 1) / bands * size_t(g.nx);
            for (uint32_t i = 0; i < n; ++i) {
                const size_t k = cg.cell[i];
                if (k + size_t(g.nx) + 1 < lo || k >= hi) {
                    continue;
                }
                // The volume from the material (fillMaterialChannels' formula): the fill may
                // run before the channels follow a sort or a change of the particles.
                const MaterialConstants& mc = s.constants[p.material[i]];
                const float volume = mc.massPerDepth / mc.restDensity;
                const float amount = volume * invArea, fx = cg.fx[i], fy = cg.fy[i];
                const size_t corner[4] = {k, k + 1, k + size_t(g.nx), k + size_t(g.nx) + 1};
                const float weight[4] = {amount * (1.0f - fx) * (1.0f - fy),
                                         amount * fx * (1.0f - fy), amount * (1.0f - fx) * fy,
                                         amount * fx * fy};
                for (int c4 = 0; c4 < 4; ++c4) {
                    if (corner[c4] >= lo && corner[c4] < hi) {
                        cg.fluid[corner[c4]] += weight[c4];
                    }
                }
            }
        }
    });
}

// The operator's face coefficients per unknown (CoarseGrid::faceWeight), or null where every face
// is 1 (a world without bodies: buildOperator keeps none).
namespace {
const float* faceWeights(const CoarseGrid& cg) {
    return cg.faceWeight.empty() ? nullptr : cg.faceWeight.data();
}
} // namespace

// Conjugate gradients, preconditioned by a multigrid V-cycle of the grid part of the operator
// (coarse_multigrid.h; it replaced MIC(0), which took 3-5 times the iterations and twice the
// time from 16,000 particles up: docs/position_based_method.md, "Coarse correction"), for the
// potential psi of the active unknowns (with the bodies' terms when `coupled`: the
// preconditioner of the grid part stays symmetric positive definite, and the solve converges
// for the whole operator); bodySum gathers the bodies' flux. `nx`: nodes per row of the grid.
// Returns cg.psi's data.
float* solvePotential(CoarseGrid& cg, int nx, const std::vector<double>& mobility,
                      std::vector<double>& bodySum, bool coupled, uint32_t maxIterations) {
    const size_t count = cg.active.size();
    const auto none = int32_t(count);
    // (A psi)_a = diagonal_a psi_a - sum of the fluid neighbours' psi (air holds 0); the
    // diagonal's small shift keeps a closed container full of fluid solvable. The dot products
    // sum in double over kDotLanes interleaved partial sums (unknown a into partial a mod
    // kDotLanes), combined in a fixed order at the end: the same result on every build and
    // worker count, and independent chains of additions instead of one that waits on the
    // previous addition's latency.
    const size_t padded = (count + kDotLanes - 1) / kDotLanes * kDotLanes;
    const size_t slots = std::max(padded, count + 1);
    cg.psi.assign(padded, 0.0f);
    cg.r.assign(padded, 0.0f);
    cg.q.assign(padded, 0.0f);
    cg.z.assign(slots, 0.0f);
    for (size_t a = 0; a < count; ++a) {
        cg.r[a] = cg.rhs[cg.active[a]];
    }
    cg.multigrid.build(count, cg.active.data(), uint32_t(nx), cg.diagonal.data(),
                       cg.neighbours.data(), faceWeights(cg));
    // d keeps slot `count` at 0 for the missing neighbour, and zeros up to the padding.
    cg.d.assign(slots, 0.0f);
    cg.diagonal.resize(padded, 0.0f);
    cg.neighbours.resize(4 * padded, none);
    if (!cg.faceWeight.empty()) {
        cg.faceWeight.resize(4 * padded, 0.0f);
    }
    const float* w = faceWeights(cg);
    float* psi = cg.psi.data();
    float* r = cg.r.data();
    float* d = cg.d.data();
    float* q = cg.q.data();
    float* z = cg.z.data();
    const int32_t* nb = cg.neighbours.data();
    const float* diagonal = cg.diagonal.data();
    // q = A x (x keeps slot `count` and the padding at 0), and x.q.
    const auto apply = [&](const float* x) {
        double lanes[kDotLanes] = {};
        for (size_t a0 = 0; a0 < padded; a0 += kDotLanes) {
            for (size_t l = 0; l < kDotLanes; ++l) {
                const size_t a = a0 + l;
                const int32_t* n4 = nb + 4 * a;
                float acc = diagonal[a] * x[a];
                if (w != nullptr) {
                    const float* w4 = w + 4 * a;
                    acc -= w4[0] * x[size_t(n4[0])];
                    acc -= w4[1] * x[size_t(n4[1])];
                    acc -= w4[2] * x[size_t(n4[2])];
                    acc -= w4[3] * x[size_t(n4[3])];
                } else {
                    acc -= x[size_t(n4[0])];
                    acc -= x[size_t(n4[1])];
                    acc -= x[size_t(n4[2])];
                    acc -= x[size_t(n4[3])];
                }
                q[a] = acc;
                lanes[l] += double(x[a]) * double(acc);
            }
        }
        if (coupled) {
            addBodyFlux(cg, mobility, x, q, bodySum);
            return laneDot(x, q, padded);
        }
        return combineLanes(lanes);
    };
    // The solve ends at kCoarseResidual of the start's residual.
    double rr = laneDot(r, r, padded);
    const double stop = rr * double(tuning::kCoarseResidual) * double(tuning::kCoarseResidual);
    cg.multigrid.apply(r, z);
    std::copy(z, z + count, d);
    double rz = laneDot(r, z, padded);
    for (uint32_t it = 0; it < maxIterations && rr > stop; ++it) {
        // q = A d, and d.q (padding slots: diagonal 0 and d 0, so q 0).
        const double dq = apply(d);
        if (!(dq > 0.0)) {
            break;
        }
        // psi += alpha d, r -= alpha q, and r.r.
        const auto alpha = float(rz / dq);
        double nextLanes[kDotLanes] = {};
        for (size_t a0 = 0; a0 < padded; a0 += kDotLanes) {
            for (size_t l = 0; l < kDotLanes; ++l) {
                const size_t a = a0 + l;
                psi[a] += alpha * d[a];
                r[a] -= alpha * q[a];
                nextLanes[l] += double(r[a]) * double(r[a]);
            }
        }
        rr = combineLanes(nextLanes);
        if (!(rr > stop)) {
            break;
        }
        cg.multigrid.apply(r, z);
        const double next = laneDot(r, z, padded);
        if (!(rz > 0.0)) {
            break;
        }
        const auto beta = float(next / rz);
        rz = next;
        for (size_t a = 0; a < padded; ++a) {
            d[a] = z[a] + beta * d[a];
        }
    }
    return psi;
}

// The node values the move reads, into cg.rhs (free after the solve).
const std::vector<float>& nodeValues(CoarseGrid& cg, int nx, int ny) {
    // Node values for the gradient: fluid nodes their potential, solid nodes the mean of their
    // fluid neighbours' (no flux through solids), air 0. Nodes inside bodies too: with the
    // bodies' extension the particles beside them jostled them (docs/position_based.md, "Bodies
    // in the coarse solve").
    std::vector<float>& value = cg.rhs; // free now
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            const size_t k = size_t(j) * size_t(nx) + size_t(i);
            if (cg.type[k] == kFluid) {
                value[k] = cg.psi[size_t(cg.slot[k])];
                continue;
            }
            float sum = 0.0f;
            uint32_t found[4];
            const int count = cg.type[k] == kSolid ? fluidNeighbours(cg, nx, ny, k, found) : 0;
            for (int c = 0; c < count; ++c) {
                sum += cg.psi[found[c]];
            }
            value[k] = count > 0 ? sum / float(count) : 0.0f;
        }
    }
    return value;
}

bool pbfCoarseFill(WorldState& s, const PbfConstants& c, const CoarseSettings& settings) {
    CoarseGrid& cg = s.coarse;
    cg.filled = cg.solved = cg.coupled = false;
    const uint32_t n = s.particles.size();
    const float cellSize = settings.cellSize;
    if (n == 0 || !(settings.share > 0.0f)) {
        return false;
    }
    Layout& g = cg.layout;
    if (!coarseLayout(s, cellSize, g)) {
        return false;
    }
    const size_t nodes = size_t(g.nx) * size_t(g.ny);
    cg.fluid.assign(nodes, 0.0f);
    cg.solid.assign(nodes, 0.0f);
    fillFluid(s, g);
    const float invArea = g.invH * g.invH;
    const Samples& w = s.samples;
    const float gx1 = g.x0 + float(g.nx - 1) * cellSize, gy1 = g.y0 + float(g.ny - 1) * cellSize;
    for (size_t k = 0; k < w.px.size(); ++k) {
        const float x = w.px[k], y = w.py[k];
        if (x >= g.x0 && x <= gx1 && y >= g.y0 && y <= gy1) {
            splat(cg.solid, g, x, y, c.sampleVolume * invArea);
        }
    }
    // The liquid's density, read here beside the particles (the solve must not: the sort may be
    // moving them), and only where bodies or several rest densities need it.
    const bool oneDensity = oneRestDensity(s);
    const double rho = oneDensity && s.bodies.empty() ? 0.0 : fluidDensity(s);
    setMoveScale(cg, s, oneDensity, rho);
    if (!s.bodies.empty()) {
        markOwners(s, g, c.sampleVolume * invArea, settings.endTime);
        cg.mobility = bodyMobility(s, rho);
    } else {
        cg.mobility.clear();
    }
    cg.filled = true;
    return true;
}

void pbfCoarseSolve(WorldState& s, const CoarseSettings& settings) {
    CoarseGrid& cg = s.coarse;
    if (!cg.filled) {
        return;
    }
    const Layout& g = cg.layout;
    const float cellSize = settings.cellSize;
    const size_t nodes = size_t(g.nx) * size_t(g.ny);
    const bool bodies = !s.bodies.empty();
    if (!classifyNodes(cg, nodes, settings.tolerance, cellSize * cellSize, bodies)) {
        return;
    }
    buildOperator(cg, g, cellSize, bodies);
    if (bodies) {
        extendIntoBodies(cg, g);
        gradientRows(cg, g);
    } else {
        labelRegions(cg);
    }
    cg.coupled = !cg.bodyFaces.empty();
    cg.bodySum.assign(cg.coupled ? 2 * s.bodies.size() : 0, 0.0);
    solvePotential(cg, g.nx, cg.mobility, cg.bodySum, cg.coupled, settings.maxIterations);
    nodeValues(cg, g.nx, g.ny);
    cg.solved = true;
}

bool pbfCoarseMove(WorldState& s, const CoarseSettings& settings, std::span<const uint32_t> order) {
    CoarseGrid& cg = s.coarse;
    if (!cg.solved) {
        return false;
    }
    Particles& p = s.particles;
    const uint32_t n = p.size();
    const Layout& g = cg.layout;
    const std::vector<float>& value = cg.rhs; // nodeValues' result
    // Each particle's move reads only the node values: the particles split over the workers.
    // The fill kept each particle's cell and fractions at its index then; `order` maps each
    // index now to that one (empty: the same).
    parallelFor(s.tasks, n, kMoveGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            moveParticle(p, s.pbfScratch, cg, g, value.data(), settings.share, i,
                         order.empty() ? i : order[i]);
        }
    });
    double bodyMomentum[2] = {0.0, 0.0};
    const bool bodies = !s.bodies.empty();
    const bool moved = cg.coupled && moveBodies(s, cg, cg.mobility, cg.bodySum, settings,
                                                cg.psi.data(), bodyMomentum);
    if (!bodies) {
        keepRegionMomentum(s, order);
    } else if (!touchesWall(cg, bodies)) {
        keepMomentum(s, bodyMomentum);
    }
    return moved;
}

} // namespace fluid::detail
