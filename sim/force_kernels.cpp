// The grid force loops: pair forces (and, in thermal scenes, heat) summed over each
// globule's neighbours (pair_kernel.h, thermal_kernel.h). This file is compiled once per
// instruction set (simd_path.h, sim/CMakeLists.txt) with GLOBULAR_SIMD_NAMESPACE naming
// the path: one source, so the paths cannot drift apart. The AVX-512 and AVX2 builds take
// the hand-written 16- and 8-lane kernels of pair_kernel.h and thermal_kernel.h; the scalar
// build takes their plain loops.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

#include "cell_group.h"
#include "each_pair_once.h"
#include "force_kernels.h"
#include "thermal_kernel.h"

#ifndef GLOBULAR_SIMD_NAMESPACE
#error "force_kernels.cpp is built once per path with GLOBULAR_SIMD_NAMESPACE (sim/CMakeLists.txt)"
#endif

namespace globular {

namespace {

/// The range of whole grid cells that a task's range [@p begin, @p end) of @p s (in grid
/// order) stands for: each bound moved on to the first globule of a cell. Every cell then
/// falls to the one task whose range holds its first globule, whatever the partitioner
/// cut, so a cell's group and its candidate lists, and with them CandidateLanes' lanes, are
/// the same on any thread count.
std::pair<std::size_t, std::size_t> wholeCells(const NeighborGrid& grid, const Globules& s,
                                               std::size_t begin, std::size_t end) {
    const std::size_t n = s.size();
    const auto startsCell = [&](std::size_t k) {
        return k == 0 || k >= n ||
               grid.cellOf(s.px[k], s.py[k], s.pz[k]) !=
                   grid.cellOf(s.px[k - 1], s.py[k - 1], s.pz[k - 1]);
    };
    while (!startsCell(begin)) ++begin;
    while (!startsCell(end)) ++end;
    return {begin, std::max(begin, end)};
}

/// Sums forces on the globules [begin, end) of @p s, which are in grid order; the range
/// is of whole cells (wholeCells). Globules that share a cell are consecutive: they are
/// handled as a group with shared candidates, crowded groups in parts (GroupParts). A
/// part's candidates keep the group's order, and every filter is conservative (the pair
/// test decides), so each globule's neighbours are the same whichever way its group is
/// split. The force is summed over each member's neighbours once compacted; with AVX-512,
/// a uniform radius and integer exponents the loop that evaluates each pair once runs
/// instead (sumPairsOnce).
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
    std::vector<GroupCandidates> candidates(1);
    candidates[0].uniformRadius = uniformRadius;
    GroupParts parts;
    NeighborBatch batch;
    for (std::size_t first = begin; first < end;) {
        groupAt(grid, s, first, end, cursor, group);
        GroupCandidates& all = candidates[0];
        all.reserve(group.total);
        all.count = 0;
        for (int b = 0; b < group.runCount; ++b) {
            collectGroupCandidates(arrays, group.runs[b].first, group.runs[b].second, group.lo,
                                   group.hi, groupReach, all);
        }
        batch.reserve(all.count);
        forEachMember(s, first, group, groupReach, candidates, parts,
                      [&](const std::vector<GroupCandidates>& from, std::size_t k) {
                          float fx = 0, fy = 0, fz = 0;
                          batch.count = 0;
                          collectNeighbors(from[0], s.px[k], s.py[k], s.pz[k], s.vx[k],
                                           s.vy[k], s.vz[k], s.radius[k], reach2, batch);
                          sumBatch<M, N>(pair, batch, fx, fy, fz);
                          forces.x[k] = fx;
                          forces.y[k] = fy;
                          forces.z[k] = fz;
                      });
        first = group.last;
    }
}

#if defined(__AVX512F__)
/// sumEachPairOnce for one material.
template <int M, int N>
void sumPairsOnce(const PairForce& pair, const NeighborGrid& grid, const CellSchedule& schedule,
                  const Globules& s, Accelerations& forces) {
    const float reach = pair.cutoff(1.0f), reach2 = reach * reach;
    sumEachPairOnce(grid, schedule, s, 1, false, forces,
                    [&](LaterPairsScratch& w, const std::vector<GroupCandidates>& lists,
                        uint32_t k, std::vector<Reactions>& reactions) {
                        float fx = 0, fy = 0, fz = 0;
                        const CandidateLanes lanes(lists[0], memberAt(s, k), reach2);
                        sumLaterCandidates<M, N>(pair, lanes, w.later[0], reactions[0].lanes(),
                                                 fx, fy, fz);
                        addForce(forces, k, fx, fy, fz);
                    });
}
#endif

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

/// pairForcesSorting (forces.h).
void sortingOne(Globules& g, const PairForce& pair, NeighborWorkspace& w, Accelerations& forces) {
    const std::size_t n = g.size();
    forces.resize(n);
    if (n == 0) return;
    const auto [smallest, largest] = radiusRange(g);
    w.grid.build(g.px.data(), g.py.data(), g.pz.data(), n, pair.cutoff(2.0f * largest));
    w.largestRadius = largest;
    // The accelerations are about to be overwritten: their array is the reorder's scratch
    // (no extra 4 bytes per globule).
    g.permute(w.grid.sortedOrder(), forces.x);
    const bool uniformRadius = smallest == largest;
#if defined(__AVX512F__)
    if (uniformRadius && pair.integerExponents) {
        using SumOnce = void (*)(const PairForce&, const NeighborGrid&, const CellSchedule&,
                                 const Globules&, Accelerations&);
        const auto once = forExponents(pair, []<int M, int N>() {
            if constexpr (M > 0 && N > 0) {
                return SumOnce(sumPairsOnce<M, N>);
            } else {
                return SumOnce(nullptr);
            }
        });
        if (once) {
            w.schedule.build(w.grid, g.px.data(), g.py.data(), g.pz.data(), n);
            zeroForces(forces, false);
            once(pair, w.grid, w.schedule, g, forces);
            return;
        }
    }
#endif
    const SumRange sum = kernelFor(pair);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, w.grain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          const auto [begin, end] = wholeCells(w.grid, g, r.begin(), r.end());
                          sum(pair, w.grid, g, uniformRadius, begin, end, forces);
                      });
}

/// One pair's sum over a batch: sumBatch for the pair's exponents.
using SumBatch = void (*)(const PairForce&, const NeighborBatch&, float&, float&, float&);
#if defined(__AVX512F__)
/// The same straight over a member's candidates (CandidateLanes).
using SumCandidates = void (*)(const PairForce&, const CandidateLanes&, float&, float&, float&);
/// The same over the candidates from a place on, the opposite forces left behind.
using SumLaterCandidates = void (*)(const PairForce&, const CandidateLanes&, uint32_t,
                                    ReactionLanes, float&, float&, float&);
#endif

/// One pair's kernels for sumRangeMixed: over the compacted neighbours and, with AVX-512
/// and integer exponents, straight over the candidates (for a uniform radius).
struct MixedKernel {
    SumBatch batch;
#if defined(__AVX512F__)
    SumCandidates direct = nullptr;
    SumLaterCandidates later = nullptr;  ///< the same from a place on (sumLaterCandidates)
#endif

    explicit MixedKernel(const PairForce& pair)
        : batch(forExponents(pair, []<int M, int N>() { return SumBatch(sumBatch<M, N>); })) {
#if defined(__AVX512F__)
        std::tie(direct, later) = forExponents(pair, []<int M, int N>() {
            if constexpr (M > 0 && N > 0) {
                return std::pair{SumCandidates(sumCandidates<M, N>),
                                 SumLaterCandidates(sumLaterCandidates<M, N>)};
            } else {
                return std::pair{SumCandidates(nullptr), SumLaterCandidates(nullptr)};
            }
        });
#endif
    }
};

/// sumRange for several materials: a cell's candidates gathered once per material, and
/// each member summed over each material's with that pair's constants and kernel, in
/// material order (the same order on any thread count); the range is of whole cells.
void sumRangeMixed(const PairTable& pairs, const std::vector<MixedKernel>& kernels,
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
    GroupParts parts;
    NeighborBatch batch;
    for (std::size_t first = begin; first < end;) {
        groupAt(grid, s, first, end, cursor, group);
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
        const auto sumMember = [&](const std::vector<GroupCandidates>& from, std::size_t k) {
            const std::size_t mine = s.material[k];
            float fx = 0, fy = 0, fz = 0;
            for (std::size_t kind = 0; kind < kinds; ++kind) {
                if (from[kind].count == 0) continue;
                const PairForce& pair = pairs(mine, kind);
                const MixedKernel& kernel = kernels[mine * kinds + kind];
                const float reach = pair.cutoff(1.0f);
#if defined(__AVX512F__)
                if (uniformRadius && kernel.direct) {
                    kernel.direct(pair, CandidateLanes(from[kind], memberAt(s, k), reach * reach),
                                  fx, fy, fz);
                    continue;
                }
#endif
                batch.count = 0;
                collectNeighbors(from[kind], s.px[k], s.py[k], s.pz[k], s.vx[k], s.vy[k],
                                 s.vz[k], s.radius[k], reach * reach, batch);
                kernel.batch(pair, batch, fx, fy, fz);
            }
            forces.x[k] = fx;
            forces.y[k] = fy;
            forces.z[k] = fz;
        };
        forEachMember(s, first, group, groupReach, candidates, parts, sumMember);
        first = group.last;
    }
}

/// pairForcesSorting (forces.h).
void sortingTable(Globules& g, const PairTable& pairs, NeighborWorkspace& w, Accelerations& forces) {
    const std::size_t n = g.size();
    forces.resize(n);
    if (n == 0) return;
    const auto [smallest, largest] = radiusRange(g);
    w.largestRadius = largest;
    w.grid.build(g.px.data(), g.py.data(), g.pz.data(), n, pairs.cutoff(2.0f * largest));
    g.permute(w.grid.sortedOrder(), forces.x);
    std::vector<MixedKernel> kernels;
    for (std::size_t a = 0; a < pairs.materials(); ++a) {
        for (std::size_t b = 0; b < pairs.materials(); ++b) kernels.emplace_back(pairs(a, b));
    }
    const bool uniformRadius = smallest == largest;
#if defined(__AVX512F__)
    const bool eachPairOnce =
        uniformRadius && std::all_of(kernels.begin(), kernels.end(),
                                     [](const MixedKernel& kernel) { return kernel.later; });
    if (eachPairOnce) {
        const std::size_t kinds = pairs.materials();
        w.schedule.build(w.grid, g.px.data(), g.py.data(), g.pz.data(), n);
        zeroForces(forces, false);
        sumEachPairOnce(w.grid, w.schedule, g, kinds, false, forces,
                        [&](LaterPairsScratch& scratch, const std::vector<GroupCandidates>& lists,
                            uint32_t k, std::vector<Reactions>& reactions) {
                            const std::size_t mine = g.material[k];
                            float fx = 0, fy = 0, fz = 0;
                            for (std::size_t kind = 0; kind < kinds; ++kind) {
                                if (scratch.later[kind] >= lists[kind].count) continue;
                                const PairForce& pair = pairs(mine, kind);
                                const float reach = pair.cutoff(1.0f);
                                const CandidateLanes lanes(lists[kind], memberAt(g, k),
                                                           reach * reach);
                                kernels[mine * kinds + kind].later(pair, lanes, scratch.later[kind],
                                                                   reactions[kind].lanes(), fx, fy,
                                                                   fz);
                            }
                            addForce(forces, k, fx, fy, fz);
                        });
        return;
    }
#endif
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, w.grain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          const auto [begin, end] = wholeCells(w.grid, g, r.begin(), r.end());
                          sumRangeMixed(pairs, kernels, w.grid, g, uniformRadius, begin, end,
                                        forces);
                      });
}

/// One pair's force and heat over a batch (sumBatchAndHeat, thermal_kernel.h).
using SumBatchAndHeat = float (*)(const PairForce&, const NeighborBatch&, float, float, float&,
                                  float&, float&);

SumBatchAndHeat heatKernelFor(const PairForce& pair) {
    return forExponents(pair,
                        []<int M, int N>() { return SumBatchAndHeat(sumBatchAndHeat<M, N>); });
}

/// The blended force sum and heat for a pair's exponents.
using SumBlended = float (*)(const ThermalPair&, float, float, const NeighborBatch&, float&,
                             float&, float&);

#if defined(__AVX512F__)
/// The same straight over a member's candidates (CandidateLanes).
using SumCandidatesAndHeat = float (*)(const PairForce&, const CandidateLanes&,
                                       const GroupCandidates&, float, float, float&, float&,
                                       float&);
using SumBlendedCandidates = float (*)(const ThermalPair&, const CandidateLanes&,
                                       const GroupCandidates&, float, float, float&, float&,
                                       float&);
/// The same over the candidates from a place on, the opposite forces and heat left behind.
using SumLaterAndHeat = float (*)(const PairForce&, const CandidateLanes&,
                                  const GroupCandidates&, float, float, float&, float&, float&,
                                  uint32_t, ReactionLanes, float);
using SumLaterBlended = float (*)(const ThermalPair&, const CandidateLanes&,
                                  const GroupCandidates&, float, float, float&, float&, float&,
                                  uint32_t, ReactionLanes, float);
#endif

/// What the thermal loop runs for one pair of materials in each phase.
struct ThermalKernel {
    ThermalPair pair;
    float reach2 = 0;  ///< (the pair's reach in both phases)^2, in units of r_i + r_j
    SumBatchAndHeat solid, liquid;
    SumBlended blended;
#if defined(__AVX512F__)
    /// With shared integer exponents, for a uniform radius: a pure phase's kernel (with
    /// that phase's constants) and the blend straight over the candidates, in the same
    /// lanes; null otherwise.
    SumCandidatesAndHeat pureDirect = nullptr;
    SumBlendedCandidates blendedDirect = nullptr;
    SumLaterAndHeat pureLater = nullptr;  ///< the same from a place on (each pair once)
    SumLaterBlended blendedLater = nullptr;
#endif

    /// The three kernels share their arithmetic, so that where a pure phase holds the
    /// blend gives its bits and the phase picked (which follows the group's candidates,
    /// so a range's cut) changes nothing: with the exponents both phases share, unrolled;
    /// where the phases' exponents differ, all three with pow() (slower, but the same).
    explicit ThermalKernel(const ThermalPair& p)
        : pair(p),
          solid(sumBatchAndHeat<0, 0>),
          liquid(sumBatchAndHeat<0, 0>),
          blended(sumBlendedBatch<0, 0>) {
        const float reach = std::max(p.solid.cutoff(1.0f), p.liquid.cutoff(1.0f));
        reach2 = reach * reach;
        const bool shared = p.solid.integerExponents && p.liquid.integerExponents &&
                            p.solid.mInt == p.liquid.mInt && p.solid.nInt == p.liquid.nInt;
        if (shared) {
            solid = heatKernelFor(p.solid);
            liquid = heatKernelFor(p.liquid);
            blended = forExponents(p.solid, []<int M, int N>() { return SumBlended(sumBlendedBatch<M, N>); });
#if defined(__AVX512F__)
            const auto direct = []<int M, int N>() {
                if constexpr (M > 0 && N > 0) {
                    return std::pair{SumCandidatesAndHeat(sumCandidatesAndHeat<M, N>),
                                     SumBlendedCandidates(sumBlendedCandidates<M, N>)};
                } else {
                    return std::pair{SumCandidatesAndHeat(nullptr), SumBlendedCandidates(nullptr)};
                }
            };
            std::tie(pureDirect, blendedDirect) = forExponents(p.solid, direct);
            const auto later = []<int M, int N>() {
                if constexpr (M > 0 && N > 0) {
                    return std::pair{SumLaterAndHeat(candidatesAndHeat<M, N, ReactionLanes>),
                                     SumLaterBlended(blendedCandidates<M, N, ReactionLanes>)};
                } else {
                    return std::pair{SumLaterAndHeat(nullptr), SumLaterBlended(nullptr)};
                }
            };
            std::tie(pureLater, blendedLater) = forExponents(p.solid, later);
#endif
        }
    }
};

/// sumRangeMixed for thermal scenes: the candidates of a cell gathered once per material
/// with their temperatures; for each member and material, the force in the pair's phase
/// and the heat flowing in (thermal_kernel.h), summed in the force's lanes: over the
/// neighbours once collected, or straight over the candidates. The range is of whole
/// cells, so crowded cells go in parts here too.
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
    GroupParts parts;
    parts.temperatures = true;
    NeighborBatch batch;
    for (std::size_t first = begin; first < end;) {
        groupAt(grid, s, first, end, cursor, group);
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
        // The phases follow the group's candidates: a part's are among them, and where a
        // pure phase holds, the blend gives its bits (thermal_kernel.h).
        for (std::size_t kind = 0; kind < kinds; ++kind) {
            const GroupCandidates& c = candidates[kind];
            if (c.count > 0) ranges[kind] = temperatureRange(c.temperature.data(), c.count);
        }
        batch.reserve(group.total);
        const auto sumMember = [&](const std::vector<GroupCandidates>& from, std::size_t k) {
            const std::size_t mine = s.materialOf(k);
            const float t = s.temperature[k];
            float fx = 0, fy = 0, fz = 0, heat = 0;
            for (std::size_t kind = 0; kind < kinds; ++kind) {
                if (from[kind].count == 0) continue;
                const ThermalKernel& kernel = kernels[mine * kinds + kind];
                const ThermalPhase phase =
                    phaseOf(kernel.pair, t, ranges[kind].first, ranges[kind].second);
                // Each kernel sums the heat in the same lanes (HeatLanes): its bits do not
                // depend on the phase picked.
                float in;
#if defined(__AVX512F__)
                if (uniformRadius && kernel.pureDirect) {
                    const CandidateLanes lanes(from[kind], memberAt(s, k), kernel.reach2);
                    if (phase == ThermalPhase::Blend) {
                        in = kernel.blendedDirect(kernel.pair, lanes, from[kind], t, kernel.reach2,
                                                  fx, fy, fz);
                    } else {
                        const PairForce& p =
                            phase == ThermalPhase::Solid ? kernel.pair.solid : kernel.pair.liquid;
                        in = kernel.pureDirect(p, lanes, from[kind], t, kernel.reach2, fx, fy, fz);
                    }
                    heat += kernel.pair.conductance * in;
                    continue;
                }
#endif
                batch.count = 0;
                collectNeighbors<true>(from[kind], s.px[k], s.py[k], s.pz[k], s.vx[k], s.vy[k],
                                       s.vz[k], s.radius[k], kernel.reach2, batch);
                if (phase == ThermalPhase::Blend) {
                    in = kernel.blended(kernel.pair, t, kernel.reach2, batch, fx, fy, fz);
                } else if (phase == ThermalPhase::Solid) {
                    in = kernel.solid(kernel.pair.solid, batch, t, kernel.reach2, fx, fy, fz);
                } else {
                    in = kernel.liquid(kernel.pair.liquid, batch, t, kernel.reach2, fx, fy, fz);
                }
                heat += kernel.pair.conductance * in;
            }
            forces.x[k] = fx;
            forces.y[k] = fy;
            forces.z[k] = fz;
            forces.heat[k] = heat;
        };
        forEachMember(s, first, group, groupReach, candidates, parts, sumMember);
        first = group.last;
    }
}

#if defined(__AVX512F__)
/// sumEachPairOnce for thermal scenes. <M, N>: the exponents every pair of materials
/// shares in both phases, so the kernels are called, and inlined, by name; <0, 0>: through
/// each pair's pointers (ThermalKernel). Either way the same kernels, so the same bits.
template <int M, int N>
void thermalPairsOnce(const std::vector<ThermalKernel>& kernels, std::size_t kinds,
                      NeighborWorkspace& w, const Globules& g, Accelerations& forces) {
    sumEachPairOnce(
        w.grid, w.schedule, g, kinds, true, forces,
        [&](LaterPairsScratch& scratch, const std::vector<GroupCandidates>& lists, uint32_t k,
            std::vector<Reactions>& reactions) {
            const std::size_t mine = g.materialOf(k);
            const float t = g.temperature[k];
            float fx = 0, fy = 0, fz = 0, heat = 0;
            for (std::size_t kind = 0; kind < kinds; ++kind) {
                const uint32_t from = scratch.later[kind];
                if (from >= lists[kind].count) continue;
                const ThermalKernel& kernel = kernels[mine * kinds + kind];
                const auto [lowest, highest] = scratch.ranges[kind];
                const ThermalPhase phase = phaseOf(kernel.pair, t, lowest, highest);
                const CandidateLanes lanes(lists[kind], memberAt(g, k), kernel.reach2);
                const float conductance = kernel.pair.conductance;
                const ReactionLanes opposite = reactions[kind].lanes();
                float in;
                if (phase == ThermalPhase::Blend) {
                    if constexpr (M > 0) {
                        in = blendedCandidates<M, N>(kernel.pair, lanes, lists[kind], t,
                                                     kernel.reach2, fx, fy, fz, from, opposite,
                                                     conductance);
                    } else {
                        in = kernel.blendedLater(kernel.pair, lanes, lists[kind], t,
                                                 kernel.reach2, fx, fy, fz, from, opposite,
                                                 conductance);
                    }
                } else {
                    const PairForce& p =
                        phase == ThermalPhase::Solid ? kernel.pair.solid : kernel.pair.liquid;
                    if constexpr (M > 0) {
                        in = candidatesAndHeat<M, N>(p, lanes, lists[kind], t, kernel.reach2,
                                                     fx, fy, fz, from, opposite, conductance);
                    } else {
                        in = kernel.pureLater(p, lanes, lists[kind], t, kernel.reach2, fx, fy,
                                              fz, from, opposite, conductance);
                    }
                }
                heat += conductance * in;
            }
            addForce(forces, k, fx, fy, fz);
            forces.heat[k] += heat;
        });
}
#endif

/// pairForcesThermal (forces.h); the dispatcher has checked the arrays.
void thermal(Globules& g, const PairTable& pairs, NeighborWorkspace& w, Accelerations& forces) {
    const std::size_t n = g.size();
    forces.resize(n);
    forces.heat.resize(n);
    if (n == 0) return;
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
#if defined(__AVX512F__)
    const bool eachPairOnce =
        uniformRadius && std::all_of(kernels.begin(), kernels.end(),
                                     [](const ThermalKernel& kernel) { return kernel.pureLater; });
    if (eachPairOnce) {
        w.schedule.build(w.grid, g.px.data(), g.py.data(), g.pz.data(), n);
        zeroForces(forces, true);
        // One set of exponents for every pair and phase (the usual case): the kernels by
        // name. ThermalKernel has checked that each pair's phases share theirs.
        const PairForce& first = kernels.front().pair.solid;
        const bool shared = std::all_of(kernels.begin(), kernels.end(), [&](const ThermalKernel& kernel) {
            return kernel.pair.solid.mInt == first.mInt && kernel.pair.solid.nInt == first.nInt;
        });
        const auto loop = shared ? forExponents(first, []<int M, int N>() {
                                       return &thermalPairsOnce<M, N>;
                                   })
                                 : &thermalPairsOnce<0, 0>;
        loop(kernels, kinds, w, g, forces);
        return;
    }
#endif
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, w.grain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          const auto [begin, end] = wholeCells(w.grid, g, r.begin(), r.end());
                          sumRangeThermal(kernels, kinds, w.grid, g, uniformRadius, begin, end,
                                          forces);
                      });
}

}  // namespace

// The one symbol this build exports (force_kernels.h).
namespace GLOBULAR_SIMD_NAMESPACE {
extern const ForceKernels kForceKernels;
const ForceKernels kForceKernels{sortingOne, sortingTable, thermal};
}  // namespace GLOBULAR_SIMD_NAMESPACE

}  // namespace globular
