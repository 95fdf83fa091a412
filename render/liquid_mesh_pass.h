#pragma once
// Internal to render/: a closed triangle mesh drawn as a liquid (render.mode = "surface"
// with a liquid material). Its thickness along each eye ray is the sum of the back
// faces' eye distances minus the front faces' (one additive pass, every layer counted, so
// it is exact for any closed mesh); then its front faces are shaded as liquid
// (liquid_shaders.h) over what was drawn before, which they refract, deferred
// (triangle_visibility.h): each pixel they cover once.

#include "frame_target.h"
#include "frame_uniforms.h"
#include "gl_objects.h"
#include "liquid_behind.h"
#include "liquid_optics.h"
#include "mesh_view.h"
#include "triangle_visibility.h"

namespace globular::detail {

class LiquidMeshPass {
  public:
    /// @param samples of the frame target the pass draws into.
    explicit LiquidMeshPass(int samples);
    /// @throw Error when an index is out of range, or the mesh is larger than the
    /// driver's buffer textures hold.
    void upload(const MeshView& mesh);
    void drawShadow(const FrameUniforms& frame) const;
    /// Draws into @p target (bound for drawing, @p frame's size), refracting what it
    /// holds; the target is bound again afterwards, drawing colour.
    void draw(const FrameUniforms& frame, const FrameTarget& target, const LiquidLook& look,
              const LiquidOptics& optics);

  private:
    gl::Program mThickness, mShade, mShadow;
    gl::VertexArray mVertexArray;
    gl::Buffer mPositions, mNormals, mIndices;
    TriangleVisibility mVisibility;
    BehindTexture mBehind;
    TextureTarget mDepth;
    std::size_t mIndexCount = 0;
    bool mClosed = true;
};

}  // namespace globular::detail
