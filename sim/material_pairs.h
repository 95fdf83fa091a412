#pragma once
// Several materials in one shot: the force constants of every pair of materials. A
// material meets itself with its own constants; two different materials by the mixing
// rule below, unless a `[[material_pair]]` section gives a constant for the pair:
//   b1, r0, m, n   the means of the two materials'
//   C_r, C_d       the wider of the two windows (the larger number)
// The table is symmetric, so the force stays equal and opposite for any mix and momentum
// is conserved.

#include <string>
#include <vector>

#include "material.h"
#include "pair_force.h"

namespace globular {

class SettingsSection;

/// A `[[material_pair]]` section: constants for the pair of materials `a` and `b`; a
/// constant left at 0 comes from the mixing rule.
struct MaterialPairSettings {
    std::string a, b;  ///< material names
    double b1 = 0, r0 = 0, m = 0, n = 0, cr = 0, cd = 0;

    void describe(SettingsSection& section);
};

/// What temperature does to one pair of materials (thermal scenes): its constants blend
/// from `solid` to `liquid` as the pair's mean temperature T crosses the melting range,
/// with s = smoothstep((T - tSolid) / (tLiquid - tSolid)); and heat flows between the two at
/// `conductance` per degree. A pair of materials without phases has solid == liquid.
/// Both phases of a pair of two materials follow the mixing rule, from the two
/// materials' phases (a material without phases brings its own constants to both), with
/// the melting range the mean of the two materials' (or the one that has phases').
struct ThermalPair {
    PairForce solid, liquid;
    /// tLiquid <= tSolid: no melting range (s = 0). s is exactly 1 from tLiquid up, so the
    /// liquid's constants hold there bit for bit.
    float tSolid = 0, tLiquid = 0, invRange = 0;
    float conductance = 0;           ///< the harmonic mean of the two conductivities
};

class PairTable {
public:
    /// One material: its own constants (the paper's single-material scenes).
    explicit PairTable(const PairForce& pair);
    /// @p materials by index (globule material k is materials[k]), @p pairs naming them.
    /// @throw SceneError for a pair naming a material that does not exist, or one twice.
    PairTable(const std::vector<MaterialSettings>& materials,
              const std::vector<MaterialPairSettings>& pairs);

    std::size_t materials() const { return mCount; }
    const PairForce& operator()(std::size_t a, std::size_t b) const { return mPairs[a * mCount + b]; }
    const ThermalPair& thermal(std::size_t a, std::size_t b) const { return mThermal[a * mCount + b]; }
    /// The largest reach of any pair, in any phase, for radii summing to @p radiusSum.
    float cutoff(float radiusSum) const;

    /// The mixing rule's constants for materials @p x and @p y.
    static ForceConstants mixed(const ForceConstants& x, const ForceConstants& y);

private:
    /// The constants of every pair when material k has @p constants[k]: the mixing rule
    /// and then @p pairs' overrides (which must name @p materials).
    static std::vector<PairForce> table(const std::vector<const ForceConstants*>& constants,
                                        const std::vector<MaterialSettings>& materials,
                                        const std::vector<MaterialPairSettings>& pairs);

    std::size_t mCount = 1;
    std::vector<PairForce> mPairs;      ///< mCount x mCount, symmetric
    std::vector<ThermalPair> mThermal;  ///< the same pairs' phases and conduction
};

/// Index of the material named @p name in @p materials ("" names the first), or -1.
int materialIndex(const std::vector<MaterialSettings>& materials, const std::string& name);

}  // namespace globular
