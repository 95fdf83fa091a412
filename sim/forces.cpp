#include "forces.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>

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

void pairForcesGrid(const Globules& g, const PairForce& pair, NeighborGrid& grid,
                    Accelerations& forces) {
    const std::size_t n = g.size();
    forces.resize(n);
    if (n == 0) return;
    buildGrid(g, pair, grid);
    const std::vector<uint32_t>& order = grid.sortedOrder();
    // Visit globules in grid order so consecutive ones share neighbours in cache.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t k = r.begin(); k != r.end(); ++k) {
                              const uint32_t i = order[k];
                              float f[3] = {0, 0, 0};
                              grid.forEachCandidate(g.px[i], g.py[i], g.pz[i], [&](uint32_t j) {
                                  if (j != i) addPair(g, pair, i, j, f);
                              });
                              forces.x[i] = f[0];
                              forces.y[i] = f[1];
                              forces.z[i] = f[2];
                          }
                      });
}

float groundForce(const GroundSettings& ground, float y, float vy, float radius) {
    const float contactY = ground.contact == "surface" ? y - radius : y;
    const float depth = contactY - float(ground.height);  // (x_p - p_g) . N_g
    if (depth >= 0.0f) return 0.0f;
    return -float(ground.ks) * depth - float(ground.kd) * vy;
}

const std::vector<uint32_t>& ForceField::gridOrder(const Globules& globules) {
    buildGrid(globules, mPair, mGrid);
    return mGrid.sortedOrder();
}

void ForceField::compute(const Globules& g, Accelerations& out) {
    if (mAllPairs) {
        pairForcesAllPairs(g, mPair, out);
    } else {
        pairForcesGrid(g, mPair, mGrid, out);
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
