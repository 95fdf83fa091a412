#pragma once
// Accelerations of every globule: the pair force of eq. (2) summed over neighbours,
// plus gravity and the ground penalty of eq. (9). Forces are gathered per globule (each
// pair is evaluated from both sides) so loops write only their own index: no locks, no
// atomics, and the same sum order, hence bit-identical results, for any thread count.

#include <vector>

#include "globules.h"
#include "neighbor_grid.h"
#include "pair_force.h"
#include "pair_kernel.h"
#include "simulation_settings.h"

namespace globular {

struct Accelerations {
    std::vector<float> x, y, z;  ///< world units / s^2
    void resize(std::size_t n) {
        x.resize(n);
        y.resize(n);
        z.resize(n);
    }
};

struct ExternalForces {
    Vec3 gravity{0, -9.8, 0};
    GroundSettings ground;
};

/// Sum of pair forces on each globule over all others: the paper's O(N^2) reference.
void pairForcesAllPairs(const Globules& globules, const PairForce& pair, Accelerations& forces);

/// Globule data in neighbour-grid order: contiguous runs per grid bucket.
struct SortedGlobules {
    std::vector<float> x, y, z, vx, vy, vz, radius;
};

/// The neighbour grid and the globules copied into its order, reused between steps.
struct NeighborWorkspace {
    NeighborGrid grid;
    SortedGlobules sorted;
};

/// The same sums over cell-list neighbours only; the workspace is rebuilt from the
/// positions. Candidates are read from contiguous grid-ordered copies.
void pairForcesGrid(const Globules& globules, const PairForce& pair,
                    NeighborWorkspace& workspace, Accelerations& forces);

/// Builds @p grid over @p globules with cells one interaction cutoff wide.
void buildGrid(const Globules& globules, const PairForce& pair, NeighborGrid& grid);

/// The ground's penalty force of eq. (9) on one globule, y component (normal +y).
float groundForce(const GroundSettings& ground, float y, float vy, float radius);

/// Computes accelerations for a whole system; owns the neighbour grid between calls.
class ForceField {
public:
    ForceField(PairForce pair, ExternalForces external, bool allPairs = false)
        : mPair(pair), mExternal(external), mAllPairs(allPairs) {}

    void compute(const Globules& globules, Accelerations& out);

    /// Rebuilds the neighbour grid for @p globules; @return their indices in grid order.
    const std::vector<uint32_t>& gridOrder(const Globules& globules);

    const PairForce& pair() const { return mPair; }
private:
    PairForce mPair;
    ExternalForces mExternal;
    bool mAllPairs;
    NeighborWorkspace mWorkspace;
};

}  // namespace globular
