#include "stable_step.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "simulation.h"

namespace globular {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSamples = 256;  ///< midpoint rule over each window

/// int from @p from to @p to of 4 pi D^2 f(D) dD (0 when the range is empty).
template <typename F>
double shellIntegral(double from, double to, F&& f) {
    if (!(to > from)) return 0;
    const double h = (to - from) / kSamples;
    double sum = 0;
    for (int k = 0; k < kSamples; ++k) {
        const double d = from + (k + 0.5) * h;
        sum += 4 * kPi * d * d * f(d);
    }
    return sum * h;
}

/// |dF/dD| of the radial force F(D) = D S_r(D) (b1 D^-m - b2 D^-n) of @p p for radii
/// summing to @p sum, at rest (no drag).
double radialStiffness(const PairForce& p, double sum, double d) {
    const double w2 = double(p.cr) * p.cr * sum * sum;
    const double s = 1 - d * d / w2;
    if (s <= 0) return 0;
    const double g = p.b1 * std::pow(d, -p.m) - p.b2 * std::pow(d, -p.n);
    const double dg = -p.m * p.b1 * std::pow(d, -p.m - 1) + p.n * p.b2 * std::pow(d, -p.n - 1);
    const double ds = -2 * d / w2;
    return std::abs(s * g + d * ds * g + d * s * dg);
}

struct Extent {
    float smallestMass = std::numeric_limits<float>::infinity();
    float smallestRadius = std::numeric_limits<float>::infinity();
    float largestRadius = 0;
    float fastest2 = 0;  ///< largest |v|^2
};

Extent extentOf(const Globules& g) {
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, g.size(), 4096), Extent{},
        [&](const tbb::blocked_range<std::size_t>& r, Extent e) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                e.smallestMass = std::min(e.smallestMass, g.mass[i]);
                e.smallestRadius = std::min(e.smallestRadius, g.radius[i]);
                e.largestRadius = std::max(e.largestRadius, g.radius[i]);
                e.fastest2 = std::max(e.fastest2, g.vx[i] * g.vx[i] + g.vy[i] * g.vy[i] + g.vz[i] * g.vz[i]);
            }
            return e;
        },
        [](Extent a, const Extent& b) {
            a.smallestMass = std::min(a.smallestMass, b.smallestMass);
            a.smallestRadius = std::min(a.smallestRadius, b.smallestRadius);
            a.largestRadius = std::max(a.largestRadius, b.largestRadius);
            a.fastest2 = std::max(a.fastest2, b.fastest2);
            return a;
        });
}

}  // namespace

StableStep::StableStep(const SimulationSetup& setup) {
    const std::vector<MaterialSettings> materials = setup.materials();
    const PairTable table(materials, setup.materialPairs);
    for (std::size_t a = 0; a < table.materials(); ++a) {
        for (std::size_t b = 0; b < table.materials(); ++b) {
            const ThermalPair& t = table.thermal(a, b);
            for (const PairForce& p : {table(a, b), t.solid, t.liquid}) mPairs.push_back(p);
            if (setup.thermal.enabled) mConductance = std::max(mConductance, double(t.conductance));
        }
    }
    mReach = table.cutoff(1.0f);
    if (setup.ground.enabled) {
        mSpringK = setup.ground.ks;
        mDamperK = setup.ground.kd;
    }
    double colliderK = 0, colliderD = 0;
    for (const ColliderSettings& c : setup.colliders) {
        colliderK = std::max(colliderK, c.ks);
        colliderD = std::max(colliderD, c.kd);
    }
    mSpringK += colliderK;
    mDamperK += colliderD;
    mSmallestHeatCapacity = std::numeric_limits<double>::infinity();
    for (const MaterialSettings& m : materials) {
        mSmallestHeatCapacity = std::min(mSmallestHeatCapacity, m.heatCapacity);
    }
}

double StableStep::contactBound(double density, double mass, double radius,
                                double heatCapacity) const {
    const double sum = 2 * radius;
    // Nearest neighbour of a close packing at this density: the closest the sums reach.
    const double nearest = density > 0 ? std::cbrt(std::sqrt(2.0) / density) : INFINITY;
    double stiffness = 0, drag = 0;
    for (const PairForce& p : mPairs) {
        const double radialEnd = double(p.cr) * sum, dragEnd = double(p.cd) * sum;
        stiffness = std::max(stiffness, shellIntegral(nearest, radialEnd, [&](double d) {
                                 return radialStiffness(p, sum, d);
                             }));
        drag = std::max(drag, shellIntegral(nearest, dragEnd, [&](double d) {
                            return 1 - d * d / (dragEnd * dragEnd);
                        }));
    }
    const double w2 = (mSpringK + (2.0 / 3.0) * density * stiffness) / mass;
    const double c = (mDamperK + (2.0 / 3.0) * density * drag) / mass;
    double bound = INFINITY;
    if (w2 > 0 || c > 0) bound = 4 / (c + std::sqrt(c * c + 4 * w2));
    if (mConductance > 0) {
        // Explicit conduction: the heating-rate matrix's largest eigenvalue is at most twice
        // a row's sum (Gershgorin), so dt <= 2 C / (2 k sum w).
        const double end = double(mReach) * sum;
        const double weights = density * shellIntegral(std::min(nearest, end), end, [&](double d) {
                                   return 1 - d * d / (end * end);
                               });
        if (weights > 0) bound = std::min(bound, mass * heatCapacity / (mConductance * weights));
    }
    return bound;
}

StableStep::Bound StableStep::bound(const Globules& g) {
    Bound b;
    b.contact = b.speed = INFINITY;
    if (g.empty()) return b;
    const Extent e = extentOf(g);
    const double cell = double(mReach) * 2 * e.largestRadius;
    const uint32_t most = mCrowded.most(g.px.data(), g.py.data(), g.pz.data(), g.size(), cell);
    const double density = double(most) / (cell * cell * cell);
    b.contact = contactBound(density, e.smallestMass, e.largestRadius, mSmallestHeatCapacity);
    if (e.fastest2 > 0) b.speed = kSpeedFraction * e.smallestRadius / std::sqrt(double(e.fastest2));
    return b;
}

}  // namespace globular
