#pragma once
// Internal to render/: where on the ground the key light's shadow can fall. The ground
// outside it is drawn without the shadow filter: llvmpipe runs a shader's every line in
// every pixel a draw covers, whatever its branches, so only geometry limits what it runs.

#include <optional>

#include "frame_uniforms.h"
#include "shadow_map.h"

namespace globular::detail {

/// An xz rectangle of the ground plane, world units; empty when it holds no point.
struct GroundRect {
    double x0 = 0, z0 = 0, x1 = 0, z1 = 0;
    bool empty() const { return !(x0 < x1 && z0 < z1); }
};

/// The ground (at height @p groundHeight) outside this rectangle is lit by the key light
/// exactly: every tap of its shadow filter (shaders.cpp, keyLightVisibility) reads only
/// texels no caster wrote (@p drawn, of a map @p f.shadowMapSize texels wide) and
/// returns 1. The rectangle also reaches a pixel's footprint past that, as a pixel is
/// shaded at its centre even where only some of its samples lie outside. Empty when
/// nothing was drawn; std::nullopt when it cannot be bounded (a light or an eye level
/// with the ground).
std::optional<GroundRect> groundShadowRegion(const FrameUniforms& f, const TexelRect& drawn,
                                             double groundHeight);

}  // namespace globular::detail
