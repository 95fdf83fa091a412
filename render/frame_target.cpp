#include "frame_target.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "errors.h"

namespace globular::detail {

namespace {

void checkComplete(const char* what, int width, int height, int samples) {
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        throw Error(std::string("render: the OpenGL driver cannot make the ") + what + " (" +
                    std::to_string(width) + "x" + std::to_string(height) + ", " +
                    std::to_string(samples) + " samples)");
    }
}

}  // namespace

FrameTarget::FrameTarget(int width, int height, int samples, bool passes)
    : mWidth(width),
      mHeight(height),
      mSamples(samples),
      mPasses(passes),
      mDraw(gl::makeFramebuffer()),
      mResolved(gl::makeFramebuffer()),
      mColorOnly(gl::makeFramebuffer()),
      mColor(gl::makeRenderbuffer()),
      mResolvedColor(gl::makeRenderbuffer()),
      mDepth(gl::makeTexture()),
      mIds(gl::makeTexture()),
      mNormal(gl::makeRenderbuffer()),
      mDistance(gl::makeRenderbuffer()),
      mMotion(gl::makeRenderbuffer()),
      mResolvedNormal(gl::makeRenderbuffer()),
      mResolvedDistance(gl::makeRenderbuffer()),
      mResolvedMotion(gl::makeRenderbuffer()) {
    const bool multi = samples > 1;
    glBindRenderbuffer(GL_RENDERBUFFER, mColor.id());
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, multi ? samples : 0, GL_RGBA16F, width,
                                     height);
    const GLenum idTarget = multi ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
    // Depth a texture, so the ambient occlusion pass can read it.
    glBindTexture(idTarget, mDepth.id());
    if (multi) {
        glTexImage2DMultisample(idTarget, samples, GL_DEPTH24_STENCIL8, width, height, GL_TRUE);
    } else {
        glTexImage2D(idTarget, 0, GL_DEPTH24_STENCIL8, width, height, 0, GL_DEPTH_STENCIL,
                     GL_UNSIGNED_INT_24_8, nullptr);
        glTexParameteri(idTarget, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(idTarget, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    glBindTexture(idTarget, mIds.id());
    if (multi) {
        glTexImage2DMultisample(idTarget, samples, GL_R32UI, width, height, GL_TRUE);
    } else {
        glTexImage2D(idTarget, 0, GL_R32UI, width, height, 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                     nullptr);
        glTexParameteri(idTarget, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(idTarget, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    glBindTexture(idTarget, 0);

    glBindFramebuffer(GL_FRAMEBUFFER, mDraw.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, mColor.id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, idTarget, mIds.id(), 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, idTarget, mDepth.id(), 0);
    if (passes) {
        glBindRenderbuffer(GL_RENDERBUFFER, mNormal.id());
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, multi ? samples : 0, GL_RGBA16F, width,
                                         height);
        glBindRenderbuffer(GL_RENDERBUFFER, mDistance.id());
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, multi ? samples : 0, GL_R32F, width,
                                         height);
        glBindRenderbuffer(GL_RENDERBUFFER, mMotion.id());
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, multi ? samples : 0, GL_RG16F, width,
                                         height);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, GL_RENDERBUFFER,
                                  mNormal.id());
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT3, GL_RENDERBUFFER,
                                  mDistance.id());
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT4, GL_RENDERBUFFER,
                                  mMotion.id());
    }
    checkComplete("frame buffer", width, height, samples);
    glBindFramebuffer(GL_FRAMEBUFFER, mColorOnly.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, mColor.id());
    checkComplete("colour-only frame buffer", width, height, samples);

    glBindRenderbuffer(GL_RENDERBUFFER, mResolvedColor.id());
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA16F, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, mResolved.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              mResolvedColor.id());
    if (passes) {
        // The resolve's formats must match the multisampled buffers'.
        glBindRenderbuffer(GL_RENDERBUFFER, mResolvedNormal.id());
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA16F, width, height);
        glBindRenderbuffer(GL_RENDERBUFFER, mResolvedDistance.id());
        glRenderbufferStorage(GL_RENDERBUFFER, GL_R32F, width, height);
        glBindRenderbuffer(GL_RENDERBUFFER, mResolvedMotion.id());
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RG16F, width, height);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, GL_RENDERBUFFER,
                                  mResolvedNormal.id());
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT3, GL_RENDERBUFFER,
                                  mResolvedDistance.id());
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT4, GL_RENDERBUFFER,
                                  mResolvedMotion.id());
    }
    checkComplete("resolve buffer", width, height, 1);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::checkErrors("creating the frame buffers");
}

void FrameTarget::bindAndClear(Vec3 background, float alpha) const {
    glBindFramebuffer(GL_FRAMEBUFFER, mDraw.id());
    glViewport(0, 0, mWidth, mHeight);
    const GLenum all[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                          GL_COLOR_ATTACHMENT3, GL_COLOR_ATTACHMENT4};
    glDrawBuffers(mPasses ? 5 : 2, all);
    glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    const float color[] = {float(background.x) * alpha, float(background.y) * alpha,
                           float(background.z) * alpha, alpha};
    const GLuint noId[] = {0, 0, 0, 0};
    const float zero[] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, color);
    glClearBufferuiv(GL_COLOR, 1, noId);
    if (mPasses) {
        glClearBufferfv(GL_COLOR, 2, zero);
        glClearBufferfv(GL_COLOR, 3, zero);
        glClearBufferfv(GL_COLOR, 4, zero);
    }
    glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
    drawColor();
}

void FrameTarget::drawColor() const {
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_NONE, GL_COLOR_ATTACHMENT2,
                              GL_COLOR_ATTACHMENT3, GL_COLOR_ATTACHMENT4};
    glDrawBuffers(mPasses ? 5 : 2, buffers);
    glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void FrameTarget::bindColorOnly() const {
    glBindFramebuffer(GL_FRAMEBUFFER, mColorOnly.id());
    glViewport(0, 0, mWidth, mHeight);
    const GLenum buffer = GL_COLOR_ATTACHMENT0;
    glDrawBuffers(1, &buffer);
}

void FrameTarget::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, mDraw.id());
    glViewport(0, 0, mWidth, mHeight);
    drawColor();
}

void FrameTarget::drawIds() const {
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_NONE, GL_NONE,
                              GL_NONE};
    glDrawBuffers(mPasses ? 5 : 2, buffers);
    glColorMaski(0, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
}

void FrameTarget::resolveAndRead(int attachment, GLenum format, std::vector<float>& out) const {
    const GLenum buffer = GL_COLOR_ATTACHMENT0 + attachment;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, mDraw.id());
    glReadBuffer(buffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, mResolved.id());
    GLenum only[5] = {GL_NONE, GL_NONE, GL_NONE, GL_NONE, GL_NONE};
    only[attachment] = buffer;
    glDrawBuffers(attachment + 1, only);
    glBlitFramebuffer(0, 0, mWidth, mHeight, 0, 0, mWidth, mHeight, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, mResolved.id());
    glReadBuffer(buffer);
    out.resize(std::size_t(mWidth) * mHeight * (format == GL_RGBA ? 4 : format == GL_RG ? 2 : 1));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, mWidth, mHeight, format, GL_FLOAT, out.data());
}

void FrameTarget::read(LinearFrame& frame, bool motion, bool withPasses) const {
    resolveAndRead(0, GL_RGBA, mReadback);
    const bool passes = mPasses && withPasses;
    motion = motion && passes;
    if (passes) {
        resolveAndRead(2, GL_RGBA, mNormalReadback);
        resolveAndRead(3, GL_RED, mDistanceReadback);
    }
    if (motion) resolveAndRead(4, GL_RG, mMotionReadback);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::checkErrors("reading the frame back");
    // GL rows run bottom to top; the frame's top to bottom.
    const std::size_t w = std::size_t(mWidth);
    frame.width = mWidth;
    frame.height = mHeight;
    frame.rgba.resize(w * mHeight * 4);
    for (int y = 0; y < mHeight; ++y) {
        const float* in = &mReadback[std::size_t(mHeight - 1 - y) * w * 4];
        std::copy(in, in + 4 * w, &frame.rgba[std::size_t(y) * w * 4]);
    }
    if (mPasses && !withPasses) return;
    frame.motion.clear();
    if (!mPasses) {
        frame.depth.clear();
        frame.normal.clear();
        return;
    }
    frame.depth.resize(w * mHeight);
    frame.normal.resize(w * mHeight * 3);
    if (motion) frame.motion.assign(w * mHeight * 2, 0.0f);
    for (int y = 0; y < mHeight; ++y) {
        const std::size_t row = std::size_t(mHeight - 1 - y) * w;
        for (std::size_t x = 0; x < w; ++x) {
            const float* n = &mNormalReadback[(row + x) * 4];
            const float coverage = n[3];
            const std::size_t out = std::size_t(y) * w + x;
            float* normal = &frame.normal[3 * out];
            const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            // Below a thousandth of a sample's weight, nothing is drawn there.
            if (!(coverage > 1e-3f) || !(length > 0)) {
                frame.depth[out] = LinearFrame::kNothing;
                normal[0] = normal[1] = normal[2] = 0;
                continue;
            }
            frame.depth[out] = mDistanceReadback[row + x] / coverage;
            for (int k = 0; k < 3; ++k) normal[k] = n[k] / length;
            if (motion) {
                frame.motion[2 * out] = mMotionReadback[2 * (row + x)] / coverage;
                frame.motion[2 * out + 1] = mMotionReadback[2 * (row + x) + 1] / coverage;
            }
        }
    }
}

}  // namespace globular::detail
