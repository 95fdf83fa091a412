#pragma once
// Internal to render/: where a frame is drawn. Linear-light colour in half floats
// (multisampled when asked), depth and stencil, and an id buffer that the sphere pass
// fills with the index of the globule seen at each sample; resolved and read back as
// floats. The stencil marks the samples a sphere covers, so the full-screen shading pass
// runs only there.

#include <vector>

#include "gl_objects.h"
#include "vec3.h"

namespace globular::detail {

class FrameTarget {
  public:
    /// @throw Error when the driver cannot make such a framebuffer.
    FrameTarget(int width, int height, int samples);

    /// Binds the target; clears colour to @p background (linear), depth, stencil and ids.
    void bindAndClear(Vec3 background) const;
    /// Draw into colour only (shading, ground, meshes).
    void drawColor() const;
    /// Draw into ids only; colour writes are masked but the colour output's alpha still
    /// drives alpha-to-coverage.
    void drawIds() const;
    /// The id buffer's texture (GL_TEXTURE_2D_MULTISAMPLE when samples > 1).
    GLuint idTexture() const { return mIds.id(); }

    /// Averages the samples and reads the image, bottom row first, RGBA floats.
    void readPixels(std::vector<float>& rgba) const;

    int width() const { return mWidth; }
    int height() const { return mHeight; }
    int samples() const { return mSamples; }

  private:
    int mWidth, mHeight, mSamples;
    gl::Framebuffer mDraw, mResolved;
    gl::Renderbuffer mColor, mDepth, mResolvedColor;
    gl::Texture mIds;
};

}  // namespace globular::detail
