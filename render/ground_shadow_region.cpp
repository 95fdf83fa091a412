#include "ground_shadow_region.h"

#include <algorithm>
#include <cmath>

namespace globular::detail {

std::optional<GroundRect> groundShadowRegion(const FrameUniforms& f, const TexelRect& drawn,
                                             double groundHeight) {
    if (drawn.empty()) return GroundRect{};
    const Mat4& m = f.lightViewProj;
    // The light's view is orthographic: map coordinates are affine in the world.
    if (m(3, 0) != 0 || m(3, 1) != 0 || m(3, 2) != 0 || m(3, 3) != 1) return std::nullopt;
    const double size = f.shadowMapSize;
    // The filter's reach from a point's own texel: its disc (radius at least 0.75
    // texels), each tap a 2x2 bilinear footprint, and a texel more for rounding.
    const double reach = std::max(double(f.shadowSoftness), 0.75) + 2.0;
    const double u0 = (drawn.x0 - reach) / size, u1 = (drawn.x1 + 1 + reach) / size;
    const double v0 = (drawn.y0 - reach) / size, v1 = (drawn.y1 + 1 + reach) / size;

    // A ground point (x, groundHeight, z) is looked up raised along its normal (+y) by
    // the filter's normal offset, at map coordinates s = A (x, z) + b.
    const double lifted = groundHeight + (1.5 + 0.5 * f.shadowSoftness) * f.shadowTexel;
    const double a00 = 0.5 * m(0, 0), a01 = 0.5 * m(0, 2), a10 = 0.5 * m(1, 0), a11 = 0.5 * m(1, 2);
    const double b0 = 0.5 * (m(0, 1) * lifted + m(0, 3)) + 0.5;
    const double b1 = 0.5 * (m(1, 1) * lifted + m(1, 3)) + 0.5;
    const double det = a00 * a11 - a01 * a10;
    const double scale = std::max({std::abs(a00), std::abs(a01), std::abs(a10), std::abs(a11)});
    if (!(std::abs(det) > 1e-6 * scale * scale)) return std::nullopt;  // a grazing light

    GroundRect region{INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (double u : {u0, u1}) {
        for (double v : {v0, v1}) {
            const double du = u - b0, dv = v - b1;
            const double x = (a11 * du - a01 * dv) / det;
            const double z = (a00 * dv - a10 * du) / det;
            region.x0 = std::min(region.x0, x), region.x1 = std::max(region.x1, x);
            region.z0 = std::min(region.z0, z), region.z1 = std::max(region.z1, z);
        }
    }
    // A pixel's footprint on the ground at distance d from an eye h above it is about
    // pixelAngle d^2 / h across; a pixel's centre lies within one footprint of any of its
    // samples. Distances peak at the rectangle's corners (d^2 is convex).
    const double height = std::abs(f.eye.y - groundHeight);
    if (!(height > 1e-9)) return std::nullopt;
    double footprint = 0;
    for (double x : {region.x0, region.x1}) {
        for (double z : {region.z0, region.z1}) {
            const double dx = x - f.eye.x, dz = z - f.eye.z;
            footprint = std::max(footprint, f.pixelAngle * (dx * dx + height * height + dz * dz) / height);
        }
    }
    const double grow = 1.5 * footprint;
    region.x0 -= grow, region.z0 -= grow, region.x1 += grow, region.z1 += grow;
    if (!std::isfinite(region.x0 + region.x1 + region.z0 + region.z1)) return std::nullopt;
    return region;
}

}  // namespace globular::detail
