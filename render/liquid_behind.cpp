#include "liquid_behind.h"

#include <string>

#include "errors.h"

namespace globular::detail {

BehindTexture::BehindTexture() : mTexture(gl::makeTexture()), mFramebuffer(gl::makeFramebuffer()) {}

void BehindTexture::capture(int width, int height) {
    GLint frame = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &frame);
    if (width != mWidth || height != mHeight) {
        mWidth = width;
        mHeight = height;
        glBindTexture(GL_TEXTURE_2D, mTexture.id());
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glBindTexture(GL_TEXTURE_2D, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, mFramebuffer.id());
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, mTexture.id(), 0);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            throw Error("render: the OpenGL driver cannot make the liquid's background texture");
        }
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(frame));
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, mFramebuffer.id());
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(frame));
    gl::checkErrors("capturing what lies behind the liquid");
}

void BehindTexture::bind(int unit) const {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, mTexture.id());
    glActiveTexture(GL_TEXTURE0);
}

void applyLiquidUniforms(const gl::Program& p, const FrameUniforms& f, const LiquidLook& look) {
    glUniform1i(p.uniform("uBehind"), 1);
    glUniform1f(p.uniform("uIor"), float(look.ior));
    glUniform1i(p.uniform("uGroundDrawn"), look.ground ? 1 : 0);
    glUniform1f(p.uniform("uGroundHeight"), float(look.groundHeight));
    setMat4(p, "uBehindViewProj", f.viewProj);
}

void TextureTarget::bind(int w, int h, GLenum format, bool withDepth, bool linear) {
    if (w != width || h != height) {
        width = w;
        height = h;
        glBindTexture(GL_TEXTURE_2D, texture.id());
        glTexImage2D(GL_TEXTURE_2D, 0, GLint(format), w, h, 0, format == GL_R32F ? GL_RED : GL_RGBA,
                     GL_FLOAT, nullptr);
        const GLint filter = linear ? GL_LINEAR : GL_NEAREST;
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glBindTexture(GL_TEXTURE_2D, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture.id(), 0);
        if (withDepth) {
            glBindRenderbuffer(GL_RENDERBUFFER, depth.id());
            glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
            glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                      depth.id());
        }
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            throw Error("render: the OpenGL driver cannot make a " + std::to_string(w) + "x" +
                        std::to_string(h) + " buffer for the liquid");
        }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    const GLenum first = GL_COLOR_ATTACHMENT0;
    glDrawBuffers(1, &first);
    glViewport(0, 0, w, h);
}

}  // namespace globular::detail
