#include "frame_target.h"

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

FrameTarget::FrameTarget(int width, int height, int samples)
    : mWidth(width),
      mHeight(height),
      mSamples(samples),
      mDraw(gl::makeFramebuffer()),
      mResolved(gl::makeFramebuffer()),
      mColor(gl::makeRenderbuffer()),
      mDepth(gl::makeRenderbuffer()),
      mResolvedColor(gl::makeRenderbuffer()),
      mIds(gl::makeTexture()) {
    const bool multi = samples > 1;
    glBindRenderbuffer(GL_RENDERBUFFER, mColor.id());
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, multi ? samples : 0, GL_RGBA16F, width,
                                     height);
    glBindRenderbuffer(GL_RENDERBUFFER, mDepth.id());
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, multi ? samples : 0, GL_DEPTH24_STENCIL8,
                                     width, height);
    const GLenum idTarget = multi ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
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
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                              mDepth.id());
    checkComplete("frame buffer", width, height, samples);

    glBindRenderbuffer(GL_RENDERBUFFER, mResolvedColor.id());
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA16F, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, mResolved.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              mResolvedColor.id());
    checkComplete("resolve buffer", width, height, 1);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::checkErrors("creating the frame buffers");
}

void FrameTarget::bindAndClear(Vec3 background) const {
    glBindFramebuffer(GL_FRAMEBUFFER, mDraw.id());
    glViewport(0, 0, mWidth, mHeight);
    const GLenum both[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, both);
    glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    const float color[] = {float(background.x), float(background.y), float(background.z), 1};
    const GLuint noId[] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, color);
    glClearBufferuiv(GL_COLOR, 1, noId);
    glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
    drawColor();
}

void FrameTarget::drawColor() const {
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_NONE};
    glDrawBuffers(2, buffers);
    glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void FrameTarget::drawIds() const {
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, buffers);
    glColorMaski(0, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
}

void FrameTarget::readPixels(std::vector<float>& rgba) const {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, mDraw.id());
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, mResolved.id());
    glBlitFramebuffer(0, 0, mWidth, mHeight, 0, 0, mWidth, mHeight, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, mResolved.id());
    rgba.resize(std::size_t(mWidth) * mHeight * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, mWidth, mHeight, GL_RGBA, GL_FLOAT, rgba.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::checkErrors("reading the frame back");
}

}  // namespace globular::detail
