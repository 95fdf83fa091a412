#include "forces.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>

#include "collider_contact.h"
#include "errors.h"
#include "thermal_kernel.h"

namespace globular {

namespace {

constexpr std::size_t kGrain = 256;

/// Adds the force of @p j on @p i to @p f.
inline void addPair(const Globules& g, const PairForce& pair, std::size_t i, std::size_t j,
                    float f[3]) {
    pair.accumulate(g.px[i] - g.px[j], g.py[i] - g.py[j], g.pz[i] - g.pz[j],
                    g.vx[i] - g.vx[j], g.vy[i] - g.vy[j], g.vz[i] - g.vz[j],
                    g.radius[i] + g.radius[j], f);
}

/// The smallest and largest radius.
std::pair<float, float> radiusRange(const Globules& g) {
    if (g.empty()) return {1.0f, 1.0f};
    using Range = std::pair<float, float>;
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, g.size(), 4096), Range{g.radius[0], g.radius[0]},
        [&](const tbb::blocked_range<std::size_t>& r, Range m) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                m = {std::min(m.first, g.radius[i]), std::max(m.second, g.radius[i])};
            }
            return m;
        },
        [](Range a, Range b) { return Range{std::min(a.first, b.first), std::max(a.second, b.second)}; });
}

}  // namespace

void pairForcesAllPairs(const Globules& g, const PairForce& pair, Accelerations& forces) {
    pairForcesAllPairs(g, PairTable(pair), forces);
}

std::pair<float, float> buildGrid(const Globules& g, const PairForce& pair, NeighborGrid& grid) {
    const auto range = radiusRange(g);
    grid.build(g.px.data(), g.py.data(), g.pz.data(), g.size(), pair.cutoff(2.0f * range.second));
    return range;
}

namespace {

/// One grid cell's members in a range of globules in grid order, and what is around them.
struct CellGroup {
    std::size_t last = 0;      ///< the members are [first, last)
    float lo[3], hi[3];        ///< the members' bounding box
    int runCount = 0;          ///< runs of candidates in the 27 cells around
    std::size_t total = 0;     ///< globules in those runs
    std::array<NeighborGrid::Run, NeighborGrid::kMaxRuns> runs;
};

/// The group of globule @p first's cell within [first, end) of @p s.
void groupAt(const NeighborGrid& grid, const Globules& s, std::size_t first, std::size_t end,
             NeighborGrid::RunCursor& cursor, CellGroup& group) {
    const auto cell = grid.cellOf(s.px[first], s.py[first], s.pz[first]);
    const float start[3] = {s.px[first], s.py[first], s.pz[first]};
    for (int a = 0; a < 3; ++a) group.lo[a] = group.hi[a] = start[a];
    std::size_t last = first + 1;
    for (; last < end && grid.cellOf(s.px[last], s.py[last], s.pz[last]) == cell; ++last) {
        const float p[3] = {s.px[last], s.py[last], s.pz[last]};
        for (int a = 0; a < 3; ++a) {
            group.lo[a] = std::min(group.lo[a], p[a]);
            group.hi[a] = std::max(group.hi[a], p[a]);
        }
    }
    group.last = last;
    group.runCount = grid.neighborRuns(s.px[first], s.py[first], s.pz[first], cursor, group.runs);
    group.total = 0;
    for (int b = 0; b < group.runCount; ++b) group.total += group.runs[b].second - group.runs[b].first;
}

/// Sums forces on the globules [begin, end) of @p s, which are in grid order. Globules
/// that share a cell are consecutive: they are handled as a group with shared candidates.
template <int M, int N>
void sumRange(const PairForce& pair, const NeighborGrid& grid, const Globules& s,
              bool uniformRadius, std::size_t begin, std::size_t end, Accelerations& forces) {
    const GlobuleArrays arrays{s.px.data(), s.py.data(), s.pz.data(),    s.vx.data(),
                               s.vy.data(), s.vz.data(), s.radius.data()};
    const float reach = pair.cutoff(1.0f), reach2 = reach * reach;
    // The cell edge is the largest reach of any pair; a hair more keeps the box test
    // conservative under rounding (the pair test decides).
    const float groupReach = grid.cellSize() * 1.0001f;
    NeighborGrid::RunCursor cursor;
    CellGroup group;
    GroupCandidates candidates;
    candidates.uniformRadius = uniformRadius;
    NeighborBatch batch;
    for (std::size_t first = begin; first < end;) {
        groupAt(grid, s, first, end, cursor, group);
        const std::size_t last = group.last;
        candidates.reserve(group.total);
        candidates.count = 0;
        for (int b = 0; b < group.runCount; ++b) {
            collectGroupCandidates(arrays, group.runs[b].first, group.runs[b].second, group.lo,
                                   group.hi, groupReach, candidates);
        }
        batch.reserve(candidates.count);
        for (std::size_t k = first; k < last; ++k) {
            batch.count = 0;
            collectNeighbors(candidates, s.px[k], s.py[k], s.pz[k], s.vx[k], s.vy[k], s.vz[k],
                             s.radius[k], reach2, batch);
            float fx = 0, fy = 0, fz = 0;
            sumBatch<M, N>(pair, batch, fx, fy, fz);
            forces.x[k] = fx;
            forces.y[k] = fy;
            forces.z[k] = fz;
        }
        first = last;
    }
}

using SumRange = void (*)(const PairForce&, const NeighborGrid&, const Globules&, bool,
                          std::size_t, std::size_t, Accelerations&);

/// What @p instance gives for the pair's exponents: instance.operator()<M, N>() with the
/// exponents unrolled for the pairs the paper uses, <0, 0> (pow()) otherwise.
template <typename Instance>
auto forExponents(const PairForce& pair, Instance&& instance) {
    if (pair.integerExponents) {
        const int m = pair.mInt, n = pair.nInt;
        if (m == 5 && n == 3) return instance.template operator()<5, 3>();
        if (m == 5 && n == 1) return instance.template operator()<5, 1>();
        if (m == 5 && n == 4) return instance.template operator()<5, 4>();
        if (m == 10 && n == 3) return instance.template operator()<10, 3>();
        if (m == 7 && n == 5) return instance.template operator()<7, 5>();
        if (m == 12 && n == 6) return instance.template operator()<12, 6>();
    }
    return instance.template operator()<0, 0>();
}

/// The force loop for the material's exponents.
SumRange kernelFor(const PairForce& pair) {
    return forExponents(pair, []<int M, int N>() { return SumRange(sumRange<M, N>); });
}

}  // namespace

void pairForcesSorting(Globules& g, const PairForce& pair, NeighborWorkspace& w,
                       Accelerations& forces) {
    const std::size_t n = g.size();
    forces.resize(n);
    if (n == 0) return;
    const auto [smallest, largest] = buildGrid(g, pair, w.grid);
    w.largestRadius = largest;
    // The accelerations are about to be overwritten: their array is the reorder's scratch
    // (no extra 4 bytes per globule).
    g.permute(w.grid.sortedOrder(), forces.x);
    const SumRange sum = kernelFor(pair);
    const bool uniformRadius = smallest == largest;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          sum(pair, w.grid, g, uniformRadius, r.begin(), r.end(), forces);
                      });
}

namespace {

/// One pair's sum over a batch: sumBatch for the pair's exponents.
using SumBatch = void (*)(const PairForce&, const NeighborBatch&, float&, float&, float&);

SumBatch batchKernelFor(const PairForce& pair) {
    return forExponents(pair, []<int M, int N>() { return SumBatch(sumBatch<M, N>); });
}

/// sumRange for several materials: a cell's candidates gathered once per material, and
/// each member summed over each material's with that pair's constants and kernel, in
/// material order (the same order on any thread count).
void sumRangeMixed(const PairTable& pairs, const std::vector<SumBatch>& kernels,
                   const NeighborGrid& grid, const Globules& s, bool uniformRadius,
                   std::size_t begin, std::size_t end, Accelerations& forces) {
    const GlobuleArrays arrays{s.px.data(), s.py.data(), s.pz.data(),    s.vx.data(),
                               s.vy.data(), s.vz.data(), s.radius.data()};
    const std::size_t kinds = pairs.materials();
    const float groupReach = grid.cellSize() * 1.0001f;
    NeighborGrid::RunCursor cursor;
    CellGroup group;
    std::vector<GroupCandidates> candidates(kinds);
    for (GroupCandidates& c : candidates) c.uniformRadius = uniformRadius;
    NeighborBatch batch;
    for (std::size_t first = begin; first < end;) {
        groupAt(grid, s, first, end, cursor, group);
        const std::size_t last = group.last;
        for (GroupCandidates& c : candidates) {
            c.reserve(group.total);
            c.count = 0;
        }
        for (int b = 0; b < group.runCount; ++b) {
            collectGroupCandidatesByMaterial(arrays, group.runs[b].first, group.runs[b].second,
                                             group.lo, group.hi, groupReach, s.material.data(),
                                             candidates);
        }
        batch.reserve(group.total);
        for (std::size_t k = first; k < last; ++k) {
            const std::size_t mine = s.material[k];
            float fx = 0, fy = 0, fz = 0;
            for (std::size_t kind = 0; kind < kinds; ++kind) {
                if (candidates[kind].count == 0) continue;
                const PairForce& pair = pairs(mine, kind);
                const float reach = pair.cutoff(1.0f);
                batch.count = 0;
                collectNeighbors(candidates[kind], s.px[k], s.py[k], s.pz[k], s.vx[k], s.vy[k],
                                 s.vz[k], s.radius[k], reach * reach, batch);
                kernels[mine * kinds + kind](pair, batch, fx, fy, fz);
            }
            forces.x[k] = fx;
            forces.y[k] = fy;
            forces.z[k] = fz;
        }
        first = last;
    }
}

}  // namespace

void pairForcesSorting(Globules& g, const PairTable& pairs, NeighborWorkspace& w,
                       Accelerations& forces) {
    const std::size_t n = g.size();
    forces.resize(n);
    if (n == 0) return;
    if (g.material.size() != n) throw Error("several materials, but globules without one");
    const auto [smallest, largest] = radiusRange(g);
    w.largestRadius = largest;
    w.grid.build(g.px.data(), g.py.data(), g.pz.data(), n, pairs.cutoff(2.0f * largest));
    g.permute(w.grid.sortedOrder(), forces.x);
    std::vector<SumBatch> kernels;
    for (std::size_t a = 0; a < pairs.materials(); ++a) {
        for (std::size_t b = 0; b < pairs.materials(); ++b) kernels.push_back(batchKernelFor(pairs(a, b)));
    }
    const bool uniformRadius = smallest == largest;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          sumRangeMixed(pairs, kernels, w.grid, g, uniformRadius, r.begin(),
                                        r.end(), forces);
                      });
}

namespace {

/// The blended force sum for a pair's exponents.
using SumBlended = void (*)(const ThermalPair&, float, const NeighborBatch&, float&, float&, float&);

/// What the thermal loop runs for one pair of materials in each phase.
struct ThermalKernel {
    ThermalPair pair;
    float reach2 = 0;  ///< (the pair's reach in both phases)^2, in units of r_i + r_j
    SumBatch solid, liquid;
    SumBlended blended;

    explicit ThermalKernel(const ThermalPair& p)
        : pair(p),
          solid(batchKernelFor(p.solid)),
          liquid(batchKernelFor(p.liquid)),
          blended(sumBlendedBatch<0, 0>) {
        const float reach = std::max(p.solid.cutoff(1.0f), p.liquid.cutoff(1.0f));
        reach2 = reach * reach;
        const bool shared = p.solid.integerExponents && p.liquid.integerExponents &&
                            p.solid.mInt == p.liquid.mInt && p.solid.nInt == p.liquid.nInt;
        if (shared) {
            blended = forExponents(p.solid, []<int M, int N>() { return SumBlended(sumBlendedBatch<M, N>); });
        }
    }
};

/// sumRangeMixed for thermal scenes: the candidates of a cell gathered once per material
/// with their temperatures; for each member and material, the heat summed as the
/// neighbours are collected and the force in the pair's phase (thermal_kernel.h).
void sumRangeThermal(const std::vector<ThermalKernel>& kernels, std::size_t kinds,
                     const NeighborGrid& grid, const Globules& s, bool uniformRadius,
                     std::size_t begin, std::size_t end, Accelerations& forces) {
    const GlobuleArrays arrays{s.px.data(), s.py.data(), s.pz.data(),     s.vx.data(),
                               s.vy.data(), s.vz.data(), s.radius.data(), s.temperature.data()};
    const float groupReach = grid.cellSize() * 1.0001f;
    NeighborGrid::RunCursor cursor;
    CellGroup group;
    std::vector<GroupCandidates> candidates(kinds);
    for (GroupCandidates& c : candidates) c.uniformRadius = uniformRadius;
    std::vector<std::pair<float, float>> ranges(kinds);
    NeighborBatch batch;
    for (std::size_t first = begin; first < end;) {
        groupAt(grid, s, first, end, cursor, group);
        const std::size_t last = group.last;
        for (GroupCandidates& c : candidates) {
            c.reserve(group.total);
            c.count = 0;
        }
        for (int b = 0; b < group.runCount; ++b) {
            if (kinds == 1) {
                collectGroupCandidates(arrays, group.runs[b].first, group.runs[b].second,
                                       group.lo, group.hi, groupReach, candidates[0]);
            } else {
                collectGroupCandidatesByMaterial(arrays, group.runs[b].first, group.runs[b].second,
                                                 group.lo, group.hi, groupReach, s.material.data(),
                                                 candidates);
            }
        }
        for (std::size_t kind = 0; kind < kinds; ++kind) {
            const GroupCandidates& c = candidates[kind];
            if (c.count > 0) ranges[kind] = temperatureRange(c.temperature.data(), c.count);
        }
        batch.reserve(group.total);
        for (std::size_t k = first; k < last; ++k) {
            const std::size_t mine = s.materialOf(k);
            const float t = s.temperature[k];
            float fx = 0, fy = 0, fz = 0, heat = 0;
            for (std::size_t kind = 0; kind < kinds; ++kind) {
                if (candidates[kind].count == 0) continue;
                const ThermalKernel& kernel = kernels[mine * kinds + kind];
                const ThermalPhase phase =
                    phaseOf(kernel.pair, t, ranges[kind].first, ranges[kind].second);
                NeighborHeat flow{t, kernel.pair.conductance, phase == ThermalPhase::Blend};
                batch.count = 0;
                collectNeighbors<true>(candidates[kind], s.px[k], s.py[k], s.pz[k], s.vx[k],
                                       s.vy[k], s.vz[k], s.radius[k], kernel.reach2, batch, &flow);
                heat += flow.heat;
                if (phase == ThermalPhase::Blend) {
                    kernel.blended(kernel.pair, t, batch, fx, fy, fz);
                } else if (phase == ThermalPhase::Solid) {
                    kernel.solid(kernel.pair.solid, batch, fx, fy, fz);
                } else {
                    kernel.liquid(kernel.pair.liquid, batch, fx, fy, fz);
                }
            }
            forces.x[k] = fx;
            forces.y[k] = fy;
            forces.z[k] = fz;
            forces.heat[k] = heat;
        }
        first = last;
    }
}

void checkThermal(const Globules& g, const PairTable& pairs) {
    if (g.temperature.size() != g.size()) throw Error("a thermal scene, but globules without a temperature");
    if (pairs.materials() > 1 && g.material.size() != g.size()) {
        throw Error("several materials, but globules without one");
    }
}

}  // namespace

void pairForcesThermal(Globules& g, const PairTable& pairs, NeighborWorkspace& w,
                       Accelerations& forces) {
    const std::size_t n = g.size();
    forces.resize(n);
    forces.heat.resize(n);
    if (n == 0) return;
    checkThermal(g, pairs);
    const auto [smallest, largest] = radiusRange(g);
    w.largestRadius = largest;
    w.grid.build(g.px.data(), g.py.data(), g.pz.data(), n, pairs.cutoff(2.0f * largest));
    g.permute(w.grid.sortedOrder(), forces.x);
    const std::size_t kinds = pairs.materials();
    std::vector<ThermalKernel> kernels;
    for (std::size_t a = 0; a < kinds; ++a) {
        for (std::size_t b = 0; b < kinds; ++b) kernels.emplace_back(pairs.thermal(a, b));
    }
    const bool uniformRadius = smallest == largest;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          sumRangeThermal(kernels, kinds, w.grid, g, uniformRadius, r.begin(),
                                          r.end(), forces);
                      });
}

void pairForcesThermalAllPairs(const Globules& g, const PairTable& pairs, Accelerations& forces) {
    const std::size_t n = g.size();
    forces.resize(n);
    forces.heat.resize(n);
    if (n == 0) return;
    checkThermal(g, pairs);
    // Every pair on its own through the generic blend: the reference the grid loop must match.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 64),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          NeighborBatch batch;
                          batch.reserve(1);
                          batch.count = 1;
                          for (std::size_t i = r.begin(); i != r.end(); ++i) {
                              float fx = 0, fy = 0, fz = 0, heat = 0;
                              for (std::size_t j = 0; j < n; ++j) {
                                  const ThermalPair& pair = pairs.thermal(g.materialOf(i), g.materialOf(j));
                                  const float reach = std::max(pair.solid.cutoff(1.0f), pair.liquid.cutoff(1.0f));
                                  const float dx = g.px[i] - g.px[j], dy = g.py[i] - g.py[j],
                                              dz = g.pz[i] - g.pz[j];
                                  const float sum = g.radius[i] + g.radius[j];
                                  const float d2 = dx * dx + dy * dy + dz * dz;
                                  const float limit = sum * sum * (reach * reach);
                                  if (j == i || !(d2 < limit) || d2 == 0) continue;
                                  batch.dx[0] = dx;
                                  batch.dy[0] = dy;
                                  batch.dz[0] = dz;
                                  batch.vDotP[0] = (g.vx[i] - g.vx[j]) * dx +
                                                   (g.vy[i] - g.vy[j]) * dy + (g.vz[i] - g.vz[j]) * dz;
                                  batch.radiusSum[0] = sum;
                                  batch.temperature[0] = g.temperature[j];
                                  sumBlendedBatch<0, 0>(pair, g.temperature[i], batch, fx, fy, fz);
                                  heat += pair.conductance * (1 - d2 / limit) *
                                          (g.temperature[j] - g.temperature[i]);
                              }
                              forces.x[i] = fx;
                              forces.y[i] = fy;
                              forces.z[i] = fz;
                              forces.heat[i] = heat;
                          }
                      });
}

void pairForcesAllPairs(const Globules& g, const PairTable& pairs, Accelerations& forces) {
    const std::size_t n = g.size();
    forces.resize(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 64),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i) {
                              float f[3] = {0, 0, 0};
                              for (std::size_t j = 0; j < n; ++j) {
                                  if (j != i) addPair(g, pairs(g.materialOf(i), g.materialOf(j)), i, j, f);
                              }
                              forces.x[i] = f[0];
                              forces.y[i] = f[1];
                              forces.z[i] = f[2];
                          }
                      });
}

void pairForcesGrid(const Globules& g, const PairForce& pair, NeighborWorkspace& w,
                    Accelerations& forces) {
    Globules sorted = g;
    Accelerations sortedForces;
    pairForcesSorting(sorted, pair, w, sortedForces);
    const std::vector<uint32_t>& order = w.grid.sortedOrder();
    forces.resize(g.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
        forces.x[order[k]] = sortedForces.x[k];
        forces.y[order[k]] = sortedForces.y[k];
        forces.z[order[k]] = sortedForces.z[k];
    }
}

float groundForce(const GroundSettings& ground, float y, float vy, float radius) {
    return GroundPenalty(ground).force(y, vy, radius);
}

void ForceField::addExternalWithColliders(const Globules& g, std::size_t i,
                                          const std::vector<ColliderMotion>& motions,
                                          const std::vector<uint8_t>& far, Accelerations& out,
                                          std::vector<Wrench>& reactions) const {
    const double mass = g.mass[i], radius = g.radius[i];
    const Vec3 p{g.px[i], g.py[i], g.pz[i]}, v{g.vx[i], g.vy[i], g.vz[i]};
    Vec3 f{out.x[i], out.y[i], out.z[i]};
    if (mGround.enabled) f.y += mGround.force(g.py[i], g.vy[i], g.radius[i]);
    f = f + mass * mExternal.gravity;
    const ColliderSet& colliders = mExternal.colliders;
    for (std::size_t k = 0; k < colliders.size(); ++k) {
        if (far[k]) continue;
        const Vec3 contact =
            colliderForce(colliders[k], motions[k], p, v, radius, mass, f, mStepSeconds);
        f = f + contact;
        if (colliders[k].body >= 0) {  // the reaction, at the globule's centre
            Wrench& r = reactions[std::size_t(colliders[k].body)];
            r.force = r.force - contact;
            r.torque = r.torque - cross(p - motions[k].pivot, contact);
        }
    }
    out.x[i] = float(f.x / mass);
    out.y[i] = float(f.y / mass);
    out.z[i] = float(f.z / mass);
}

void ForceField::addGravityAndGround(const Globules& g, std::size_t i, Accelerations& out) const {
    float fy = out.y[i];
    if (mGround.enabled) fy += mGround.force(g.py[i], g.vy[i], g.radius[i]);
    const float invMass = 1.0f / g.mass[i];
    out.x[i] = out.x[i] * invMass + float(mExternal.gravity.x);
    out.y[i] = fy * invMass + float(mExternal.gravity.y);
    out.z[i] = out.z[i] * invMass + float(mExternal.gravity.z);
}

void ForceField::addExternalForces(Globules& g, Accelerations& out) {
    ColliderSet& colliders = mExternal.colliders;
    if (!colliders.empty()) {
        const std::vector<ColliderMotion> motions = colliders.motions();
        // Globules lie in neighbour-grid order, so runs of them share a block of space:
        // a collider whose surface is out of reach of the whole block (its distance at
        // the block's centre beyond the half-diagonal and the contact's reach) is skipped
        // for the run. The distance of an exact SDF changes no faster than the point
        // moves; a mesh's trilinear field up to sqrt(3) times as fast. A skipped collider
        // would add exactly zero; a globule out of every collider's reach takes the
        // single-precision path of a scene without colliders. Which path a globule takes
        // depends only on positions, so results stay the same for any thread count.
        const float edge = mAllPairs ? 4 * mLargestRadius : mWorkspace.grid.cellSize();
        const double halfDiagonal = 0.5 * std::sqrt(3.0) * edge;
        const auto farFrom = [&](const std::array<int64_t, 3>& block, std::vector<uint8_t>& far) {
            const Vec3 centre{(double(block[0]) + 0.5) * edge, (double(block[1]) + 0.5) * edge,
                              (double(block[2]) + 0.5) * edge};
            for (std::size_t k = 0; k < colliders.size(); ++k) {
                const Collider& c = colliders[k];
                const double slack = c.solid.shape() == ColliderShape::Mesh ? std::sqrt(3.0) : 1.0;
                const double reach =
                    slack * halfDiagonal + (c.surfaceContact ? double(mLargestRadius) : 0.0);
                far[k] = c.solid.sample(motions[k].now.toLocal(centre)).phi > reach;
            }
        };
        const float invEdge = 1.0f / edge;
        const auto blockOf = [&](std::size_t i) {
            const float p[3] = {g.px[i], g.py[i], g.pz[i]};
            std::array<int64_t, 3> block;
            for (int a = 0; a < 3; ++a) {
                const float c = std::floor(p[a] * invEdge);
                // Beyond a float's exact integers (or not finite): no block, never skipped.
                if (!(std::abs(c) < 1e7f)) return std::array<int64_t, 3>{INT64_MIN, 0, 0};
                block[a] = int64_t(c);
            }
            return block;
        };
        using Reactions = std::vector<Wrench>;
        // A deterministic reduction: the same split, hence the same sums, on any number
        // of threads (the bodies' motion stays bit-identical).
        const Reactions reactions = tbb::parallel_deterministic_reduce(
            tbb::blocked_range<std::size_t>(0, g.size(), 1024),
            Reactions(colliders.bodies().size()),
            [&](const tbb::blocked_range<std::size_t>& r, Reactions sums) {
                std::vector<uint8_t> far(colliders.size(), 0);
                bool allFar = false;
                std::array<int64_t, 3> current{INT64_MIN, 0, 0};
                for (std::size_t i = r.begin(); i != r.end(); ++i) {
                    const std::array<int64_t, 3> block = blockOf(i);
                    if (block != current || block[0] == INT64_MIN) {
                        current = block;
                        if (block[0] == INT64_MIN) {
                            std::fill(far.begin(), far.end(), 0);
                        } else {
                            farFrom(block, far);
                        }
                        allFar = std::all_of(far.begin(), far.end(), [](uint8_t f) { return f != 0; });
                    }
                    if (allFar) {
                        addGravityAndGround(g, i, out);  // as without colliders
                    } else {
                        addExternalWithColliders(g, i, motions, far, out, sums);
                    }
                }
                return sums;
            },
            [](Reactions a, const Reactions& b) {
                for (std::size_t k = 0; k < a.size(); ++k) {
                    a[k].force = a[k].force + b[k].force;
                    a[k].torque = a[k].torque + b[k].torque;
                }
                return a;
            });
        colliders.setReactions(reactions);
        return;
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, g.size(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i) {
                              addGravityAndGround(g, i, out);
                          }
                      });
}

void ForceField::compute(Globules& g, Accelerations& out) {
    const bool one = mPairs.materials() == 1;
    if (mExternal.thermal.enabled()) {
        mAllPairs ? pairForcesThermalAllPairs(g, mPairs, out)
                  : pairForcesThermal(g, mPairs, mWorkspace, out);
    } else if (mAllPairs) {
        one ? pairForcesAllPairs(g, mPairs(0, 0), out) : pairForcesAllPairs(g, mPairs, out);
    } else {
        one ? pairForcesSorting(g, mPairs(0, 0), mWorkspace, out)
            : pairForcesSorting(g, mPairs, mWorkspace, out);
    }
    if (!mExternal.colliders.empty()) {  // the grid already knows it
        mLargestRadius = mAllPairs ? radiusRange(g).second : mWorkspace.largestRadius;
    }
    addExternalForces(g, out);
    mExternal.thermal.apply(g, mExternal.colliders, out);
}

}  // namespace globular
