#pragma once
// How a material looks when it is drawn as a liquid: what it absorbs (Beer-Lambert) and
// how it bends light (index of refraction). Filled from a scene's [material] keys (look,
// absorption, density, ior) and used by mode = "fluid" and by liquid surface meshes.

#include <vector>

#include "vec3.h"

namespace globular {

struct MaterialSettings;

struct LiquidOptics {
    /// Drawn as a liquid (transmission, absorption, Fresnel reflection); false: opaque.
    bool liquid = true;
    /// Absorption coefficient per world unit, linear RGB: light crossing a depth d keeps
    /// exp(-sigma d) of each channel. [material] absorption times density.
    Vec3 sigma{0.30, 0.09, 0.035};
    double ior = 1.33;  ///< index of refraction (water 1.33)
};

/// The optics of @p material: look = "liquid", or "auto" with preset = "liquid", is a
/// liquid; sigma = absorption * density.
LiquidOptics liquidOptics(const MaterialSettings& material);

/// The optics of material @p index, the default liquid when @p all has no such entry.
inline LiquidOptics opticsOf(const std::vector<LiquidOptics>& all, std::size_t index) {
    return index < all.size() ? all[index] : LiquidOptics{};
}

}  // namespace globular
