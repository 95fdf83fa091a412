#include "mesh_pass.h"

#include <algorithm>
#include <string>

#include "errors.h"
#include "shaders.h"

namespace globular::detail {

void uploadMeshGeometry(const MeshView& mesh, const gl::Buffer& positions,
                        const gl::Buffer& normals) {
    const auto bytes = GLsizeiptr(mesh.vertexCount * 3 * sizeof(float));
    glBindBuffer(GL_ARRAY_BUFFER, positions.id());
    glBufferData(GL_ARRAY_BUFFER, bytes, mesh.positions, GL_STREAM_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(0);
    if (mesh.normals) {
        glBindBuffer(GL_ARRAY_BUFFER, normals.id());
        glBufferData(GL_ARRAY_BUFFER, bytes, mesh.normals, GL_STREAM_DRAW);
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
        glEnableVertexAttribArray(1);
    } else {
        glDisableVertexAttribArray(1);
        glVertexAttrib3f(1, 0, 0, 0);  // the fragment shader then uses face normals
    }
}

MeshPass::MeshPass()
    : mProgram("mesh", shaders::meshVertex(), shaders::meshFragment()),
      mShadowProgram("mesh shadow", shaders::meshShadowVertex(), shaders::depthOnlyFragment()),
      mVertexArray(gl::makeVertexArray()),
      mPositions(gl::makeBuffer()),
      mNormals(gl::makeBuffer()),
      mValues(gl::makeBuffer()),
      mMaterials(gl::makeBuffer()),
      mIndices(gl::makeBuffer()) {}

void MeshPass::upload(const MeshView& mesh) {
    const std::size_t indexCount = mesh.triangleCount * 3;
    checkTriangleIndices(mesh);
    mIndexCount = indexCount;
    glBindVertexArray(mVertexArray.id());
    uploadMeshGeometry(mesh, mPositions, mNormals);
    if (mesh.values) {
        glBindBuffer(GL_ARRAY_BUFFER, mValues.id());
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(mesh.vertexCount * sizeof(float)), mesh.values,
                     GL_STREAM_DRAW);
        glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, 0, nullptr);
        glEnableVertexAttribArray(2);
    } else {
        glDisableVertexAttribArray(2);
        glVertexAttrib1f(2, 0);
    }
    if (mesh.materials) {
        glBindBuffer(GL_ARRAY_BUFFER, mMaterials.id());
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(mesh.vertexCount * sizeof(float)),
                     mesh.materials, GL_STREAM_DRAW);
        glVertexAttribPointer(3, 1, GL_FLOAT, GL_FALSE, 0, nullptr);
        glEnableVertexAttribArray(3);
    } else {
        glDisableVertexAttribArray(3);
        glVertexAttrib1f(3, 0);
    }
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mIndices.id());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indexCount * sizeof(uint32_t)), mesh.triangles,
                 GL_STREAM_DRAW);
    glBindVertexArray(0);
    gl::checkErrors("uploading the mesh");
}

void MeshPass::drawShadow(const FrameUniforms& f) const {
    if (mIndexCount == 0) return;
    glUseProgram(mShadowProgram.id());
    setMat4(mShadowProgram, "uLightViewProj", f.lightViewProj);
    glBindVertexArray(mVertexArray.id());
    glDrawElements(GL_TRIANGLES, GLsizei(mIndexCount), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
}

void MeshPass::draw(const FrameUniforms& f, Cull cull) const {
    if (mIndexCount == 0) return;
    glUseProgram(mProgram.id());
    applyFrameUniforms(mProgram, f);
    glBindVertexArray(mVertexArray.id());
    if (cull != Cull::None) {
        glFrontFace(GL_CCW);
        glCullFace(GL_BACK);
        glEnable(GL_CULL_FACE);
    }
    glDrawElements(GL_TRIANGLES, GLsizei(mIndexCount), GL_UNSIGNED_INT, nullptr);
    glDisable(GL_CULL_FACE);
    glBindVertexArray(0);
}

}  // namespace globular::detail
