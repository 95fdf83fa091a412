#include "triangle_visibility.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "errors.h"
#include "shaders.h"
#include "transform.h"

namespace globular::detail {

namespace {

void attachBuffer(const gl::Texture& texture, GLenum format, const gl::Buffer& buffer) {
    glBindTexture(GL_TEXTURE_BUFFER, texture.id());
    glTexBuffer(GL_TEXTURE_BUFFER, format, buffer.id());
}

}  // namespace

TriangleVisibility::TriangleVisibility()
    : mIds("mesh visibility", shaders::positionVertex(), shaders::triangleIdFragment()),
      mEmpty(gl::makeVertexArray()),
      mPositions(gl::makeTexture()),
      mNormals(gl::makeTexture()),
      mTriangles(gl::makeTexture()) {}

void TriangleVisibility::attach(const MeshView& mesh, const gl::Buffer& positions,
                                const gl::Buffer& normals, const gl::Buffer& indices) {
    GLint texels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &texels);
    if (std::max(mesh.triangleCount, mesh.vertexCount) > std::size_t(texels)) {
        throw Error("render: a mesh of " + std::to_string(mesh.vertexCount) + " vertices and " +
                    std::to_string(mesh.triangleCount) +
                    " triangles; this OpenGL driver's buffer textures hold at most " +
                    std::to_string(texels) + " of either");
    }
    mHasNormals = mesh.normals != nullptr;
    attachBuffer(mPositions, GL_RGB32F, positions);
    if (mHasNormals) attachBuffer(mNormals, GL_RGB32F, normals);
    attachBuffer(mTriangles, GL_RGB32UI, indices);
    glBindTexture(GL_TEXTURE_BUFFER, 0);

    constexpr double kHuge = std::numeric_limits<double>::max();
    mLow = {kHuge, kHuge, kHuge};
    mHigh = {-kHuge, -kHuge, -kHuge};
    for (std::size_t i = 0; i < mesh.vertexCount; ++i) {
        const float* p = mesh.positions + 3 * i;
        mLow = {std::min(mLow.x, double(p[0])), std::min(mLow.y, double(p[1])),
                std::min(mLow.z, double(p[2]))};
        mHigh = {std::max(mHigh.x, double(p[0])), std::max(mHigh.y, double(p[1])),
                 std::max(mHigh.z, double(p[2]))};
    }
}

std::array<float, 4> TriangleVisibility::screenRectangle(const FrameUniforms& f) const {
    std::array<float, 4> box{1, 1, -1, -1};
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p{corner & 1 ? mHigh.x : mLow.x, corner & 2 ? mHigh.y : mLow.y,
                     corner & 4 ? mHigh.z : mLow.z};
        const Vec4 c = transformPoint(f.viewProj, p);
        // A corner behind the eye (or a box lost to non-finite points) bounds nothing.
        if (!(c.w > 1e-9) || !std::isfinite(c.x) || !std::isfinite(c.y)) return {-1, -1, 1, 1};
        box[0] = std::min(box[0], float(c.x / c.w));
        box[1] = std::min(box[1], float(c.y / c.w));
        box[2] = std::max(box[2], float(c.x / c.w));
        box[3] = std::max(box[3], float(c.y / c.w));
    }
    // A pixel more on each side: the box's rounding must not cut covered pixels off.
    const float padX = 2.0f / float(f.width), padY = 2.0f / float(f.height);
    return {std::max(box[0] - padX, -1.0f), std::max(box[1] - padY, -1.0f),
            std::min(box[2] + padX, 1.0f), std::min(box[3] + padY, 1.0f)};
}

void TriangleVisibility::drawVisibility(const FrameUniforms& f, const FrameTarget& target,
                                        const gl::VertexArray& vertexArray,
                                        std::size_t indexCount, bool cullBack) const {
    target.drawIds();
    // Another pass may have used the ids and stencil earlier in the frame.
    const GLuint none[] = {0, 0, 0, 0};
    glClearBufferuiv(GL_COLOR, 1, none);
    glClearStencil(0);
    glStencilMask(0xff);
    glClear(GL_STENCIL_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glUseProgram(mIds.id());
    setMat4(mIds, "uViewProj", f.viewProj);
    if (cullBack) {
        glFrontFace(GL_CCW);
        glCullFace(GL_BACK);
        glEnable(GL_CULL_FACE);
    }
    glBindVertexArray(vertexArray.id());
    glDrawElements(GL_TRIANGLES, GLsizei(indexCount), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    glDisable(GL_CULL_FACE);
    glDisable(GL_STENCIL_TEST);
    target.drawColor();
}

void TriangleVisibility::drawShading(const gl::Program& program, const FrameUniforms& f,
                                     const FrameTarget& target, int firstUnit) const {
    glUniform1i(program.uniform("uHasNormals"), mHasNormals ? 1 : 0);
    const std::array<float, 4> rectangle = screenRectangle(f);
    glUniform4fv(program.uniform("uRectangle"), 1, rectangle.data());
    const struct {
        const char* name;
        GLenum kind;
        GLuint texture;
    } inputs[] = {
        {"uIds", GLenum(target.samples() > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D),
         target.idTexture()},
        {"uTriangles", GL_TEXTURE_BUFFER, mTriangles.id()},
        {"uPositions", GL_TEXTURE_BUFFER, mPositions.id()},
        {"uNormals", GL_TEXTURE_BUFFER, mNormals.id()},
    };
    for (int i = 0; i < int(std::size(inputs)); ++i) {
        glActiveTexture(GLenum(GL_TEXTURE0 + firstUnit + i));
        glBindTexture(inputs[i].kind, inputs[i].texture);
        glUniform1i(program.uniform(inputs[i].name), firstUnit + i);
    }
    glActiveTexture(GL_TEXTURE0);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glBindVertexArray(mEmpty.id());
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glBindVertexArray(0);
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_DEPTH_TEST);
}

}  // namespace globular::detail
