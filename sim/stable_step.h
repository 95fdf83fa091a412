#pragma once
// The longest step the explicit integrators take without blowing up, for
// `[simulation] adaptive = true` (Simulation::advanceFrame). Two bounds, the smaller wins:
//
// 1. Contact. Near contact a globule is a mass m on springs and dampers: the ground's
//    (k_s, k_d), the stiffest collider's, and its neighbours' pair forces. Linearised, each
//    mode is x'' = -c x' - w^2 x, which semi-implicit Euler keeps bounded iff
//        w^2 dt^2 + 2 c dt <= 4,   i.e.   dt <= 4 / (c + sqrt(c^2 + 4 w^2)).
//    A neighbour at distance D adds the radial force's stiffness |dF/dD| to w^2 m and the
//    drag window S_d(D) to c m. Summed over a medium of number density rho (the densest
//    neighbour-grid cell of the step), from the nearest-neighbour distance of a packing at
//    that density, (sqrt 2 / rho)^(1/3), to the windows' ends:
//        w^2 m = (2/3) rho int 4 pi D^2 |F'(D)| dD,   c m = (2/3) rho int 4 pi D^2 S_d(D) dD,
//    2 for the relative motion of two globules, 1/3 for the mean projection on one axis.
//    In thermal scenes conduction adds its own explicit bound, C / (k rho int 4 pi D^2 w dD).
// 2. Speed. The fastest globule moves at most kSpeedFraction of the smallest radius per
//    step, so that no approach skips through the steep part of the repulsion.
//
// Only the state decides the bound (no history), so a resumed run takes the same steps.

#include <vector>

#include "crowded_cell.h"
#include "globules.h"
#include "material_pairs.h"

namespace globular {

struct SimulationSetup;

class StableStep {
public:
    /// The fraction of the bound taken: margin for what the linearisation leaves out.
    static constexpr double kSafety = 0.8;
    /// Speed bound: the fastest globule crosses this fraction of a radius per step.
    static constexpr double kSpeedFraction = 0.1;

    explicit StableStep(const SimulationSetup& setup);

    /// What limits a step now, seconds.
    struct Bound {
        double contact = 0;  ///< springs, dampers and conduction at the densest spot
        double speed = 0;    ///< the fastest globule
        double step() const { return kSafety * (contact < speed ? contact : speed); }
    };
    /// The bound for @p globules as they stand. The density is the most crowded cell's
    /// (cells one search reach wide, counted exactly: CrowdedCell), in any order of the
    /// globules. Not for concurrent calls on one object (the count's table is reused).
    Bound bound(const Globules& globules);

    /// The contact bound in a medium of @p density globules per unit volume, for the
    /// scene's lightest globule, largest radius and most conductive material.
    double contactBound(double density, double mass, double radius, double heatCapacity) const;

private:
    std::vector<PairForce> mPairs;      ///< every pair of materials, every phase
    double mSpringK = 0, mDamperK = 0;  ///< ground + stiffest collider
    double mConductance = 0;            ///< largest; 0 without temperature
    double mSmallestHeatCapacity = 1;   ///< per unit mass
    float mReach = 3;                   ///< of the neighbour search, in r_i + r_j
    CrowdedCell mCrowded;               ///< the densest cell's count
};

}  // namespace globular
