#include "fluid_pass.h"

#include <algorithm>
#include <cmath>

#include "errors.h"
#include "liquid_shaders.h"
#include "shaders.h"

namespace globular::detail {

namespace {

void uploadFloats(const gl::Buffer& buffer, const float* data, std::size_t n) {
    glBindBuffer(GL_ARRAY_BUFFER, buffer.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(n * sizeof(float)), data, GL_STREAM_DRAW);
}

// The fluid's shape passes see the globules as the camera does, at @p scale of the
// frame's resolution.
void applySpriteUniforms(const gl::Program& p, const FrameUniforms& f, float maxSprite,
                         double scale) {
    setMat4(p, "uView", f.view);
    setMat4(p, "uViewProj", f.viewProj);
    setVec3(p, "uEye", f.eye);
    setVec3(p, "uCamForward", f.camForward);
    setVec3(p, "uCamRight", f.camRight);
    setVec3(p, "uCamUp", f.camUp);
    glUniform2f(p.uniform("uViewport"), float(std::max(1, int(f.width * scale))),
                float(std::max(1, int(f.height * scale))));
    glUniform2f(p.uniform("uFocalPixels"), float(f.focalPixels[0] * scale),
                float(f.focalPixels[1] * scale));
    glUniform1f(p.uniform("uNear"), f.zNear);
    glUniform1f(p.uniform("uMaxSprite"), maxSprite);
}

void applyMaterials(const gl::Program& p, const std::vector<LiquidOptics>& materials) {
    float sigma[16 * 3];
    int liquid[16];
    for (std::size_t k = 0; k < 16; ++k) {
        const LiquidOptics o = opticsOf(materials, k);
        sigma[3 * k] = float(o.sigma.x);
        sigma[3 * k + 1] = float(o.sigma.y);
        sigma[3 * k + 2] = float(o.sigma.z);
        liquid[k] = o.liquid ? 1 : 0;
    }
    glUniform3fv(p.uniform("uSigma"), 16, sigma);
    glUniform1iv(p.uniform("uLiquid"), 16, liquid);
}

}  // namespace

FluidPass::FluidPass()
    : mDepth("fluid depth", shaders::fluidPointVertex(), shaders::fluidDepthFragment()),
      mThickness("fluid thickness", shaders::fluidPointVertex(), shaders::fluidThicknessFragment()),
      mSmooth("fluid smoothing", shaders::fullScreenVertex(), shaders::fluidSmoothFragment()),
      mComposite("fluid shading", shaders::fullScreenVertex(), shaders::fluidCompositeFragment()),
      mShadow("fluid shadow", shaders::sphereShadowPointVertex(), shaders::sphereShadowFragment(true)),
      mPoints(gl::makeVertexArray()),
      mEmpty(gl::makeVertexArray()),
      mX(gl::makeBuffer()),
      mY(gl::makeBuffer()),
      mZ(gl::makeBuffer()),
      mRadius(gl::makeBuffer()),
      mMaterial(gl::makeBuffer()),
      mVx(gl::makeBuffer()),
      mVy(gl::makeBuffer()),
      mVz(gl::makeBuffer()),
      mVelocity(gl::makeTexture()) {
    float pointSizes[2] = {1, 64};
    glGetFloatv(GL_POINT_SIZE_RANGE, pointSizes);
    mMaxSprite = std::min(250.0f, pointSizes[1] - 2.0f);
    glBindVertexArray(mPoints.id());
    const gl::Buffer* arrays[] = {&mX, &mY, &mZ, &mRadius};
    for (GLuint i = 0; i < 4; ++i) {
        glBindBuffer(GL_ARRAY_BUFFER, arrays[i]->id());
        glVertexAttribPointer(i + 1, 1, GL_FLOAT, GL_FALSE, 0, nullptr);
        glEnableVertexAttribArray(i + 1);
    }
    glBindVertexArray(0);
    gl::checkErrors("setting up the fluid passes");
}

void FluidPass::upload(const Globules& g, bool velocities) {
    const std::size_t n = g.size();
    if (g.py.size() != n || g.pz.size() != n || g.radius.size() != n) {
        throw Error("render: the globules' arrays have different lengths");
    }
    mCount = n;
    uploadFloats(mX, g.px.data(), n);
    uploadFloats(mY, g.py.data(), n);
    uploadFloats(mZ, g.pz.data(), n);
    uploadFloats(mRadius, g.radius.data(), n);
    double sum = 0;
    std::size_t finite = 0;
    for (float r : g.radius) {
        if (std::isfinite(r) && r > 0) {
            sum += r;
            ++finite;
        }
    }
    mMeanRadius = finite > 0 ? sum / double(finite) : 1.0;
    glBindVertexArray(mPoints.id());
    const bool moving = velocities && g.vx.size() == n && g.vy.size() == n && g.vz.size() == n;
    const gl::Buffer* velocity[] = {&mVx, &mVy, &mVz};
    const std::vector<float>* components[] = {&g.vx, &g.vy, &g.vz};
    for (GLuint i = 0; i < 3; ++i) {
        if (moving && n > 0) {
            uploadFloats(*velocity[i], components[i]->data(), n);
            glVertexAttribPointer(6 + i, 1, GL_FLOAT, GL_FALSE, 0, nullptr);
            glEnableVertexAttribArray(6 + i);
        } else {
            glDisableVertexAttribArray(6 + i);
            glVertexAttrib1f(6 + i, 0);
        }
    }
    if (g.material.size() == n && n > 0) {
        glBindBuffer(GL_ARRAY_BUFFER, mMaterial.id());
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(n), g.material.data(), GL_STREAM_DRAW);
        glVertexAttribIPointer(5, 1, GL_UNSIGNED_BYTE, 0, nullptr);
        glEnableVertexAttribArray(5);
    } else {
        glDisableVertexAttribArray(5);
        glVertexAttribI1ui(5, 0);  // one material
    }
    glBindVertexArray(0);
    gl::checkErrors("uploading the fluid's globules");
}

void FluidPass::drawPoints() const {
    glEnable(GL_PROGRAM_POINT_SIZE);
    glBindVertexArray(mPoints.id());
    glDrawArrays(GL_POINTS, 0, GLsizei(mCount));
    glBindVertexArray(0);
}

void FluidPass::drawShadow(const FrameUniforms& f) const {
    if (mCount == 0) return;
    glUseProgram(mShadow.id());
    setMat4(mShadow, "uLightViewProj", f.lightViewProj);
    setVec3(mShadow, "uLightToward", f.lightToward.front());
    glUniform1f(mShadow.uniform("uTexelsPerUnit"), f.texelsPerUnit);
    glUniform1f(mShadow.uniform("uMaxSprite"), mMaxSprite);
    drawPoints();
}

void FluidPass::draw(const FrameUniforms& f, const FluidLook& look) {
    if (mCount == 0) return;
    GLint frame = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &frame);
    mBehind.capture(f.width, f.height);

    // 1. The front: view depth of the nearest sphere.
    mFront.bind(f.width, f.height, GL_R32F, true, false);
    // ... with the nearest sphere's velocity beside it, for the motion pass.
    if (mVelocityWidth != f.width || mVelocityHeight != f.height) {
        mVelocityWidth = f.width;
        mVelocityHeight = f.height;
        glBindTexture(GL_TEXTURE_2D, mVelocity.id());
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, f.width, f.height, 0, GL_RGBA, GL_FLOAT, nullptr);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glBindTexture(GL_TEXTURE_2D, 0);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, mVelocity.id(), 0);
    }
    const GLenum both[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, both);
    const float none[] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, none);
    glClearBufferfv(GL_COLOR, 1, none);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glUseProgram(mDepth.id());
    applySpriteUniforms(mDepth, f, mMaxSprite, 1.0);
    applyMaterials(mDepth, look.materials);
    glUniform1f(mDepth.uniform("uSide"), -1.0f);
    drawPoints();

    // ... and the back: view depth of the farthest sphere's back, for the liquid's depth.
    mBack.bind(f.width, f.height, GL_R32F, true, false);
    glClearBufferfv(GL_COLOR, 0, none);
    glClearDepth(0.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    glClearDepth(1.0);
    glDepthFunc(GL_GREATER);
    glUniform1f(mDepth.uniform("uSide"), 1.0f);
    drawPoints();
    glDepthFunc(GL_LESS);

    // 2. Thickness and optical depth, summed, at half resolution.
    const int hw = std::max(1, f.width / 2), hh = std::max(1, f.height / 2);
    mDepths.bind(hw, hh, GL_RGBA32F, false, true);
    glClearBufferfv(GL_COLOR, 0, none);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glBlendEquation(GL_FUNC_ADD);
    glUseProgram(mThickness.id());
    applySpriteUniforms(mThickness, f, mMaxSprite, double(hw) / f.width);
    applyMaterials(mThickness, look.materials);
    drawPoints();
    glDisable(GL_BLEND);

    // 3. Smoothing: x then y, twice, between two buffers.
    glUseProgram(mSmooth.id());
    glUniform1i(mSmooth.uniform("uDepth"), 2);
    glUniform1f(mSmooth.uniform("uWorldRadius"), float(look.smoothing * mMeanRadius));
    glUniform1f(mSmooth.uniform("uFocal"), f.focalPixels[0]);
    glUniform1f(mSmooth.uniform("uMaxPixels"), 48.0f);
    glBindVertexArray(mEmpty.id());
    const gl::Texture* source = &mFront.texture;
    if (look.smoothing > 0) {
        for (int pass = 0; pass < 4; ++pass) {
            TextureTarget& into = pass % 2 == 0 ? mPing : mPong;
            into.bind(f.width, f.height, GL_R32F, false, false);
            glActiveTexture(GL_TEXTURE2);
            glBindTexture(GL_TEXTURE_2D, source->id());
            glUniform2i(mSmooth.uniform("uAxis"), pass % 2 == 0 ? 0 : 1, pass % 2 == 0 ? 1 : 0);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            source = &into.texture;
        }
    }

    // 4. Shading, into the frame, depth-tested against what is there.
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(frame));
    glViewport(0, 0, f.width, f.height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glUseProgram(mComposite.id());
    applyFrameUniforms(mComposite, f);
    applyLiquidUniforms(mComposite, f, look.liquid);
    glUniform1i(mComposite.uniform("uSmoothed"), 2);
    glUniform1i(mComposite.uniform("uDepths"), 3);
    glUniform1i(mComposite.uniform("uFront"), 4);
    glUniform1i(mComposite.uniform("uBack"), 5);
    glUniform1i(mComposite.uniform("uVelocity"), 6);
    glUniform1f(mComposite.uniform("uEdgeThickness"), float(mMeanRadius));
    mBehind.bind(1);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, source->id());
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, mDepths.texture.id());
    glActiveTexture(GL_TEXTURE4);
    glBindTexture(GL_TEXTURE_2D, mFront.texture.id());
    glActiveTexture(GL_TEXTURE5);
    glBindTexture(GL_TEXTURE_2D, mBack.texture.id());
    glActiveTexture(GL_TEXTURE6);
    glBindTexture(GL_TEXTURE_2D, mVelocity.id());
    glActiveTexture(GL_TEXTURE0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    gl::checkErrors("drawing the fluid");
}

}  // namespace globular::detail
