#pragma once
// Internal to render/: the ground plane, a large square under the content with a subtle
// box-filtered checker, lit and shadowed like everything else, that fades into the
// background with distance so it reads as an endless studio floor.

#include "frame_uniforms.h"
#include "gl_objects.h"

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
    void draw(const FrameUniforms& frame, const GroundLook& look) const;

  private:
    gl::Program mProgram;
    gl::VertexArray mVertexArray;
    gl::Buffer mCorners;
};

}  // namespace globular::detail
