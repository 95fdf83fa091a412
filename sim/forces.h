#pragma once
// Accelerations of every globule: the pair force of eq. (2) summed over neighbours,
// plus gravity and the ground penalty of eq. (9). With AVX-512, one radius for every
// globule and integer exponents, each pair is evaluated once and its opposite force added
// to the other globule (Newton's third law, each_pair_once.h), rows of cells coloured so
// that no two threads write one globule (cell_schedule.h). Elsewhere forces are gathered
// per globule, each pair evaluated from both sides, so loops write only their own index.
// Either way: no locks, no atomics, and a sum order that follows the positions alone,
// hence bit-identical results for any thread count.
// The globules themselves are kept in neighbour-grid order (re-sorted every step) rather
// than copied into it: no second copy of the state (issue 7's memory budget).

#include <utility>
#include <vector>

#include "accelerations.h"
#include "collider_set.h"
#include "force_kernels.h"
#include "material_pairs.h"
#include "globules.h"
#include "neighbor_grid.h"
#include "pair_force.h"
#include "pair_kernel.h"
#include "simd_path.h"
#include "simulation_settings.h"
#include "thermal_sources.h"

namespace globular {

struct ExternalForces {
    Vec3 gravity{0, -9.8, 0};
    GroundSettings ground;
    ColliderSet colliders;  ///< [[collider]] (collider_contact.h)
    ThermalSources thermal;  ///< [thermal]: off by default
};

/// Sum of pair forces on each globule over all others: the paper's O(N^2) reference.
void pairForcesAllPairs(const Globules& globules, const PairForce& pair, Accelerations& forces);

/// The same sums over cell-list neighbours only. Sorts @p globules into neighbour-grid
/// order first (every array, in place; the order depends only on the positions), so
/// that a globule's neighbours lie in a few contiguous runs; @p forces come out in the
/// new order. @p path: the build of the loop that runs (simd_path.h).
void pairForcesSorting(Globules& globules, const PairForce& pair, NeighborWorkspace& workspace,
                       Accelerations& forces, SimdPath path = activeSimdPath());

/// pairForcesSorting for globules that must keep their order (tests, tools): works on a
/// sorted copy; @p forces are in the order of @p globules.
void pairForcesGrid(const Globules& globules, const PairForce& pair,
                    NeighborWorkspace& workspace, Accelerations& forces,
                    SimdPath path = activeSimdPath());

/// Builds @p grid over @p globules with cells one interaction cutoff wide.
/// @return the smallest and largest radius (the cutoff follows the largest).
std::pair<float, float> buildGrid(const Globules& globules, const PairForce& pair,
                                  NeighborGrid& grid);

/// pairForcesSorting for several materials: each pair with its materials' constants from
/// @p pairs (globules.material gives each globule's). A cell's candidates are split by
/// material, so every pair still goes through the single-material kernels.
void pairForcesSorting(Globules& globules, const PairTable& pairs, NeighborWorkspace& workspace,
                       Accelerations& forces, SimdPath path = activeSimdPath());

/// pairForcesSorting for thermal scenes (thermal_kernel.h): each pair's constants blended
/// by its mean temperature, and the heat flowing into each globule in @p forces.heat.
/// globules.temperature must be set (globules.material too with several materials).
void pairForcesThermal(Globules& globules, const PairTable& pairs, NeighborWorkspace& workspace,
                       Accelerations& forces, SimdPath path = activeSimdPath());

/// The O(N^2) reference of pairForcesThermal.
void pairForcesThermalAllPairs(const Globules& globules, const PairTable& pairs,
                               Accelerations& forces);

/// The O(N^2) reference for several materials.
void pairForcesAllPairs(const Globules& globules, const PairTable& pairs, Accelerations& forces);

/// The ground's penalty force of eq. (9) on one globule, y component (normal +y).
float groundForce(const GroundSettings& ground, float y, float vy, float radius);

/// The ground's constants as the per-globule loops read them: no string compares there.
struct GroundPenalty {
    bool enabled = false, atSurface = false;
    float height = 0, ks = 0, kd = 0;

    explicit GroundPenalty(const GroundSettings& ground)
        : enabled(ground.enabled),
          atSurface(ground.contact == "surface"),
          height(float(ground.height)),
          ks(float(ground.ks)),
          kd(float(ground.kd)) {}
    /// groundForce of these constants.
    float force(float y, float vy, float radius) const {
        const float depth = (atSurface ? y - radius : y) - height;  // (x_p - p_g) . N_g
        if (depth >= 0.0f) return 0.0f;
        return -ks * depth - kd * vy;
    }
};

/// Computes accelerations for a whole system; owns the neighbour grid between calls.
class ForceField {
public:
    ForceField(PairForce pair, ExternalForces external, bool allPairs = false)
        : mPairs(pair), mExternal(std::move(external)), mGround(mExternal.ground), mAllPairs(allPairs) {}
    /// Several materials: @p pairs gives each pair's constants.
    ForceField(PairTable pairs, ExternalForces external, bool allPairs = false)
        : mPairs(std::move(pairs)), mExternal(std::move(external)), mGround(mExternal.ground),
          mAllPairs(allPairs) {}

    /// Fills @p out for @p globules, which the grid method reorders first (see
    /// pairForcesSorting); @p out is in their new order.
    void compute(Globules& globules, Accelerations& out);

    const PairTable& pairs() const { return mPairs; }
    /// The step about to be taken: colliders' static friction needs its length, and the
    /// colliders' clock starts at its time (the integrator moves it on, collider_set.h).
    void setStep(double time, double dt) {
        mExternal.colliders.setTime(time);
        mStepSeconds = dt;
    }
    ColliderSet& colliders() { return mExternal.colliders; }
    /// The build of the grid force loops this field runs (activeSimdPath() unless set;
    /// the caller checks simdPathSupported).
    SimdPath simdPath() const { return mSimd; }
    void setSimdPath(SimdPath path) { mSimd = path; }
    const ColliderSet& colliders() const { return mExternal.colliders; }

private:
    /// Gravity, the ground and the colliders on globule @p i, added to its pair force
    /// in @p out, and the result turned into an acceleration (all in double: a collider's
    /// distance and friction are not in the hot loop). What the globule does to a
    /// dynamic collider is added to @p reactions (one per body).
    /// Colliders whose @p far flag is set are out of reach and skipped.
    void addExternalWithColliders(const Globules& g, std::size_t i,
                                  const std::vector<ColliderMotion>& motions,
                                  const std::vector<uint8_t>& far, Accelerations& out,
                                  std::vector<Wrench>& reactions) const;
    /// Gravity and the ground only, in single precision (the loop without colliders).
    void addGravityAndGround(const Globules& g, std::size_t i, Accelerations& out) const;
    void addExternalForces(Globules& g, Accelerations& out);

    PairTable mPairs;
    ExternalForces mExternal;
    GroundPenalty mGround;  ///< mExternal.ground, ready for the loops
    bool mAllPairs;
    NeighborWorkspace mWorkspace;
    SimdPath mSimd = activeSimdPath();
    double mStepSeconds = 0;
    float mLargestRadius = 1;  ///< of the last compute's globules
};

}  // namespace globular
