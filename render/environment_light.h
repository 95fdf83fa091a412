#pragma once
// Internal to render/: the environment on the GPU. The lat-long radiance (the procedural
// sky or an HDR file, environment.h) becomes a cube map pre-filtered by GGX roughness
// (one mip level per roughness step) and the irradiance's 9 spherical-harmonic
// coefficients; both are computed once and kept while the environment does not change.

#include <string>

#include "environment.h"
#include "gl_objects.h"

namespace globular::detail {

/// The texture unit the cube map is bound to (the sphere pass uses the low ones).
inline constexpr int kEnvironmentUnit = 15;

class EnvironmentLight {
  public:
    EnvironmentLight();

    /// Makes the environment current: the OpenEXR @p file when not empty, else the
    /// procedural @p sky. Recomputed only when they differ from the last call.
    /// @throw IoError naming a missing or damaged file.
    void prepare(const std::string& file, const SkyLook& sky);
    /// Binds the cube map to kEnvironmentUnit.
    void bind() const;

    const IrradianceSH& irradiance() const { return mIrradiance; }
    /// The last mip level (roughness 1).
    float maxLod() const { return float(mLevels - 1); }

  private:
    gl::Texture mCube;
    std::string mKey;
    IrradianceSH mIrradiance{};
    int mLevels = 1;
};

}  // namespace globular::detail
