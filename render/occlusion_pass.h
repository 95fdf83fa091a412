#pragma once
// Internal to render/: screen-space ambient occlusion. After the opaque content, the set
// and the ground are drawn, one pass over the screen (where occlusion_region.h says it can
// darken) reads the depth buffer, rebuilds each pixel's world position and normal, and
// counts how many points of a hemisphere of radius R above it lie behind what the camera
// sees (Mittring, "Finding Next Gen: CryEngine 2", SIGGRAPH 2007; the normal-oriented
// hemisphere of later variants). The colour is multiplied by 1 - strength * (occluded
// fraction), so creases and the floor where globules touch it darken. Being applied after
// shading, it dims direct light too within R of an occluder; the key light's shadow map
// already darkens most such places.

#include <optional>
#include <vector>

#include "frame_target.h"
#include "frame_uniforms.h"
#include "gl_objects.h"
#include "occlusion_region.h"

namespace globular::detail {

class OcclusionPass {
  public:
    /// @param samples of the frame target it reads.
    explicit OcclusionPass(int samples);
    /// Darkens the colour of @p target (left bound afterwards) by the occlusion within
    /// @p radius world units, @p strength in [0, 1], over the pixels of @p region
    /// (occlusion_region.h; std::nullopt: every pixel).
    void apply(const FrameUniforms& frame, const FrameTarget& target, float radius,
               float strength, const std::optional<std::vector<PixelRect>>& region) const;

  private:
    int mSamples;
    gl::Program mProgram;
    gl::VertexArray mVertexArray;
    gl::Buffer mCorners;  ///< the rectangles' triangles, window coordinates
};

}  // namespace globular::detail
