#pragma once
// A grid cell's group of globules, as the force loops take it (force_kernels.cpp): the
// members, their box, the runs of candidates around them and, in a crowded cell, its
// parts, each with candidates of its own. Included by the per-path builds of the force
// loops only (cmake/isolated_build.cmake keeps each build's copy to itself).

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "globules.h"
#include "neighbor_grid.h"
#include "pair_kernel.h"

namespace globular {

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
inline Member memberAt(const Globules& s, std::size_t k) {
    return {s.px[k], s.py[k], s.pz[k], s.vx[k], s.vy[k], s.vz[k], s.radius[k]};
}
#endif

/// Grows the box [@p lo, @p hi] to hold globule @p k of @p s.
inline void growBox(const Globules& s, std::size_t k, float lo[3], float hi[3]) {
    const float p[3] = {s.px[k], s.py[k], s.pz[k]};
    for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], p[a]);
        hi[a] = std::max(hi[a], p[a]);
    }
}

/// @p group as the globules [first, @p last) of @p s, which share a cell.
inline void groupOf(const NeighborGrid& grid, const Globules& s, std::size_t first, std::size_t last,
             NeighborGrid::RunCursor& cursor, CellGroup& group) {
    const float start[3] = {s.px[first], s.py[first], s.pz[first]};
    for (int a = 0; a < 3; ++a) group.lo[a] = group.hi[a] = start[a];
    for (std::size_t k = first + 1; k < last; ++k) growBox(s, k, group.lo, group.hi);
    group.last = last;
    group.runCount = grid.neighborRuns(s.px[first], s.py[first], s.pz[first], cursor, group.runs);
    group.total = 0;
    for (int b = 0; b < group.runCount; ++b) group.total += group.runs[b].second - group.runs[b].first;
}

/// The group of globule @p first's cell within [first, end) of @p s.
inline void groupAt(const NeighborGrid& grid, const Globules& s, std::size_t first, std::size_t end,
             NeighborGrid::RunCursor& cursor, CellGroup& group) {
    const auto cell = grid.cellOf(s.px[first], s.py[first], s.pz[first]);
    std::size_t last = first + 1;
    while (last < end && grid.cellOf(s.px[last], s.py[last], s.pz[last]) == cell) ++last;
    groupOf(grid, s, first, last, cursor, group);
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
inline void splitGroup(const Globules& s, std::size_t first, const CellGroup& group, GroupParts& parts) {
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
inline GlobuleArrays arraysOf(const GroupCandidates& c, bool temperatures) {
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

}  // namespace globular
