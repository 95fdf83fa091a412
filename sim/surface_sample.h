#pragma once
// What a collider's solid tells a point: how far it is from the surface, and which way
// is out.

#include "vec3.h"

namespace globular {

/// Signed distance to a solid's surface and the outward normal there.
struct SurfaceSample {
    double phi = 0;        ///< negative inside the solid, world units
    Vec3 normal{0, 1, 0};  ///< unit, pointing out of the solid
};

}  // namespace globular
