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

#include "force_kernels.h"
#include "thermal_kernel.h"

#ifndef GLOBULAR_SIMD_NAMESPACE
#error "force_kernels.cpp is built once per path with GLOBULAR_SIMD_NAMESPACE (sim/CMakeLists.txt)"
#endif

namespace globular {

namespace {

/// One grid cell's members in a range of globules in grid order, and what is around them.
struct CellGroup {
    std::size_t last = 0;      ///< the members are [first, last)
    float lo[3], hi[3];        ///< the members' bounding box
    int runCount = 0;          ///< runs of candidates in the 27 cells around
    std::size_t total = 0;     ///< globules in those runs
    std::array<NeighborGrid::Run, NeighborGrid::kMaxRuns> runs;
};

#if defined(__AVX512F__)
/// Globule @p k of @p s as a member whose force is summed (CandidateLanes).
Member memberAt(const Globules& s, std::size_t k) {
    return {s.px[k], s.py[k], s.pz[k], s.vx[k], s.vy[k], s.vz[k], s.radius[k]};
}
#endif

/// Grows the box [@p lo, @p hi] to hold globule @p k of @p s.
void growBox(const Globules& s, std::size_t k, float lo[3], float hi[3]) {
    const float p[3] = {s.px[k], s.py[k], s.pz[k]};
    for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], p[a]);
        hi[a] = std::max(hi[a], p[a]);
    }
}

/// The group of globule @p first's cell within [first, end) of @p s.
void groupAt(const NeighborGrid& grid, const Globules& s, std::size_t first, std::size_t end,
             NeighborGrid::RunCursor& cursor, CellGroup& group) {
    const auto cell = grid.cellOf(s.px[first], s.py[first], s.pz[first]);
    const float start[3] = {s.px[first], s.py[first], s.pz[first]};
    for (int a = 0; a < 3; ++a) group.lo[a] = group.hi[a] = start[a];
    std::size_t last = first + 1;
    for (; last < end && grid.cellOf(s.px[last], s.py[last], s.pz[last]) == cell; ++last) {
        growBox(s, last, group.lo, group.hi);
    }
    group.last = last;
    group.runCount = grid.neighborRuns(s.px[first], s.py[first], s.pz[first], cursor, group.runs);
    group.total = 0;
    for (int b = 0; b < group.runCount; ++b) group.total += group.runs[b].second - group.runs[b].first;
}

/// A crowded group's members in up to four parts, split at the middle of the group's box
/// in y and z, each part with its own box. A part's box is about half the group's in two
/// axes, so its candidates, filtered from the group's, are about half as many, and each
/// member tests only its part's. In the dense pile (about 60 members a group, ~2 000
/// candidates) the second filter costs a member ~130 tests and spares it ~900 (estimates
/// from the boxes' volumes); its step measured 1.3x faster. Eight parts (x split too)
/// measured no faster.
struct GroupParts {
    static constexpr int kMax = 4;
    /// Smaller groups are not split. Split from 16, the liquid block (4-18 members a
    /// group) measured perhaps 5 % slower; the pour's simulation stage gained 1.22x split
    /// from 16, 1.18x from 24 and 1.07x from 32.
    static constexpr std::size_t kMinMembers = 24;
    int count = 0;
    std::array<uint32_t, kMax + 1> start{};  ///< part p is members[start[p], start[p + 1])
    std::array<std::array<float, 3>, kMax> lo, hi;
    std::vector<uint32_t> members;  ///< globule indices, part by part
    std::vector<GroupCandidates> candidates;  ///< the part at hand's, one list per material
    bool temperatures = false;  ///< the candidates carry temperatures (thermal scenes)
};

/// Splits @p group's members [first, group.last) of @p s into @p parts (none empty).
void splitGroup(const Globules& s, std::size_t first, const CellGroup& group, GroupParts& parts) {
    const float midY = 0.5f * (group.lo[1] + group.hi[1]);
    const float midZ = 0.5f * (group.lo[2] + group.hi[2]);
    const auto partOf = [&](std::size_t k) {
        return int(s.py[k] > midY) + 2 * int(s.pz[k] > midZ);
    };
    std::array<uint32_t, GroupParts::kMax + 1> fill{};
    for (std::size_t k = first; k < group.last; ++k) ++fill[partOf(k) + 1];
    for (int p = 0; p < GroupParts::kMax; ++p) fill[p + 1] += fill[p];
    const auto bounds = fill;
    parts.members.resize(group.last - first);
    for (std::size_t k = first; k < group.last; ++k) parts.members[fill[partOf(k)]++] = uint32_t(k);
    parts.count = 0;
    for (int p = 0; p < GroupParts::kMax; ++p) {
        if (bounds[p] == bounds[p + 1]) continue;
        const int q = parts.count++;
        parts.start[q] = bounds[p];
        parts.start[q + 1] = bounds[p + 1];
        auto& lo = parts.lo[q];
        auto& hi = parts.hi[q];
        const uint32_t k0 = parts.members[bounds[p]];
        lo = hi = {s.px[k0], s.py[k0], s.pz[k0]};
        for (uint32_t m = bounds[p] + 1; m < bounds[p + 1]; ++m) {
            growBox(s, parts.members[m], lo.data(), hi.data());
        }
    }
}

/// @p c as globule arrays: the source of a part's candidates; @p temperatures: with theirs.
GlobuleArrays arraysOf(const GroupCandidates& c, bool temperatures) {
    return {c.x.data(),  c.y.data(),  c.z.data(),      c.vx.data(),
            c.vy.data(), c.vz.data(), c.radius.data(), temperatures ? c.temperature.data() : nullptr};
}

/// Calls sum(from, k) for every member k of @p group ([first, group.last) of @p s), @p from
/// being the candidate lists (one per material) that k is to test: the group's
/// @p candidates or, in a crowded group, its part's, filtered from them (GroupParts).
template <typename Sum>
void forEachMember(const Globules& s, std::size_t first, const CellGroup& group, float groupReach,
                   const std::vector<GroupCandidates>& candidates, GroupParts& parts, Sum&& sum) {
    if (group.last - first < GroupParts::kMinMembers) {
        for (std::size_t k = first; k < group.last; ++k) sum(candidates, k);
        return;
    }
    splitGroup(s, first, group, parts);
    parts.candidates.resize(candidates.size());
    for (std::size_t kind = 0; kind < candidates.size(); ++kind) {
        parts.candidates[kind].uniformRadius = candidates[kind].uniformRadius;
        parts.candidates[kind].reserve(candidates[kind].count);
    }
    for (int p = 0; p < parts.count; ++p) {
        for (std::size_t kind = 0; kind < candidates.size(); ++kind) {
            GroupCandidates& part = parts.candidates[kind];
            part.count = 0;
            collectGroupCandidates(arraysOf(candidates[kind], parts.temperatures), 0,
                                   candidates[kind].count,
                                   parts.lo[p].data(), parts.hi[p].data(), groupReach, part);
        }
        for (uint32_t m = parts.start[p]; m < parts.start[p + 1]; ++m) {
            sum(parts.candidates, parts.members[m]);
        }
    }
}

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
/// split. With AVX-512 and a uniform radius the force is summed straight over the
/// candidates (CandidateLanes); elsewhere over the neighbours once compacted.
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
                          bool summed = false;
#if defined(__AVX512F__)
                          if constexpr (M > 0 && N > 0) {
                              if (uniformRadius) {
                                  const CandidateLanes lanes(from[0], memberAt(s, k), reach2);
                                  sumCandidates<M, N>(pair, lanes, fx, fy, fz);
                                  summed = true;
                              }
                          }
#endif
                          if (!summed) {
                              batch.count = 0;
                              collectNeighbors(from[0], s.px[k], s.py[k], s.pz[k], s.vx[k],
                                               s.vy[k], s.vz[k], s.radius[k], reach2, batch);
                              sumBatch<M, N>(pair, batch, fx, fy, fz);
                          }
                          forces.x[k] = fx;
                          forces.y[k] = fy;
                          forces.z[k] = fz;
                      });
        first = group.last;
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
    const SumRange sum = kernelFor(pair);
    const bool uniformRadius = smallest == largest;
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
#endif

/// One pair's kernels for sumRangeMixed: over the compacted neighbours and, with AVX-512
/// and integer exponents, straight over the candidates (for a uniform radius).
struct MixedKernel {
    SumBatch batch;
#if defined(__AVX512F__)
    SumCandidates direct = nullptr;
#endif

    explicit MixedKernel(const PairForce& pair)
        : batch(forExponents(pair, []<int M, int N>() { return SumBatch(sumBatch<M, N>); })) {
#if defined(__AVX512F__)
        direct = forExponents(pair, []<int M, int N>() {
            if constexpr (M > 0 && N > 0) {
                return SumCandidates(sumCandidates<M, N>);
            } else {
                return SumCandidates(nullptr);
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
