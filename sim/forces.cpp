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

/// Adds the force of @p j on @p i to @p f.
inline void addPair(const Globules& g, const PairForce& pair, std::size_t i, std::size_t j,
                    float f[3]) {
    pair.accumulate(g.px[i] - g.px[j], g.py[i] - g.py[j], g.pz[i] - g.pz[j],
                    g.vx[i] - g.vx[j], g.vy[i] - g.vy[j], g.vz[i] - g.vz[j],
                    g.radius[i] + g.radius[j], f);
}

void checkThermal(const Globules& g, const PairTable& pairs) {
    if (g.temperature.size() != g.size()) throw Error("a thermal scene, but globules without a temperature");
    if (pairs.materials() > 1 && g.material.size() != g.size()) {
        throw Error("several materials, but globules without one");
    }
}

}  // namespace

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

void pairForcesAllPairs(const Globules& g, const PairForce& pair, Accelerations& forces) {
    pairForcesAllPairs(g, PairTable(pair), forces);
}

std::pair<float, float> buildGrid(const Globules& g, const PairForce& pair, NeighborGrid& grid) {
    const auto range = radiusRange(g);
    grid.build(g.px.data(), g.py.data(), g.pz.data(), g.size(), pair.cutoff(2.0f * range.second));
    return range;
}

void pairForcesSorting(Globules& g, const PairForce& pair, NeighborWorkspace& w,
                       Accelerations& forces, SimdPath path) {
    forceKernels(path).sorting(g, pair, w, forces);
}

void pairForcesSorting(Globules& g, const PairTable& pairs, NeighborWorkspace& w,
                       Accelerations& forces, SimdPath path) {
    if (!g.empty() && g.material.size() != g.size()) {
        throw Error("several materials, but globules without one");
    }
    forceKernels(path).sortingTable(g, pairs, w, forces);
}

void pairForcesThermal(Globules& g, const PairTable& pairs, NeighborWorkspace& w,
                       Accelerations& forces, SimdPath path) {
    if (!g.empty()) checkThermal(g, pairs);
    forceKernels(path).thermal(g, pairs, w, forces);
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
                                  // (The reference sums the heat itself, below.)
                                  const float ti = g.temperature[i];
                                  sumBlendedBatch<0, 0>(pair, ti, reach * reach, batch, fx, fy, fz);
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
                    Accelerations& forces, SimdPath path) {
    Globules sorted = g;
    Accelerations sortedForces;
    pairForcesSorting(sorted, pair, w, sortedForces, path);
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
                  : pairForcesThermal(g, mPairs, mWorkspace, out, mSimd);
    } else if (mAllPairs) {
        one ? pairForcesAllPairs(g, mPairs(0, 0), out) : pairForcesAllPairs(g, mPairs, out);
    } else {
        one ? pairForcesSorting(g, mPairs(0, 0), mWorkspace, out, mSimd)
            : pairForcesSorting(g, mPairs, mWorkspace, out, mSimd);
    }
    if (!mExternal.colliders.empty()) {  // the grid already knows it
        mLargestRadius = mAllPairs ? radiusRange(g).second : mWorkspace.largestRadius;
    }
    addExternalForces(g, out);
    mExternal.thermal.apply(g, mExternal.colliders, out);
}

}  // namespace globular