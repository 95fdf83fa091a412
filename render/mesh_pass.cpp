#include "mesh_pass.h"

#include <algorithm>
#include <string>
#include <utility>

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

MeshPass::MeshPass(int samples)
    : mProgram("mesh", shaders::screenRectangleVertex(), shaders::meshFragment(samples)),
      mShadowProgram("mesh shadow", shaders::positionVertex(), shaders::depthOnlyFragment()),
      mVertexArray(gl::makeVertexArray()),
      mPositions(gl::makeBuffer()),
      mNormals(gl::makeBuffer()),
      mValues(gl::makeBuffer()),
      mMaterials(gl::makeBuffer()),
      mIndices(gl::makeBuffer()),
      mValueTexture(gl::makeTexture()),
      mMaterialTexture(gl::makeTexture()) {}

void MeshPass::upload(const MeshView& mesh) {
    const std::size_t indexCount = mesh.triangleCount * 3;
    checkTriangleIndices(mesh);
    mIndexCount = indexCount;
    glBindVertexArray(mVertexArray.id());
    uploadMeshGeometry(mesh, mPositions, mNormals);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mIndices.id());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indexCount * sizeof(uint32_t)), mesh.triangles,
                 GL_STREAM_DRAW);
    glBindVertexArray(0);
    mVisibility.attach(mesh, mPositions, mNormals, mIndices);
    // The shading reads each vertex's value and material through buffer textures.
    mHasValues = mesh.values != nullptr;
    mHasMaterials = mesh.materials != nullptr;
    const std::pair<const float*, const gl::Buffer*> perVertex[] = {{mesh.values, &mValues},
                                                                    {mesh.materials, &mMaterials}};
    const gl::Texture* textures[] = {&mValueTexture, &mMaterialTexture};
    for (int i = 0; i < 2; ++i) {
        if (!perVertex[i].first) continue;
        glBindBuffer(GL_TEXTURE_BUFFER, perVertex[i].second->id());
        glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(mesh.vertexCount * sizeof(float)),
                     perVertex[i].first, GL_STREAM_DRAW);
        glBindTexture(GL_TEXTURE_BUFFER, textures[i]->id());
        glTexBuffer(GL_TEXTURE_BUFFER, GL_R32F, perVertex[i].second->id());
    }
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    gl::checkErrors("uploading the mesh");
}

void drawShadowFaces(const gl::Program& program, const FrameUniforms& f,
                     const gl::VertexArray& vertexArray, std::size_t indexCount, bool closed) {
    if (indexCount == 0) return;
    glUseProgram(program.id());
    setMat4(program, "uViewProj", f.lightViewProj);
    if (closed) {
        glFrontFace(GL_CCW);
        glCullFace(GL_BACK);
        glEnable(GL_CULL_FACE);
    }
    glBindVertexArray(vertexArray.id());
    glDrawElements(GL_TRIANGLES, GLsizei(indexCount), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    glDisable(GL_CULL_FACE);
}

void MeshPass::drawShadow(const FrameUniforms& f, Cull cull) const {
    drawShadowFaces(mShadowProgram, f, mVertexArray, mIndexCount, cull == Cull::Back);
}

void MeshPass::draw(const FrameUniforms& f, const FrameTarget& target, Cull cull) const {
    if (mIndexCount == 0) return;
    mVisibility.drawVisibility(f, target, mVertexArray, mIndexCount, cull == Cull::Back);
    glUseProgram(mProgram.id());
    applyFrameUniforms(mProgram, f);
    glUniform1i(mProgram.uniform("uHasValues"), mHasValues ? 1 : 0);
    glUniform1i(mProgram.uniform("uHasMaterials"), mHasMaterials ? 1 : 0);
    glActiveTexture(GL_TEXTURE5);
    glBindTexture(GL_TEXTURE_BUFFER, mValueTexture.id());
    glUniform1i(mProgram.uniform("uValues"), 5);
    glActiveTexture(GL_TEXTURE6);
    glBindTexture(GL_TEXTURE_BUFFER, mMaterialTexture.id());
    glUniform1i(mProgram.uniform("uMaterials"), 6);
    mVisibility.drawShading(mProgram, f, target, 1);
}

}  // namespace globular::detail
