#pragma once
// Internal to render/: the ground plane, a large square under the content with a subtle
// box-filtered checker, lit and shadowed like everything else, that fades into the
// background with distance so it reads as an endless studio floor.

#include <optional>

#include "frame_uniforms.h"
#include "gl_objects.h"
#include "ground_shadow_region.h"

namespace globular::detail {

struct GroundLook {
    double height = 0;              ///< y of the plane, world units
    Vec3 center;                    ///< the content's centre; the fade is measured from it (xz)
    double fadeStart = 10;          ///< world units from center
    double fadeEnd = 30;            ///< fully background here; the square ends just beyond
    double checkerSize = 1;         ///< world units
    double checkerContrast = 0.12;  ///< fraction by which dark squares are darker
    Vec3 color;                     ///< linear
    Vec3 background;                ///< linear
    double backgroundAlpha = 1;     ///< 0: transparent; the ground fades into alpha
};

class GroundPass {
  public:
    GroundPass();
    /// @param shadowRegion where the key light's shadow can fall
    /// (groundShadowRegion()): only there is the ground drawn with the shadow filter, the
    /// rest in pieces that share its corners, so no pixel is missed or drawn twice.
    /// std::nullopt: with the filter everywhere.
    void draw(const FrameUniforms& frame, const GroundLook& look,
              const std::optional<GroundRect>& shadowRegion) const;

  private:
    void drawTriangles(const gl::Program& program, const FrameUniforms& frame,
                       const GroundLook& look, const float* corners, int cornerCount) const;

    gl::Program mShadowed;
    gl::Program mLit;  ///< the same shading without the key light's shadow filter
    gl::VertexArray mVertexArray;
    gl::Buffer mCorners;
};

}  // namespace globular::detail
