#include "liquid_mesh_pass.h"

#include "errors.h"
#include "liquid_shaders.h"
#include "mesh_pass.h"
#include "shaders.h"

namespace globular::detail {

LiquidMeshPass::LiquidMeshPass(int samples)
    : mThickness("liquid mesh thickness", shaders::liquidMeshVertex(),
                 shaders::liquidMeshThicknessFragment()),
      mShade("liquid mesh", shaders::screenRectangleVertex(), shaders::liquidMeshFragment(samples)),
      mShadow("liquid mesh shadow", shaders::positionVertex(), shaders::depthOnlyFragment()),
      mVertexArray(gl::makeVertexArray()),
      mPositions(gl::makeBuffer()),
      mNormals(gl::makeBuffer()),
      mIndices(gl::makeBuffer()) {}

void LiquidMeshPass::upload(const MeshView& mesh) {
    const std::size_t indexCount = mesh.triangleCount * 3;
    checkTriangleIndices(mesh);
    mIndexCount = indexCount;
    mClosed = mesh.closed;
    glBindVertexArray(mVertexArray.id());
    uploadMeshGeometry(mesh, mPositions, mNormals);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mIndices.id());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indexCount * sizeof(uint32_t)), mesh.triangles,
                 GL_STREAM_DRAW);
    glBindVertexArray(0);
    mVisibility.attach(mesh, mPositions, mNormals, mIndices);
    gl::checkErrors("uploading the liquid mesh");
}

void LiquidMeshPass::drawShadow(const FrameUniforms& f) const {
    drawShadowFaces(mShadow, f, mVertexArray, mIndexCount, mClosed);
}

void LiquidMeshPass::draw(const FrameUniforms& f, const FrameTarget& target,
                          const LiquidLook& look, const LiquidOptics& optics) {
    if (mIndexCount == 0) return;
    mBehind.capture(f.width, f.height);

    // Thickness: every face, no depth test, eye distances added with their sign.
    mDepth.bind(f.width, f.height, GL_R32F, false, false);
    const float none[] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, none);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glBlendEquation(GL_FUNC_ADD);
    glFrontFace(GL_CCW);
    glUseProgram(mThickness.id());
    setMat4(mThickness, "uViewProj", f.viewProj);
    setVec3(mThickness, "uEye", f.eye);
    glBindVertexArray(mVertexArray.id());
    glDrawElements(GL_TRIANGLES, GLsizei(mIndexCount), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    glDisable(GL_BLEND);

    // The front faces, then their shading as liquid into the frame.
    target.bind();
    mVisibility.drawVisibility(f, target, mVertexArray, mIndexCount, mClosed);
    glUseProgram(mShade.id());
    applyFrameUniforms(mShade, f);
    LiquidLook own = look;
    own.ior = optics.ior;
    applyLiquidUniforms(mShade, f, own);
    setVec3(mShade, "uMeshSigma", optics.sigma);
    mBehind.bind(1);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, mDepth.texture.id());
    glUniform1i(mShade.uniform("uThickness"), 2);
    mVisibility.drawShading(mShade, f, target, 3);
    gl::checkErrors("drawing the liquid mesh");
}

}  // namespace globular::detail
