#pragma once
// The `[thermal]` section and `[[heater]]` sections of a scene: temperature, and what
// heats and cools the globules. Each globule carries a temperature T and a heat capacity
// C = m c (its mass times its material's heat_capacity); per unit time
//   C dT/dt = sum over neighbours j of k_ij w_ij (T_j - T_i)     conduction
//           + C cooling (ambient - T)                             Newton cooling in air
//           + C h (T_surface - T), while touching                 the ground, a collider
//           + P, inside a heater                                   heater power
// with w_ij = 1 - d^2 / (reach^2 (r_i + r_j)^2) falling to zero at the force's reach.
// Conduction is symmetric, so without sources it conserves the total heat sum C T.
// Buoyancy adds -beta (T - reference) m g to each globule (beta: its material's expansion).

#include <vector>

#include "vec3.h"

namespace globular {

class SettingsSection;

struct ThermalSettings {
    bool enabled = false;   ///< off: no temperature at all (no cost)
    double ambient = 20;    ///< air temperature, degrees
    double cooling = 0;     ///< Newton cooling rate toward ambient, 1/s
    double reference = 20;  ///< T_ref of buoyancy
    double groundTemperature = 20;
    double groundTransfer = 0;  ///< contact heat transfer rate with the ground, 1/s; 0: insulating

    void describe(SettingsSection& section);
};

/// A box that heats (power > 0) or cools (power < 0) the globules inside it.
struct HeaterSettings {
    Vec3 min{-1, 0, -1}, max{1, 1, 1};
    double power = 10;  ///< heat per second into each globule inside

    void describe(SettingsSection& section);
    /// @throw SceneError naming the key when the box is empty.
    void validate(const SettingsSection& section) const;
    bool contains(Vec3 p) const {
        return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y && p.z >= min.z &&
               p.z <= max.z;
    }
};

}  // namespace globular
