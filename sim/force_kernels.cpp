// The grid force loops: pair forces (and, in thermal scenes, heat) over the globules'
// neighbours (pair_kernel.h, thermal_kernel.h). This file is compiled once per
// instruction set (simd_path.h, sim/CMakeLists.txt) with GLOBULAR_SIMD_NAMESPACE naming
// the path: one source, so the paths cannot drift apart. The AVX-512 build takes the
// hand-written 16-lane kernels; the AVX2 and scalar builds take their plain loops, which
// the compiler vectorises where it can (the compaction of neighbours stays serial).
//
// Each pair is evaluated once (Newton's third law), by its lower index in grid order:
// globule i sums the force of its neighbours j > i and hands each j the opposite
// (scatterBatch), and the same for heat. The writes to j make the loop a scatter, which
// must neither race nor depend on the thread count; the groups of a cell's members are
// therefore taken by colour. A row of cells (cy, cz) has colour (cy mod 3, cz mod 3);
// the 9 colours run one after another, and within a colour a task takes whole chunks of
// hash buckets, their groups of that colour in grid order, one after another.
//   - No race: a group writes only globules of its own row and of the rows within one
//     cell in y and z (the pair reach is at most a cell edge; candidates from other
//     rows that share a bucket fail the distance test and write nothing). Two rows of
//     one colour lie three or more cells apart in y or z, so their writes are disjoint,
//     and a row lies in one bucket, so in one task.
//   - The same bits on any thread count: in each colour, exactly one row is within one
//     cell of a globule's row, so everything a globule receives in that colour comes
//     from one task, in its fixed order; the colours run in a fixed order.
// The forces are zeroed first and every contribution is added to them.

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "force_kernels.h"
#include "thermal_kernel.h"

#ifndef GLOBULAR_SIMD_NAMESPACE
#error "force_kernels.cpp is built once per path with GLOBULAR_SIMD_NAMESPACE (sim/CMakeLists.txt)"
#endif

namespace globular {

namespace {

constexpr int kColours = 9;
/// Hash buckets per task: a few hundred tasks per colour for 100k globules.
constexpr std::size_t kBucketsPerChunk = 256;

/// The colour of the row of cells (cy, cz): (cy mod 3, cz mod 3) as one number.
int rowColour(int32_t cy, int32_t cz) {
    const auto mod3 = [](int32_t v) { return ((v % 3) + 3) % 3; };
    return mod3(cy) * 3 + mod3(cz);
}

/// Fills @p schedule (NeighborWorkspace::schedule) for the globules @p s in the grid
/// order of @p grid. @return the number of chunks.
std::size_t buildSchedule(const NeighborGrid& grid, const Globules& s,
                          std::vector<std::vector<CellGroupRange>>& schedule) {
    const std::vector<uint32_t>& starts = grid.bucketStarts();
    const std::size_t buckets = starts.size() - 1;
    const std::size_t chunks = (buckets + kBucketsPerChunk - 1) / kBucketsPerChunk;
    if (schedule.size() < chunks * kColours) schedule.resize(chunks * kColours);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks),
                      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t chunk = r.begin(); chunk != r.end(); ++chunk) {
            std::vector<CellGroupRange>* lists = &schedule[chunk * kColours];
            for (int c = 0; c < kColours; ++c) lists[c].clear();
            const std::size_t lastBucket = std::min(buckets, (chunk + 1) * kBucketsPerChunk);
            for (std::size_t b = chunk * kBucketsPerChunk; b < lastBucket; ++b) {
                const uint32_t end = starts[b + 1];
                for (uint32_t first = starts[b]; first < end;) {
                    const auto cell = grid.cellOf(s.px[first], s.py[first], s.pz[first]);
                    uint32_t last = first + 1;
                    while (last < end && grid.cellOf(s.px[last], s.py[last], s.pz[last]) == cell) ++last;
                    lists[rowColour(cell[1], cell[2])].push_back({first, last});
                    first = last;
                }
            }
        }
    });
    return chunks;
}

/// One grid cell's members, the box around them and the runs of their candidates.
struct CellGroup {
    uint32_t first = 0, last = 0;  ///< the members are [first, last)
    float lo[3], hi[3];            ///< the members' bounding box
    int runCount = 0;              ///< runs of candidates above first in the 27 cells around
    std::size_t total = 0;         ///< globules in those runs
    std::array<NeighborGrid::Run, NeighborGrid::kMaxRuns> runs;
};

/// The group @p range of @p s: its box, and the parts of its runs above its first member
/// (the only partners its members take).
void groupAt(const NeighborGrid& grid, const Globules& s, CellGroupRange range,
             NeighborGrid::RunCursor& cursor, CellGroup& group) {
    const uint32_t first = range.first;
    group.first = first;
    group.last = range.last;
    const float start[3] = {s.px[first], s.py[first], s.pz[first]};
    for (int a = 0; a < 3; ++a) group.lo[a] = group.hi[a] = start[a];
    for (uint32_t k = first + 1; k < range.last; ++k) {
        const float p[3] = {s.px[k], s.py[k], s.pz[k]};
        for (int a = 0; a < 3; ++a) {
            group.lo[a] = std::min(group.lo[a], p[a]);
            group.hi[a] = std::max(group.hi[a], p[a]);
        }
    }
    std::array<NeighborGrid::Run, NeighborGrid::kMaxRuns> runs;
    const int count = grid.neighborRuns(start[0], start[1], start[2], cursor, runs);
    group.runCount = 0;
    group.total = 0;
    for (int b = 0; b < count; ++b) {
        const uint32_t from = std::max(runs[b].first, first + 1);
        if (from >= runs[b].second) continue;
        group.runs[group.runCount++] = {from, runs[b].second};
        group.total += runs[b].second - from;
    }
}

/// What a task of the force loop works in: one candidate list per material, the batch.
struct Scratch {
    std::vector<GroupCandidates> candidates;
    std::vector<uint32_t> from;  ///< per material: the first candidate above the member
    std::vector<std::pair<float, float>> ranges;  ///< thermal: candidate temperatures
    NeighborBatch batch;

    Scratch(std::size_t kinds, bool uniformRadius)
        : candidates(kinds), from(kinds), ranges(kinds) {
        for (GroupCandidates& c : candidates) c.uniformRadius = uniformRadius;
    }

    /// Empty candidate lists with room for @p group's.
    void clear(const CellGroup& group) {
        for (GroupCandidates& c : candidates) {
            c.reserve(group.total);
            c.count = 0;
        }
        std::fill(from.begin(), from.end(), 0u);
        batch.reserve(group.total);
    }
};

/// Calls process(group, scratch) for every cell group of the globules @p s (in the grid
/// order of w.grid), colour after colour (the top of this file): race-free, and the
/// same additions in the same order on any thread count.
template <typename Process>
void forEachGroup(NeighborWorkspace& w, const Globules& s, std::size_t kinds,
                  bool uniformRadius, Process&& process) {
    const std::size_t chunks = buildSchedule(w.grid, s, w.schedule);
    tbb::enumerable_thread_specific<Scratch> scratch([&] { return Scratch(kinds, uniformRadius); });
    for (int colour = 0; colour < kColours; ++colour) {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks),
                          [&](const tbb::blocked_range<std::size_t>& r) {
            Scratch& mine = scratch.local();
            NeighborGrid::RunCursor cursor;  // fresh: the grid changes between steps
            CellGroup group;
            for (std::size_t chunk = r.begin(); chunk != r.end(); ++chunk) {
                for (const CellGroupRange range : w.schedule[chunk * kColours + colour]) {
                    groupAt(w.grid, s, range, cursor, group);
                    process(group, mine);
                }
            }
        });
    }
}

/// Zeroed forces (and heat, with @p heat) for @p n globules.
void clearForces(Accelerations& forces, std::size_t n, bool heat) {
    forces.resize(n);
    for (auto* a : {&forces.x, &forces.y, &forces.z}) std::fill(a->begin(), a->end(), 0.0f);
    if (heat) forces.heat.assign(n, 0.0f);
}

/// The cell edge is the largest reach of any pair; a hair more keeps the box test
/// conservative under rounding (the pair test decides).
float groupReachOf(const NeighborGrid& grid) { return grid.cellSize() * 1.0001f; }

/// One material: the forces between the members of @p group and their partners above
/// them, each pair once.
template <int M, int N>
void sumGroup(const PairForce& pair, const GlobuleArrays& arrays, const Globules& s,
              const CellGroup& group, float groupReach, Scratch& w, Accelerations& forces) {
    const float reach = pair.cutoff(1.0f), reach2 = reach * reach;
    w.clear(group);
    GroupCandidates& candidates = w.candidates[0];
    for (int b = 0; b < group.runCount; ++b) {
        collectGroupCandidates(arrays, group.runs[b].first, group.runs[b].second, group.lo,
                               group.hi, groupReach, candidates);
    }
    NeighborBatch& batch = w.batch;
    float *fx = forces.x.data(), *fy = forces.y.data(), *fz = forces.z.data();
    uint32_t from = 0;
    for (uint32_t k = group.first; k < group.last; ++k) {
        from = candidates.after(k, from);
        batch.count = 0;
        collectNeighbors(candidates, from, s.px[k], s.py[k], s.pz[k], s.vx[k], s.vy[k],
                         s.vz[k], s.radius[k], reach2, batch);
        float ax = 0, ay = 0, az = 0;
        sumBatch<M, N>(pair, batch, ax, ay, az);
        fx[k] += ax;
        fy[k] += ay;
        fz[k] += az;
        scatterBatch(batch, fx, fy, fz);
    }
}

using SumGroup = void (*)(const PairForce&, const GlobuleArrays&, const Globules&,
                          const CellGroup&, float, Scratch&, Accelerations&);

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

/// The group loop for the material's exponents.
SumGroup kernelFor(const PairForce& pair) {
    return forExponents(pair, []<int M, int N>() { return SumGroup(sumGroup<M, N>); });
}

/// Builds the grid over @p g for pairs of reach up to @p cutoff (of the largest radius
/// sum), puts @p g in grid order and zeroes @p forces. @return whether all radii are equal.
template <typename Cutoff>
bool prepare(Globules& g, NeighborWorkspace& w, Accelerations& forces, bool heat, Cutoff&& cutoff) {
    const std::size_t n = g.size();
    forces.resize(n);
    const auto [smallest, largest] = radiusRange(g);
    w.largestRadius = largest;
    w.grid.build(g.px.data(), g.py.data(), g.pz.data(), n, cutoff(2.0f * largest));
    // The accelerations are about to be cleared: their array is the reorder's scratch
    // (no extra 4 bytes per globule).
    g.permute(w.grid.sortedOrder(), forces.x);
    clearForces(forces, n, heat);
    return smallest == largest;
}

GlobuleArrays arraysOf(const Globules& s) {
    return {s.px.data(), s.py.data(), s.pz.data(), s.vx.data(),
            s.vy.data(), s.vz.data(), s.radius.data()};
}

/// pairForcesSorting (forces.h).
void sortingOne(Globules& g, const PairForce& pair, NeighborWorkspace& w, Accelerations& forces) {
    if (g.empty()) {
        clearForces(forces, 0, false);
        return;
    }
    const bool uniformRadius =
        prepare(g, w, forces, false, [&](float sum) { return pair.cutoff(sum); });
    const SumGroup sum = kernelFor(pair);
    const GlobuleArrays arrays = arraysOf(g);
    const float groupReach = groupReachOf(w.grid);
    forEachGroup(w, g, 1, uniformRadius, [&](const CellGroup& group, Scratch& scratch) {
        sum(pair, arrays, g, group, groupReach, scratch, forces);
    });
}

/// One pair's sum over a batch: sumBatch for the pair's exponents.
using SumBatch = void (*)(const PairForce&, NeighborBatch&, float&, float&, float&);

SumBatch batchKernelFor(const PairForce& pair) {
    return forExponents(pair, []<int M, int N>() { return SumBatch(sumBatch<M, N>); });
}

/// sumGroup for several materials: the group's candidates gathered once per material,
/// and each member summed over each material's with that pair's constants and kernel, in
/// material order. The table is symmetric: pairs(a, b) is the pair from either side.
void sumGroupMixed(const PairTable& pairs, const std::vector<SumBatch>& kernels,
                   const GlobuleArrays& arrays, const Globules& s, const CellGroup& group,
                   float groupReach, Scratch& w, Accelerations& forces) {
    const std::size_t kinds = pairs.materials();
    w.clear(group);
    for (int b = 0; b < group.runCount; ++b) {
        collectGroupCandidatesByMaterial(arrays, group.runs[b].first, group.runs[b].second,
                                         group.lo, group.hi, groupReach, s.material.data(),
                                         w.candidates);
    }
    NeighborBatch& batch = w.batch;
    float *fx = forces.x.data(), *fy = forces.y.data(), *fz = forces.z.data();
    for (uint32_t k = group.first; k < group.last; ++k) {
        const std::size_t mine = s.material[k];
        float ax = 0, ay = 0, az = 0;
        for (std::size_t kind = 0; kind < kinds; ++kind) {
            const GroupCandidates& candidates = w.candidates[kind];
            if (candidates.count == 0) continue;
            const PairForce& pair = pairs(mine, kind);
            const float reach = pair.cutoff(1.0f);
            w.from[kind] = candidates.after(k, w.from[kind]);
            batch.count = 0;
            collectNeighbors(candidates, w.from[kind], s.px[k], s.py[k], s.pz[k], s.vx[k],
                             s.vy[k], s.vz[k], s.radius[k], reach * reach, batch);
            kernels[mine * kinds + kind](pair, batch, ax, ay, az);
            scatterBatch(batch, fx, fy, fz);
        }
        fx[k] += ax;
        fy[k] += ay;
        fz[k] += az;
    }
}

/// pairForcesSorting (forces.h).
void sortingTable(Globules& g, const PairTable& pairs, NeighborWorkspace& w, Accelerations& forces) {
    if (g.empty()) {
        clearForces(forces, 0, false);
        return;
    }
    const bool uniformRadius =
        prepare(g, w, forces, false, [&](float sum) { return pairs.cutoff(sum); });
    const std::size_t kinds = pairs.materials();
    std::vector<SumBatch> kernels;
    for (std::size_t a = 0; a < kinds; ++a) {
        for (std::size_t b = 0; b < kinds; ++b) kernels.push_back(batchKernelFor(pairs(a, b)));
    }
    const GlobuleArrays arrays = arraysOf(g);
    const float groupReach = groupReachOf(w.grid);
    forEachGroup(w, g, kinds, uniformRadius, [&](const CellGroup& group, Scratch& scratch) {
        sumGroupMixed(pairs, kernels, arrays, g, group, groupReach, scratch, forces);
    });
}

/// The blended force sum for a pair's exponents.
using SumBlended = void (*)(const ThermalPair&, float, NeighborBatch&, float&, float&, float&);

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

/// sumGroupMixed for thermal scenes: the candidates of a group gathered once per
/// material with their temperatures; for each member and material, the heat summed as
/// the neighbours are collected and the force in the pair's phase (thermal_kernel.h).
/// The phase is chosen from all the group's candidates of that material, so it holds for
/// every pair the member takes: each pair's force is its blend, whichever way is taken.
void sumGroupThermal(const std::vector<ThermalKernel>& kernels, std::size_t kinds,
                     const GlobuleArrays& arrays, const Globules& s, const CellGroup& group,
                     float groupReach, Scratch& w, Accelerations& forces) {
    w.clear(group);
    for (int b = 0; b < group.runCount; ++b) {
        if (kinds == 1) {
            collectGroupCandidates(arrays, group.runs[b].first, group.runs[b].second, group.lo,
                                   group.hi, groupReach, w.candidates[0]);
        } else {
            collectGroupCandidatesByMaterial(arrays, group.runs[b].first, group.runs[b].second,
                                             group.lo, group.hi, groupReach, s.material.data(),
                                             w.candidates);
        }
    }
    for (std::size_t kind = 0; kind < kinds; ++kind) {
        const GroupCandidates& c = w.candidates[kind];
        if (c.count > 0) w.ranges[kind] = temperatureRange(c.temperature.data(), c.count);
    }
    NeighborBatch& batch = w.batch;
    float *fx = forces.x.data(), *fy = forces.y.data(), *fz = forces.z.data();
    float* heatOf = forces.heat.data();
    for (uint32_t k = group.first; k < group.last; ++k) {
        const std::size_t mine = s.materialOf(k);
        const float t = s.temperature[k];
        float ax = 0, ay = 0, az = 0, heat = 0;
        for (std::size_t kind = 0; kind < kinds; ++kind) {
            const GroupCandidates& candidates = w.candidates[kind];
            if (candidates.count == 0) continue;
            const ThermalKernel& kernel = kernels[mine * kinds + kind];
            const ThermalPhase phase =
                phaseOf(kernel.pair, t, w.ranges[kind].first, w.ranges[kind].second);
            NeighborHeat flow{t, kernel.pair.conductance, phase == ThermalPhase::Blend};
            w.from[kind] = candidates.after(k, w.from[kind]);
            batch.count = 0;
            collectNeighbors<true>(candidates, w.from[kind], s.px[k], s.py[k], s.pz[k], s.vx[k],
                                   s.vy[k], s.vz[k], s.radius[k], kernel.reach2, batch, &flow);
            heat += flow.heat;
            if (phase == ThermalPhase::Blend) {
                kernel.blended(kernel.pair, t, batch, ax, ay, az);
            } else if (phase == ThermalPhase::Solid) {
                kernel.solid(kernel.pair.solid, batch, ax, ay, az);
            } else {
                kernel.liquid(kernel.pair.liquid, batch, ax, ay, az);
            }
            scatterBatch(batch, fx, fy, fz);
            scatterHeat(batch, kernel.pair.conductance, heatOf);
        }
        fx[k] += ax;
        fy[k] += ay;
        fz[k] += az;
        heatOf[k] += heat;
    }
}

/// pairForcesThermal (forces.h); the dispatcher has checked the arrays.
void thermal(Globules& g, const PairTable& pairs, NeighborWorkspace& w, Accelerations& forces) {
    if (g.empty()) {
        clearForces(forces, 0, true);
        return;
    }
    const bool uniformRadius =
        prepare(g, w, forces, true, [&](float sum) { return pairs.cutoff(sum); });
    const std::size_t kinds = pairs.materials();
    std::vector<ThermalKernel> kernels;
    for (std::size_t a = 0; a < kinds; ++a) {
        for (std::size_t b = 0; b < kinds; ++b) kernels.emplace_back(pairs.thermal(a, b));
    }
    GlobuleArrays arrays = arraysOf(g);
    arrays.temperature = g.temperature.data();
    const float groupReach = groupReachOf(w.grid);
    forEachGroup(w, g, kinds, uniformRadius, [&](const CellGroup& group, Scratch& scratch) {
        sumGroupThermal(kernels, kinds, arrays, g, group, groupReach, scratch, forces);
    });
}

}  // namespace

// The one symbol this build exports (force_kernels.h).
namespace GLOBULAR_SIMD_NAMESPACE {
extern const ForceKernels kForceKernels;
const ForceKernels kForceKernels{sortingOne, sortingTable, thermal};
}  // namespace GLOBULAR_SIMD_NAMESPACE

}  // namespace globular
