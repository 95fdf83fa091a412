#pragma once
// Internal to render/: a triangle mesh (the surfacing stage's output) drawn smooth-shaded
// with its vertex normals, in the camera view and in the key light's shadow map.

#include "frame_uniforms.h"
#include "gl_objects.h"
#include "mesh_view.h"

namespace globular::detail {

/// Uploads the mesh's positions (attribute 0) and normals (attribute 1; without them
/// (0, 0, 0), so the fragment shaders use face normals) into the bound vertex array.
void uploadMeshGeometry(const MeshView& mesh, const gl::Buffer& positions,
                        const gl::Buffer& normals);

class MeshPass {
  public:
    MeshPass();
    /// @throw Error when an index is out of range (the GL would read garbage).
    void upload(const MeshView& mesh);
    void drawShadow(const FrameUniforms& frame) const;
    /// Which faces to skip. Back: half the work for a closed mesh wound counter-clockwise
    /// seen from outside (the surface stage's), which matters because multisampled
    /// llvmpipe shades hidden fragments too.
    enum class Cull { None, Back };
    void draw(const FrameUniforms& frame, Cull cull) const;

  private:
    gl::Program mProgram;
    gl::Program mShadowProgram;
    gl::VertexArray mVertexArray;
    gl::Buffer mPositions, mNormals, mValues, mMaterials, mIndices;
    std::size_t mIndexCount = 0;
};

}  // namespace globular::detail
