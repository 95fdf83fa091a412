#pragma once
// Internal to render/: a closed triangle mesh drawn as a liquid (render.mode = "surface"
// with a liquid material). Its thickness along each eye ray is the sum of the back
// faces' eye distances minus the front faces' (one additive pass, every layer counted, so
// it is exact for any closed mesh); then its front faces are shaded as liquid
// (liquid_shaders.h) over what was drawn before, which they refract.

#include "frame_uniforms.h"
#include "gl_objects.h"
#include "liquid_behind.h"
#include "liquid_optics.h"
#include "mesh_view.h"

namespace globular::detail {

class LiquidMeshPass {
  public:
    LiquidMeshPass();
    /// @throw Error when an index is out of range.
    void upload(const MeshView& mesh);
    void drawShadow(const FrameUniforms& frame) const;
    /// Draws into the framebuffer bound for drawing (the frame target, @p frame's size),
    /// refracting what it holds; that framebuffer is bound again afterwards.
    void draw(const FrameUniforms& frame, const LiquidLook& look, const LiquidOptics& optics);

  private:
    gl::Program mThickness, mShade, mShadow;
    gl::VertexArray mVertexArray, mEmpty;
    gl::Buffer mPositions, mNormals, mIndices;
    BehindTexture mBehind;
    TextureTarget mDepth;
    std::size_t mIndexCount = 0;
    bool mClosed = true;
};

}  // namespace globular::detail
