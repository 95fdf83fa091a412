#include "forces.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <climits>

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

float maxRadius(const Globules& g) {
    if (g.empty()) return 1.0f;
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, g.size(), 4096), 0.0f,
        [&](const tbb::blocked_range<std::size_t>& r, float m) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) m = std::max(m, g.radius[i]);
            return m;
        },
        [](float a, float b) { return std::max(a, b); });
}

}  // namespace

void pairForcesAllPairs(const Globules& g, const PairForce& pair, Accelerations& forces) {
    const std::size_t n = g.size();
    forces.resize(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 64),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i) {
                              float f[3] = {0, 0, 0};
                              for (std::size_t j = 0; j < n; ++j) {
                                  if (j != i) addPair(g, pair, i, j, f);
                              }
                              forces.x[i] = f[0];
                              forces.y[i] = f[1];
                              forces.z[i] = f[2];
                          }
                      });
}

void buildGrid(const Globules& g, const PairForce& pair, NeighborGrid& grid) {
    grid.build(g.px.data(), g.py.data(), g.pz.data(), g.size(),
               pair.cutoff(2.0f * maxRadius(g)));
}

namespace {

void gatherSorted(const Globules& g, const std::vector<uint32_t>& order, SortedGlobules& s) {
    const std::size_t n = g.size();
    for (auto* a : {&s.x, &s.y, &s.z, &s.vx, &s.vy, &s.vz, &s.radius}) a->resize(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t k = r.begin(); k != r.end(); ++k) {
                              const uint32_t i = order[k];
                              s.x[k] = g.px[i];
                              s.y[k] = g.py[i];
                              s.z[k] = g.pz[i];
                              s.vx[k] = g.vx[i];
                              s.vy[k] = g.vy[i];
                              s.vz[k] = g.vz[i];
                              s.radius[k] = g.radius[i];
                          }
                      });
}

/// Sums forces for sorted positions [begin, end), writing each to its globule's index.
template <int M, int N>
void sumRange(const PairForce& pair, const NeighborWorkspace& w,
              const std::vector<uint32_t>& order, std::size_t begin, std::size_t end,
              Accelerations& forces) {
    const SortedGlobules& s = w.sorted;
    const GlobuleArrays arrays{s.x.data(),  s.y.data(),  s.z.data(),     s.vx.data(),
                               s.vy.data(), s.vz.data(), s.radius.data()};
    const float reach = pair.cutoff(1.0f), reach2 = reach * reach;
    std::array<NeighborGrid::Run, NeighborGrid::kMaxRuns> runs;
    std::array<int64_t, 3> cell{INT64_MIN, 0, 0};
    int runCount = 0;
    NeighborBatch batch;
    for (std::size_t k = begin; k < end; ++k) {
        // Consecutive globules mostly share a cell: reuse its neighbour runs.
        const auto here = w.grid.cellOf(s.x[k], s.y[k], s.z[k]);
        if (here != cell) {
            cell = here;
            runCount = w.grid.neighborRuns(s.x[k], s.y[k], s.z[k], runs);
            std::size_t candidates = 0;
            for (int b = 0; b < runCount; ++b) candidates += runs[b].second - runs[b].first;
            batch.reserve(candidates);
        }
        batch.count = 0;
        for (int b = 0; b < runCount; ++b) {
            collectNeighbors(arrays, runs[b].first, runs[b].second, s.x[k], s.y[k], s.z[k],
                             s.vx[k], s.vy[k], s.vz[k], s.radius[k], reach2, batch);
        }
        float fx = 0, fy = 0, fz = 0;
        sumBatch<M, N>(pair, batch, fx, fy, fz);
        const uint32_t i = order[k];
        forces.x[i] = fx;
        forces.y[i] = fy;
        forces.z[i] = fz;
    }
}

using SumRange = void (*)(const PairForce&, const NeighborWorkspace&,
                          const std::vector<uint32_t>&, std::size_t, std::size_t,
                          Accelerations&);

/// The kernel for the material's exponents: unrolled powers for the pairs the paper
/// uses, pow() otherwise.
SumRange kernelFor(const PairForce& pair) {
    if (pair.integerExponents) {
        const int m = pair.mInt, n = pair.nInt;
        if (m == 5 && n == 3) return sumRange<5, 3>;
        if (m == 5 && n == 1) return sumRange<5, 1>;
        if (m == 5 && n == 4) return sumRange<5, 4>;
        if (m == 10 && n == 3) return sumRange<10, 3>;
        if (m == 7 && n == 5) return sumRange<7, 5>;
        if (m == 12 && n == 6) return sumRange<12, 6>;
    }
    return sumRange<0, 0>;
}

}  // namespace

void pairForcesGrid(const Globules& g, const PairForce& pair, NeighborWorkspace& w,
                    Accelerations& forces) {
    const std::size_t n = g.size();
    forces.resize(n);
    if (n == 0) return;
    buildGrid(g, pair, w.grid);
    const std::vector<uint32_t>& order = w.grid.sortedOrder();
    gatherSorted(g, order, w.sorted);
    const SumRange sum = kernelFor(pair);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          sum(pair, w, order, r.begin(), r.end(), forces);
                      });
}

float groundForce(const GroundSettings& ground, float y, float vy, float radius) {
    const float contactY = ground.contact == "surface" ? y - radius : y;
    const float depth = contactY - float(ground.height);  // (x_p - p_g) . N_g
    if (depth >= 0.0f) return 0.0f;
    return -float(ground.ks) * depth - float(ground.kd) * vy;
}

const std::vector<uint32_t>& ForceField::gridOrder(const Globules& globules) {
    buildGrid(globules, mPair, mWorkspace.grid);
    return mWorkspace.grid.sortedOrder();
}

void ForceField::compute(const Globules& g, Accelerations& out) {
    if (mAllPairs) {
        pairForcesAllPairs(g, mPair, out);
    } else {
        pairForcesGrid(g, mPair, mWorkspace, out);
    }
    const float gx = float(mExternal.gravity.x), gy = float(mExternal.gravity.y),
                gz = float(mExternal.gravity.z);
    const GroundSettings& ground = mExternal.ground;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, g.size(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i) {
                              float fy = out.y[i];
                              if (ground.enabled) fy += groundForce(ground, g.py[i], g.vy[i], g.radius[i]);
                              const float invMass = 1.0f / g.mass[i];
                              out.x[i] = out.x[i] * invMass + gx;
                              out.y[i] = fy * invMass + gy;
                              out.z[i] = out.z[i] * invMass + gz;
                          }
                      });
}

}  // namespace globular
