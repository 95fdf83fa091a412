#include "thermal_settings.h"

#include "errors.h"
#include "settings_schema.h"

namespace globular {

void ThermalSettings::describe(SettingsSection& s) {
    s.flag("enabled", enabled,
           "globules carry a temperature (conduction, cooling, heaters, melting, buoyancy)");
    s.number("ambient", ambient, NumberRange::between(-1e6, 1e6), "air temperature");
    s.number("cooling", cooling, NumberRange::nonNegative(),
             "Newton cooling rate toward ambient, 1/s");
    s.number("reference", reference, NumberRange::between(-1e6, 1e6),
             "T_ref of buoyancy -beta (T - T_ref) m g");
    s.number("ground_temperature", groundTemperature, NumberRange::between(-1e6, 1e6),
             "temperature of the ground plane");
    s.number("ground_transfer", groundTransfer, NumberRange::nonNegative(),
             "heat transfer rate with the ground while touching it, 1/s (0: insulating)");
}

void HeaterSettings::describe(SettingsSection& s) {
    s.vec3("min", min, NumberRange::between(-1e6, 1e6), "lowest corner of the box");
    s.vec3("max", max, NumberRange::between(-1e6, 1e6), "highest corner of the box");
    s.number("power", power, NumberRange::between(-1e9, 1e9),
             "heat per second into each globule inside (negative: cools)");
}

void HeaterSettings::validate(const SettingsSection& s) const {
    if (!(min.x < max.x && min.y < max.y && min.z < max.z)) {
        throw SceneError(s.describeKey("max") + ": every coordinate of max must exceed min's");
    }
}

}  // namespace globular
