#pragma once
// Internal to render/: a triangle mesh shaded deferred, as the spheres are
// (sphere_pass.h). The visibility pass draws the faces into the frame target's depth,
// stencil and id buffer (1 + the triangle's index at each sample); then one pass over the
// mesh's rectangle on the screen shades each pixel it covers, once for each triangle its
// samples saw, weighted by their number (shaders::triangleHitLibrary): the multisampled
// rasteriser's result, at the cost of about two shadings a pixel. Drawn directly, llvmpipe
// ran the fragment shader on every 4x4 block each triangle touches: a pour's surface has
// triangles a pixel or two across, so the shader ran about fifteen times per pixel.

#include <array>
#include <cstddef>

#include "frame_target.h"
#include "frame_uniforms.h"
#include "gl_objects.h"
#include "mesh_view.h"
#include "vec3.h"

namespace globular::detail {

class TriangleVisibility {
  public:
    TriangleVisibility();
    /// After @p mesh was uploaded into these buffers (positions, normals and indices as
    /// uploadMeshGeometry and GL_ELEMENT_ARRAY_BUFFER hold them): reads them as buffer
    /// textures, and keeps the mesh's bounding box.
    /// @throw Error when the mesh is larger than the driver's buffer textures hold.
    void attach(const MeshView& mesh, const gl::Buffer& positions, const gl::Buffer& normals,
                const gl::Buffer& indices);
    /// Draws the faces of @p vertexArray (@p indexCount indices, back faces skipped when
    /// @p cullBack) into @p target (bound): depth-tested, and where they are nearest, the
    /// stencil set to 1 and the triangles' ids written. The target then draws colour.
    void drawVisibility(const FrameUniforms& frame, const FrameTarget& target,
                        const gl::VertexArray& vertexArray, std::size_t indexCount,
                        bool cullBack) const;
    /// With @p program (in use, its fragment shader built on triangleHitLibrary): binds the
    /// id buffer and the mesh's buffer textures to units @p firstUnit to firstUnit + 3,
    /// draws the mesh's screen rectangle over the samples the visibility pass marked (no
    /// depth test: the depth buffer holds the faces' already), and restores the state.
    void drawShading(const gl::Program& program, const FrameUniforms& frame,
                     const FrameTarget& target, int firstUnit) const;

  private:
    /// The mesh's bounding box on the screen (normalised device coordinates, x0 y0 x1
    /// y1), the whole screen when part of it lies behind the eye.
    std::array<float, 4> screenRectangle(const FrameUniforms& frame) const;

    gl::Program mIds;
    gl::VertexArray mEmpty;
    gl::Texture mPositions, mNormals, mTriangles;
    bool mHasNormals = false;
    Vec3 mLow, mHigh;  // the mesh's bounding box
};

}  // namespace globular::detail
