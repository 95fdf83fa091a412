#include "material.h"

#include <cmath>

#include "errors.h"
#include "reporter.h"
#include "settings_schema.h"

namespace globular {

void ForceConstants::describeConstants(SettingsSection& s) {
    s.choice("preset", preset, {"powder", "liquid", "solid", "custom"},
             "window constants of eq. (6)-(8); custom requires cr and cd");
    s.number("r0", r0, NumberRange::positive(), "rest distance, world units");
    s.number("b1", b1, NumberRange::positive(), "radial force strength (paper: [1, 3])");
    s.number("m", m, NumberRange::positive(), "repulsion exponent (paper: m > n)");
    s.number("n", n, NumberRange::positive(), "attraction exponent");
    s.number("alpha", alpha, NumberRange::positive(), "liquid drag reach C_d = alpha r0");
    s.number("cr", cr, NumberRange::nonNegative(),
             "radial window C_r as a number (0 = from preset)");
    s.number("cd", cd, NumberRange::nonNegative(),
             "drag window C_d as a number (0 = from preset)");
}

void MaterialSettings::describe(SettingsSection& s) {
    s.text("name", name, "how emitters and [[material_pair]] name it (several materials)");
    describeConstants(s);
    s.vec3("color", color, NumberRange::between(0, 1),
           "sRGB colour for [render] color_by = \"material\"; [0, 0, 0]: one of a palette "
           "by the material's place");
    s.number("roughness", roughness, NumberRange::between(0, 1),
             "render: perceptual roughness of its surface, 0 = mirror, 1 = fully rough (GGX)");
    s.number("metallic", metallic, NumberRange::between(0, 1),
             "render: 0 = dielectric (plastic, water: 4% reflectance, the rest diffused), 1 = "
             "metal (reflects its base colour, diffuses nothing)");
    s.number("subsurface", subsurface, NumberRange::between(0, 1),
             "render: wrap of the diffuse light past the shadow line, the soft look of light "
             "scattered under the surface (wax, soap, flesh); 0 = Lambert. It keeps the "
             "light a lit sphere reflects in all and dims the side facing the light by "
             "1 / (1 + subsurface)");
    s.choice("look", look, {"auto", "liquid", "opaque"},
             "render: how mode = \"surface\" and \"fluid\" draw it; liquid: transmission "
             "that refracts what lies behind, Beer-Lambert absorption and Fresnel reflection; "
             "opaque: a shaded solid (fluid mode: spheres); auto: liquid for preset = "
             "\"liquid\", else opaque");
    s.vec3("absorption", absorption, NumberRange::nonNegative(),
           "render (liquid look): absorption coefficient per world unit at density 1, linear "
           "RGB; light crossing a depth d keeps exp(-absorption * density * d) of each channel "
           "(absorbing red most gives a blue liquid)");
    s.number("density", density, NumberRange::nonNegative(),
             "render (liquid look): multiplies absorption; 0 = perfectly clear");
    s.number("ior", ior, NumberRange::between(1, 3),
             "render (liquid look): index of refraction (water 1.33)");
    s.number("heat_capacity", heatCapacity, NumberRange::positive(),
             "thermal: heat capacity per unit mass");
    s.number("conductivity", conductivity, NumberRange::nonNegative(),
             "thermal: heat flow between touching globules per degree (pairs of materials: "
             "the harmonic mean)");
    s.number("expansion", expansion, NumberRange::any(),
             "thermal: expansion coefficient beta, buoyancy -beta (T - T_ref) m g");
    s.number("t_solid", tSolid, NumberRange::any(),
             "thermal: at or below it the [material.solid] constants hold");
    s.number("t_liquid", tLiquid, NumberRange::any(),
             "thermal: at or above it the [material.liquid] constants hold");
}

Vec3 materialColor(const MaterialSettings& material, std::size_t index) {
    if (!(material.color == Vec3{0, 0, 0})) return material.color;
    // The render default's blue first, then colours far from it and from each other.
    static const Vec3 kPalette[] = {{0.16, 0.42, 0.82}, {0.90, 0.45, 0.10}, {0.95, 0.80, 0.20},
                                    {0.25, 0.65, 0.30}, {0.80, 0.15, 0.15}, {0.55, 0.35, 0.75},
                                    {0.20, 0.75, 0.80}, {0.90, 0.55, 0.70}};
    return kPalette[index % (sizeof kPalette / sizeof kPalette[0])];
}

double ForceConstants::resolvedCr() const {
    if (cr > 0) return cr;
    return preset == "solid" ? 2.0 * r0 : r0;
}

double ForceConstants::resolvedCd() const {
    if (cd > 0) return cd;
    if (preset == "solid") return 2.0 * r0;
    if (preset == "liquid") return alpha * r0;
    return r0;
}

void ForceConstants::validate(const SettingsSection& s, Reporter& reporter) const {
    if (preset == "custom" && (cr <= 0 || cd <= 0)) {
        throw SceneError(s.describeKey("preset") +
                         ": the custom preset needs both cr and cd set to positive numbers");
    }
    if (m <= n) {
        reporter.warn(s.describeKey("m") + ": m = " + std::to_string(m) +
                      " is not greater than n = " + std::to_string(n) +
                      "; the paper recommends m > n (attraction then dominates at short range)");
    }
    if (b1 < 1.0 || b1 > 3.0) {
        reporter.warn(s.describeKey("b1") + ": b1 = " + std::to_string(b1) +
                      " is outside the paper's stable range [1, 3]");
    }
    if (preset == "liquid" && cd == 0 && (alpha < 1.5 || alpha > 2.0)) {
        reporter.warn(s.describeKey("alpha") + ": alpha = " + std::to_string(alpha) +
                      " is outside the paper's liquid range [1.5, 2]");
    }
}

void MaterialSettings::validate(const SettingsSection& s, Reporter& reporter) const {
    ForceConstants::validate(s, reporter);
    if (!phases) {
        for (const char* key : {"t_solid", "t_liquid"}) {
            if (s.placeOf(key)) {
                throw SceneError(s.describeKey(key) +
                                 ": a melting range needs a [material.solid] or "
                                 "[material.liquid] table of constants");
            }
        }
        return;
    }
    if (!s.placeOf("t_solid") || !s.placeOf("t_liquid")) {
        throw SceneError(s.describeKey(s.placeOf("t_solid") ? "t_liquid" : "t_solid") +
                         ": a material with phases needs both t_solid and t_liquid");
    }
    if (!(tSolid < tLiquid)) {
        throw SceneError(s.describeKey("t_solid") + " = " + numberForMessage(tSolid) +
                         " must lie below t_liquid = " + numberForMessage(tLiquid));
    }
}

}  // namespace globular
