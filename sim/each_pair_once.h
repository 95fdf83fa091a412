#pragma once
// The force loop that evaluates each pair once (Newton's third law), with AVX-512 and a
// uniform radius (force_kernels.cpp): the groups visited colour by colour
// (cell_schedule.h), each member summed over the candidates after it in grid order, and
// the opposite forces (and heat) gathered per list and added to the candidates once the
// list is done. Included by the per-path builds of the force loops only.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "accelerations.h"
#include "cell_group.h"
#include "cell_schedule.h"
#include "pair_kernel.h"
#include "thermal_kernel.h"

#if defined(__AVX512F__)
namespace globular {

/// What a thread of the loop that evaluates each pair once keeps from one group to the
/// next, across colours and steps: its lists grow to the largest group's once.
struct LaterPairsScratch {
    NeighborGrid::RunCursor cursor;
    CellGroup group;
    std::vector<GroupCandidates> candidates;  ///< the group's later candidates, per material
    GroupParts parts;
    std::vector<Reactions> reactions;      ///< the group's, per material
    std::vector<Reactions> partReactions;  ///< a crowded group's part's, per material
    std::vector<uint32_t> later;  ///< per material: the member's first candidate after it
    std::vector<std::pair<float, float>> ranges;  ///< thermal: the group's temperatures

    /// Ready for @p kinds materials.
    void prepare(std::size_t kinds, bool temperatures) {
        if (candidates.size() != kinds) {
            candidates.assign(kinds, GroupCandidates{});
            reactions.assign(kinds, Reactions{});
            partReactions.assign(kinds, Reactions{});
        }
        for (GroupCandidates& c : candidates) {
            c.uniformRadius = true;
            c.indexed = true;
        }
        parts.temperatures = temperatures;
    }
};

/// The scratch of the calling thread. A cache only: what it holds is rebuilt for every
/// group; kept per thread so that the colours of every step do not allocate again. Static,
/// not inline: an inline function's local would be a unique global symbol, which the
/// isolated build (cmake/isolated_build.cmake) cannot make local to its path.
static LaterPairsScratch& laterPairsScratch() {
    thread_local LaterPairsScratch scratch;
    return scratch;
}

/// Calls visit(lists, members, count, part) for each list of candidates that the members
/// of @p group ([first, group.last) of @p s) sum over: the group's @p candidates (part
/// false), or in a crowded group each part's (GroupParts), filtered from them (part true:
/// their sources are places in the group's lists). Members come in ascending order, as
/// do the candidates of every list (grid order), globule indices in both.
template <typename Visit>
void forEachList(const Globules& s, std::size_t first, const CellGroup& group, float groupReach,
                 const std::vector<GroupCandidates>& candidates, GroupParts& parts,
                 Visit&& visit) {
    if (group.last - first < GroupParts::kMinMembers) {
        parts.members.resize(group.last - first);
        for (std::size_t k = first; k < group.last; ++k) parts.members[k - first] = uint32_t(k);
        visit(candidates, parts.members.data(), uint32_t(parts.members.size()), false);
        return;
    }
    splitGroup(s, first, group, parts);
    parts.candidates.resize(candidates.size());
    for (std::size_t kind = 0; kind < candidates.size(); ++kind) {
        parts.candidates[kind].uniformRadius = candidates[kind].uniformRadius;
        parts.candidates[kind].indexed = true;
        parts.candidates[kind].reserve(candidates[kind].count);
    }
    for (int p = 0; p < parts.count; ++p) {
        for (std::size_t kind = 0; kind < candidates.size(); ++kind) {
            GroupCandidates& part = parts.candidates[kind];
            part.clear();
            GlobuleArrays from = arraysOf(candidates[kind], parts.temperatures);
            from.index = candidates[kind].index.data();
            collectGroupCandidates(from, 0, candidates[kind].count, parts.lo[p].data(),
                                   parts.hi[p].data(), groupReach, part);
        }
        visit(parts.candidates, parts.members.data() + parts.start[p],
              parts.start[p + 1] - parts.start[p], true);
    }
}

/// Adds the entries of @p r (one per entry of @p list) back where @p list's entries were
/// collected from (GroupCandidates::sources): to @p x, @p y, @p z (and @p heat) at the
/// same places. Entries that are zero are left out: an entry that met no member may lie
/// up to a cell edge and a hair away, where a row of the same colour writes at the same
/// time (CellSchedule), and a masked store leaves its globule untouched. A block no member
/// met stores through an empty mask: no branch to skip it (which mispredicted).
inline void addBack(const GroupCandidates& list, const Reactions& r, float* x, float* y, float* z,
             float* heat) {
    const __m512 zero = _mm512_setzero_ps();
    // Locals, not members: the masked stores below may alias anything.
    const float *fromX = r.x.data(), *fromY = r.y.data(), *fromZ = r.z.data();
    const float* fromHeat = heat ? r.heat.data() : nullptr;
    const GroupCandidates::Source* sources = list.sources.data();
    const uint32_t count = list.sourceCount;
    uint32_t c = 0;
    for (uint32_t b = 0; b < count; ++b) {
        const GroupCandidates::Source source = sources[b];
        const __mmask16 kept = source.kept;
        const auto entries = [&](const float* from) {
            return _mm512_maskz_expand_ps(kept, _mm512_loadu_ps(from + c));
        };
        const __m512 rx = entries(fromX), ry = entries(fromY), rz = entries(fromZ);
        const __m512 rh = heat ? entries(fromHeat) : zero;
        c += uint32_t(__builtin_popcount(kept));
        const __mmask16 met = _mm512_cmp_ps_mask(rx, zero, _CMP_NEQ_UQ) |
                              _mm512_cmp_ps_mask(ry, zero, _CMP_NEQ_UQ) |
                              _mm512_cmp_ps_mask(rz, zero, _CMP_NEQ_UQ) |
                              _mm512_cmp_ps_mask(rh, zero, _CMP_NEQ_UQ);
        const auto add = [&](float* to, __m512 v) {
            float* at = to + source.at;
            _mm512_mask_storeu_ps(at, met, _mm512_add_ps(_mm512_maskz_loadu_ps(met, at), v));
        };
        add(x, rx);
        add(y, ry);
        add(z, rz);
        if (heat) add(heat, rh);
    }
}

/// Runs @p sumGroup(first, last, scratch) for every group of @p schedule, colour by
/// colour, the tasks of a colour in parallel (CellSchedule): what a group writes, to its
/// members and their neighbours, no other group of its colour writes.
template <typename SumGroup>
void forEachGroupByColour(const CellSchedule& schedule, SumGroup&& sumGroup) {
    const auto& groups = schedule.groups();
    for (int colour = 0; colour < CellSchedule::kColours; ++colour) {
        const auto [begin, end] = schedule.colourTasks(colour);
        if (begin == end) continue;
        tbb::parallel_for(tbb::blocked_range<uint32_t>(begin, end, 1),
                          [&](const tbb::blocked_range<uint32_t>& r) {
                              LaterPairsScratch& scratch = laterPairsScratch();
                              // The cursor's runs are of the grid it last searched, perhaps
                              // an earlier step's.
                              scratch.cursor.valid = false;
                              for (uint32_t task = r.begin(); task != r.end(); ++task) {
                                  const auto [g, gEnd] = schedule.taskGroups(task);
                                  for (const uint32_t* q = g; q != gEnd; ++q) {
                                      sumGroup(groups[*q].first, groups[*q].last, scratch);
                                  }
                              }
                          });
    }
}

/// The loop that evaluates each pair once (Newton's third law), with AVX-512 and a uniform
/// radius: a group's candidates are those after its first member in grid order, one list
/// per material, and each member sums over those after itself in its list; the opposite
/// forces (and heat) gather per list and go to the candidates once the list is done
/// (addBack). sumMember(w, lists, k, reactions) sums member k over lists[kind] from
/// w.later[kind] on and adds its force (and heat) to @p forces[k]. Half the pairs of the
/// loop that gathers each globule's own sum, for one scatter per list; the sums' order
/// follows the colours and grid order, never the threads. @p forces (and heat) are zero.
template <typename SumMember>
void sumEachPairOnce(const NeighborGrid& grid, const CellSchedule& schedule, const Globules& s,
                     std::size_t kinds, bool thermal, Accelerations& forces,
                     SumMember&& sumMember) {
    const GlobuleArrays arrays{s.px.data(),     s.py.data(), s.pz.data(),
                               s.vx.data(),     s.vy.data(), s.vz.data(),
                               s.radius.data(), thermal ? s.temperature.data() : nullptr};
    const float groupReach = grid.cellSize() * 1.0001f;
    float* heat = thermal ? forces.heat.data() : nullptr;
    forEachGroupByColour(schedule, [&](uint32_t first, uint32_t last, LaterPairsScratch& w) {
        w.prepare(kinds, thermal);
        groupOf(grid, s, first, last, w.cursor, w.group);
        for (GroupCandidates& c : w.candidates) {
            c.reserve(w.group.total);
            c.clear();
        }
        for (int b = 0; b < w.group.runCount; ++b) {
            const uint32_t from = std::max(w.group.runs[b].first, first + 1);
            const uint32_t end = w.group.runs[b].second;
            if (from >= end) continue;
            if (kinds == 1) {
                collectGroupCandidates(arrays, from, end, w.group.lo, w.group.hi, groupReach,
                                       w.candidates[0]);
            } else {
                collectGroupCandidatesByMaterial(arrays, from, end, w.group.lo, w.group.hi,
                                                 groupReach, s.material.data(), w.candidates);
            }
        }
        if (thermal) {
            // The phases follow the group's candidates, as in sumRangeThermal.
            w.ranges.resize(kinds);
            for (std::size_t kind = 0; kind < kinds; ++kind) {
                const GroupCandidates& c = w.candidates[kind];
                if (c.count > 0) w.ranges[kind] = temperatureRange(c.temperature.data(), c.count);
            }
        }
        for (std::size_t kind = 0; kind < kinds; ++kind) {
            w.reactions[kind].clear(w.candidates[kind].count, thermal);
        }
        forEachList(
            s, first, w.group, groupReach, w.candidates, w.parts,
            [&](const std::vector<GroupCandidates>& lists, const uint32_t* members,
                uint32_t count, bool part) {
                std::vector<Reactions>& reactions = part ? w.partReactions : w.reactions;
                if (part) {
                    for (std::size_t kind = 0; kind < kinds; ++kind) {
                        reactions[kind].clear(lists[kind].count, thermal);
                    }
                }
                w.later.assign(kinds, 0);
                for (uint32_t m = 0; m < count; ++m) {
                    const uint32_t k = members[m];
                    for (std::size_t kind = 0; kind < kinds; ++kind) {
                        const GroupCandidates& list = lists[kind];
                        uint32_t& later = w.later[kind];
                        while (later < list.count && list.index[later] <= k) ++later;
                    }
                    sumMember(w, lists, k, reactions);
                }
                if (!part) return;
                for (std::size_t kind = 0; kind < kinds; ++kind) {
                    Reactions& group = w.reactions[kind];
                    addBack(lists[kind], reactions[kind], group.x.data(), group.y.data(),
                            group.z.data(), thermal ? group.heat.data() : nullptr);
                }
            });
        for (std::size_t kind = 0; kind < kinds; ++kind) {
            addBack(w.candidates[kind], w.reactions[kind], forces.x.data(), forces.y.data(),
                    forces.z.data(), heat);
        }
    });
}

/// Adds (fx, fy, fz) to globule @p k's force in @p forces.
inline void addForce(Accelerations& forces, uint32_t k, float fx, float fy, float fz) {
    forces.x[k] += fx;
    forces.y[k] += fy;
    forces.z[k] += fz;
}

/// @p forces (and @p heat) set to zero, for the loop that evaluates each pair once.
inline void zeroForces(Accelerations& forces, bool heat) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, forces.x.size(), 16384),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (auto* a : {&forces.x, &forces.y, &forces.z, &forces.heat}) {
                              if (a == &forces.heat && !heat) continue;
                              std::fill(a->begin() + r.begin(), a->begin() + r.end(), 0.0f);
                          }
                      });
}

}  // namespace globular
#endif
