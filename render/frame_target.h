#pragma once
// Internal to render/: where a frame is drawn. Linear-light colour in half floats
// (multisampled when asked), depth and stencil (a texture), and an id buffer that the sphere pass
// fills with the index of the globule seen at each sample; resolved and read back as
// floats. The stencil marks the samples a sphere covers, so the full-screen shading pass
// runs only there. With passes, two more buffers hold what a compositor uses, each
// weighted by coverage so the resolve's average divided by coverage is the mean over the
// covered samples: the world normal and coverage (RGBA16F), the distance from the eye
// (R32F), the screen-space motion (RG16F).

#include <vector>

#include "gl_objects.h"
#include "linear_frame.h"
#include "vec3.h"

namespace globular::detail {

class FrameTarget {
  public:
    /// @throw Error when the driver cannot make such a framebuffer.
    FrameTarget(int width, int height, int samples, bool passes = false);

    /// Binds the target; clears colour to @p background (linear) premultiplied by
    /// @p alpha, depth, stencil, ids and the passes.
    void bindAndClear(Vec3 background, float alpha = 1) const;
    /// Draw into colour only (shading, ground, meshes).
    void drawColor() const;
    /// Draw into ids only; colour writes are masked but the colour output's alpha still
    /// drives alpha-to-coverage.
    void drawIds() const;
    /// The id buffer's texture (GL_TEXTURE_2D_MULTISAMPLE when samples > 1).
    GLuint idTexture() const { return mIds.id(); }
    /// The depth (and stencil) texture, of the same kind.
    GLuint depthTexture() const { return mDepth.id(); }
    /// Binds a framebuffer of the colour alone (no depth, so the depth texture can be
    /// read while drawing into the colour); bind() returns to the full target.
    void bindColorOnly() const;
    /// Binds the target again (without clearing), drawing colour.
    void bind() const;

    /// Averages the samples and reads the image into @p frame (rows top first), with the
    /// passes when the target has them and @p withPasses (motion too when @p motion);
    /// without, @p frame's passes are left as they were.
    void read(LinearFrame& frame, bool motion = false, bool withPasses = true) const;
    bool passes() const { return mPasses; }

    int width() const { return mWidth; }
    int height() const { return mHeight; }
    int samples() const { return mSamples; }

  private:
    /// Resolves colour attachment @p attachment and reads it, bottom row first.
    void resolveAndRead(int attachment, GLenum format, std::vector<float>& out) const;

    int mWidth, mHeight, mSamples;
    bool mPasses;
    gl::Framebuffer mDraw, mResolved, mColorOnly;
    gl::Renderbuffer mColor, mResolvedColor;
    gl::Texture mDepth, mIds;
    // Passes only: normal, distance and motion, and their resolves.
    gl::Renderbuffer mNormal, mDistance, mMotion, mResolvedNormal, mResolvedDistance,
        mResolvedMotion;
    mutable std::vector<float> mReadback, mNormalReadback, mDistanceReadback, mMotionReadback;
};

}  // namespace globular::detail
