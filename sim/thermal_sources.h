#pragma once
// The per-globule terms of the heat equation (thermal_settings.h) and buoyancy: the pair
// loop leaves the heat flowing in from neighbours; this turns it into a rate of change of
// temperature and adds Newton cooling, contact with the ground and with colliders that
// have a heat_transfer, and heaters. Buoyancy, -beta (T - T_ref) g per unit mass, is
// added to the accelerations.

#include <vector>

#include "accelerations.h"
#include "collider_set.h"
#include "globules.h"
#include "material.h"
#include "simulation_settings.h"
#include "thermal_settings.h"

namespace globular {

class ThermalSources {
public:
    /// Off: a scene without temperature.
    ThermalSources() = default;
    ThermalSources(const ThermalSettings& settings, std::vector<HeaterSettings> heaters,
                   const std::vector<MaterialSettings>& materials, Vec3 gravity,
                   const GroundSettings& ground);

    bool enabled() const { return mEnabled; }

    /// @p out's heat (heat flowing in from neighbours, per globule) becomes dT/dt with
    /// every other source added; buoyancy goes into its accelerations. @p colliders are
    /// at the step's time.
    void apply(const Globules& globules, const ColliderSet& colliders, Accelerations& out) const;

private:
    bool mEnabled = false;
    ThermalSettings mSettings;
    std::vector<HeaterSettings> mHeaters;
    std::vector<float> mHeatCapacity, mExpansion;  ///< per material
    Vec3 mGravity{0, 0, 0};
    GroundSettings mGround;
};

}  // namespace globular
