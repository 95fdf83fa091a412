#pragma once
// Internal to render/: a triangle mesh (the surfacing stage's output, or a prop of the
// set) drawn smooth-shaded with its vertex normals, in the key light's shadow map and, its
// shading deferred (triangle_visibility.h), in the camera view.

#include "frame_target.h"
#include "frame_uniforms.h"
#include "gl_objects.h"
#include "mesh_view.h"
#include "triangle_visibility.h"

namespace globular::detail {

/// Uploads the mesh's positions (attribute 0) and normals (attribute 1; without them
/// (0, 0, 0), so the fragment shaders use face normals) into the bound vertex array.
void uploadMeshGeometry(const MeshView& mesh, const gl::Buffer& positions,
                        const gl::Buffer& normals);

/// Draws @p indexCount indices of @p vertexArray with @p program (positions through
/// uViewProj) into the key light's map (bound for drawing), the faces turned from the
/// light skipped when @p closed: a closed mesh's nearest faces along the light are the
/// lit ones, so the map is the same but at the silhouette's texels, and the pour's liquid
/// draws 1.2-1.3x as fast on llvmpipe (docs/performance.md, twentieth pass).
void drawShadowFaces(const gl::Program& program, const FrameUniforms& frame,
                     const gl::VertexArray& vertexArray, std::size_t indexCount, bool closed);

class MeshPass {
  public:
    /// @param samples of the frame target it draws into.
    explicit MeshPass(int samples);
    /// @throw Error when an index is out of range (the GL would read garbage).
    void upload(const MeshView& mesh);
    /// Which faces to skip. Back: half the visibility pass's work for a closed mesh wound
    /// counter-clockwise seen from outside (the surface stage's), and in the shadow map
    /// the faces turned from the light, behind the lit ones.
    enum class Cull { None, Back };
    /// Draws the faces into the key light's map (bound for drawing).
    void drawShadow(const FrameUniforms& frame, Cull cull) const;
    /// Draws into @p target (bound for drawing), which then draws colour.
    void draw(const FrameUniforms& frame, const FrameTarget& target, Cull cull) const;

  private:
    gl::Program mProgram;
    gl::Program mShadowProgram;
    gl::VertexArray mVertexArray;
    gl::Buffer mPositions, mNormals, mValues, mMaterials, mIndices;
    gl::Texture mValueTexture, mMaterialTexture;
    TriangleVisibility mVisibility;
    std::size_t mIndexCount = 0;
    bool mHasValues = false, mHasMaterials = false;
};

}  // namespace globular::detail
