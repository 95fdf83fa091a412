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
    /// The largest reach of any pair for radii summing to @p radiusSum.
    float cutoff(float radiusSum) const;

    /// The mixing rule's constants for materials @p x and @p y.
    static MaterialSettings mixed(const MaterialSettings& x, const MaterialSettings& y);

private:
    std::size_t mCount = 1;
    std::vector<PairForce> mPairs;  ///< mCount x mCount, symmetric
};

/// Index of the material named @p name in @p materials ("" names the first), or -1.
int materialIndex(const std::vector<MaterialSettings>& materials, const std::string& name);

}  // namespace globular
