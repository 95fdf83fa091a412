#pragma once
// The light arriving from every direction (image-based lighting), prepared on the CPU:
// a lat-long radiance image (the procedural sky, or an HDR file) becomes
//  - the irradiance E(n) as 9 spherical-harmonic coefficients (order 2), for diffuse
//    light: Ramamoorthi and Hanrahan, "An Efficient Representation for Irradiance
//    Environment Maps", SIGGRAPH 2001;
//  - a cube map whose mip levels hold the radiance pre-filtered by a GGX lobe of growing
//    roughness (GGX importance sampling with the source's mip level chosen by the sample's
//    solid angle), for specular light with the split-sum approximation: Karis, "Real
//    Shading in Unreal Engine 4", SIGGRAPH 2013 course notes; Colbert and Krivanek, "GPU-
//    Based Importance Sampling", GPU Gems 3, 2007.
// No GL here: environment_light.h uploads the result.

#include <array>
#include <filesystem>
#include <vector>

#include "vec3.h"

namespace globular {

/// Linear RGB radiance over the sphere of directions, equirectangular: column u covers
/// the azimuth phi = 2 pi (u + 0.5) / width - pi, row v the polar angle theta = pi (v + 0.5)
/// / height from straight up (+y). Direction (sin theta sin phi, cos theta, -sin theta cos
/// phi): the image's middle looks along -z.
struct LatLongImage {
    int width = 0, height = 0;
    std::vector<float> rgb;  ///< 3 floats per pixel, rows from the top (+y) down

    Vec3 at(int x, int y) const {
        const float* p = &rgb[3 * (std::size_t(y) * width + x)];
        return {p[0], p[1], p[2]};
    }
    /// Bilinear, wrapping in azimuth.
    Vec3 sample(Vec3 direction) const;
};

/// Unit direction of lat-long coordinates (u, v) in [0, 1] (see LatLongImage).
Vec3 latLongDirection(double u, double v);

/// The default environment: a sky over a ground, all linear radiance.
struct SkyLook {
    Vec3 zenith{0.20, 0.30, 0.48};   ///< straight up
    Vec3 horizon{0.55, 0.58, 0.62};  ///< along the horizon
    Vec3 ground{0.25, 0.24, 0.22};   ///< from below: the lit floor's bounce
    /// The sun's direction (unit, towards it) and a soft glow around it (the disc itself
    /// is the key light, drawn with its shadow).
    Vec3 sunToward{-0.45, 0.82, 0.29};
    Vec3 sunGlow{0.35, 0.32, 0.28};
};

/// The procedural sky sampled into a lat-long image.
LatLongImage proceduralSky(const SkyLook& sky, int width = 256, int height = 128);

/// Reads a lat-long HDR environment (OpenEXR, R G B; a missing channel reads as 0).
/// Negative values (lossy compression's noise around black) read as 0.
/// @throw IoError naming @p path when it is missing, damaged, not an EXR, has no R, G or B,
///        or holds a non-finite value.
LatLongImage readLatLongExr(const std::filesystem::path& path);

/// The irradiance E(n) = integral of L(w) max(n.w, 0) dw, as 9 coefficients c such that
/// E(n) = c0 + c1 y + c2 z + c3 x + c4 xy + c5 yz + c6 (3 z^2 - 1) + c7 xz + c8 (x^2 - y^2)
/// (the order-2 projection of L convolved with the clamped cosine; exact for any L of order
/// at most 2, e.g. a constant L gives E = pi L).
using IrradianceSH = std::array<Vec3, 9>;
IrradianceSH irradianceSH(const LatLongImage& radiance);
Vec3 evaluateIrradiance(const IrradianceSH& sh, Vec3 n);

/// A cube map of mip levels; level l (size baseSize >> l) is the radiance pre-filtered
/// by a GGX lobe of perceptual roughness l / (levels - 1), with n = v = r (Karis 2013).
/// Faces in OpenGL order (+x, -x, +y, -y, +z, -z), rows t = 0 first, 3 floats per texel.
struct PrefilteredCube {
    int baseSize = 0;
    std::vector<std::vector<float>> levels;

    int levelCount() const { return int(levels.size()); }
    int sizeOf(int level) const { return baseSize >> level; }
    /// Trilinear lookup at fractional @p lod (as the GPU's textureLod, seamless).
    Vec3 sample(Vec3 direction, double lod) const;
};

/// @param samples GGX samples per texel of the first rough level (4 times more on each
///        smaller level, at most 16 times).
PrefilteredCube prefilterGgx(const LatLongImage& radiance, int baseSize = 128, int levels = 6,
                             int samples = 64);

/// The GGX lobe of perceptual @p roughness reflected about n = v, for tests: the
/// normalised integral of L over the lobe's importance samples, without the mip chain.
Vec3 ggxReference(const LatLongImage& radiance, Vec3 n, double roughness, int samples);

}  // namespace globular
