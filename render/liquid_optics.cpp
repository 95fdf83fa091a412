#include "liquid_optics.h"

#include "material.h"

namespace globular {

LiquidOptics liquidOptics(const MaterialSettings& m) {
    LiquidOptics o;
    o.liquid = m.look == "liquid" || (m.look == "auto" && m.preset == "liquid");
    o.sigma = m.absorption * m.density;
    o.ior = m.ior;
    return o;
}

}  // namespace globular
