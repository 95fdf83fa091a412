#include "thermal_sources.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace globular {

ThermalSources::ThermalSources(const ThermalSettings& settings, std::vector<HeaterSettings> heaters,
                               const std::vector<MaterialSettings>& materials, Vec3 gravity,
                               const GroundSettings& ground)
    : mEnabled(settings.enabled),
      mSettings(settings),
      mHeaters(std::move(heaters)),
      mGravity(gravity),
      mGround(ground) {
    for (const MaterialSettings& m : materials) {
        mHeatCapacity.push_back(float(m.heatCapacity));
        mExpansion.push_back(float(m.expansion));
    }
}

void ThermalSources::apply(const Globules& g, const ColliderSet& colliders,
                           Accelerations& out) const {
    if (!mEnabled) return;
    // Colliders that exchange heat, with their poses now.
    std::vector<std::size_t> exchanging;
    for (std::size_t k = 0; k < colliders.size(); ++k) {
        if (colliders[k].settings.heatTransfer > 0) exchanging.push_back(k);
    }
    const std::vector<ColliderMotion> motions =
        exchanging.empty() ? std::vector<ColliderMotion>{} : colliders.motions();
    const float ambient = float(mSettings.ambient), cooling = float(mSettings.cooling);
    const float reference = float(mSettings.reference);
    const bool groundExchange = mGround.enabled && mSettings.groundTransfer > 0;
    const float groundTemperature = float(mSettings.groundTemperature);
    const float groundTransfer = float(mSettings.groundTransfer);
    const bool groundAtSurface = mGround.contact == "surface";
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, g.size(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const std::size_t material = g.materialOf(i);
            const float t = g.temperature[i];
            const float capacity = g.mass[i] * mHeatCapacity[material];
            float heat = out.heat[i];  // from the neighbours
            for (const HeaterSettings& h : mHeaters) {
                if (h.contains(g.position(i))) heat += float(h.power);
            }
            float rate = heat / capacity + cooling * (ambient - t);
            if (groundExchange) {
                const float contactY = groundAtSurface ? g.py[i] - g.radius[i] : g.py[i];
                if (contactY < float(mGround.height)) rate += groundTransfer * (groundTemperature - t);
            }
            for (std::size_t k : exchanging) {
                const Collider& c = colliders[k];
                const double phi = c.solid.sample(motions[k].now.toLocal(g.position(i))).phi;
                if (phi - (c.surfaceContact ? g.radius[i] : 0.0) < 0) {
                    rate += float(c.settings.heatTransfer) * (float(c.settings.temperature) - t);
                }
            }
            out.heat[i] = rate;
            // Buoyancy: -beta (T - T_ref) g per unit mass.
            const float lift = -mExpansion[material] * (t - reference);
            if (lift != 0) {
                out.x[i] += lift * float(mGravity.x);
                out.y[i] += lift * float(mGravity.y);
                out.z[i] += lift * float(mGravity.z);
            }
        }
    });
}

}  // namespace globular
