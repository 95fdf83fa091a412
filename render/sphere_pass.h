#pragma once
// Internal to render/: globules drawn as ray-cast spheres, in three passes.
//  1. Shadow: each globule a disc with exact front depth in the key light's map.
//  2. Visibility: each globule a point sprite covering its exact screen extent; the
//     fragment intersects the eye ray with the sphere and writes its true depth and the
//     globule's id (alpha-to-coverage anti-aliases the silhouette).
//  3. Shading: one pass over the screen tiles that hold spheres looks up the id of each
//     pixel and shades that sphere. (llvmpipe runs a multisampled fragment shader on
//     every 4x4 block a primitive touches, masked or not, so a full-screen pass would
//     pay for the empty sky; the tiles, marked from the sprites' rectangles, do not.)
// Deferring the shading makes its cost one per pixel instead of one per overlapping
// sphere (a million globules overlap tens of times), and sprites cost a vertex each.
// Spheres too large for a sprite (llvmpipe: 255 pixels) are drawn as instanced squares.
// Sprites hidden behind other spheres, in the camera's view or the light's, are culled on
// the CPU before drawing (sphere_culling.h) and the rest drawn by index: the same image.
// The globules' arrays are uploaded as they are, and read back by the shading pass
// through buffer textures: no interleaving copy.

#include <array>
#include <cstdint>
#include <vector>

#include "frame_target.h"
#include "frame_uniforms.h"
#include "gl_objects.h"
#include "globules.h"
#include "sphere_culling.h"

namespace globular::detail {

class SpherePass {
  public:
    /// @param samples of the frame target the passes draw into.
    explicit SpherePass(int samples);
    /// Uploads positions, radii, the value and (with frame.frameSeconds > 0, the motion
    /// pass) velocities, and picks the spheres too big for a sprite in @p frame's camera
    /// or light view.
    /// The value each sphere carries to the shader (its colour by color_by).
    enum class Value { None, Speed, Material, Temperature };
    void upload(const Globules& globules, Value value, const FrameUniforms& frame);
    void drawShadow(const FrameUniforms& frame) const;
    void drawVisibility(const FrameUniforms& frame, const FrameTarget& target) const;
    void drawShading(const FrameUniforms& frame, const FrameTarget& target) const;

    /// Occlusion culling (sphere_culling.h), on by default: the frame is the same either
    /// way, only faster with it.
    void setCulling(bool on) { mCulling = on; }

    std::size_t count() const { return mCount; }
    /// Spheres drawn in the camera's view and in the shadow map after culling.
    std::size_t visibleCount() const { return mCulling ? mVisible.size() : mCount; }
    std::size_t shadowCount() const { return mCulling ? mShadowVisible.size() : mCount; }
    std::size_t squareCount() const { return mSquareCount; }

  private:
    void drawSquares() const;
    /// The sprites: those in @p indices (@p count of them) when culling, else all.
    void drawPoints(const gl::Buffer& indices, std::size_t count) const;
    /// Marks the kTile x kTile pixel tiles that @p rects (x0, y0, x1, y1 in pixels from the
    /// bottom left) touch and uploads them as triangles, runs along each row merged.
    void uploadTiles(const std::vector<float>& rects, bool everywhere, const FrameUniforms& f);

    int mSamples;
    float mMaxSprite;  // pixels or texels; bigger spheres are drawn as squares
    gl::Program mVisibilityPoints, mVisibilitySquares, mShade, mShadowPoints, mShadowSquares;
    gl::VertexArray mPointArray, mSquareArray, mTileArray;
    // x, y, z, radius, value (speed, material or temperature), the velocity's x, y, z
    // (with the motion pass; one zero otherwise), and the material index (several
    // materials; one zero otherwise)
    std::array<gl::Buffer, 9> mArrays;
    std::array<gl::Texture, 9> mTextures;  // the same, as buffer textures
    bool mSeveralMaterials = false;
    gl::Buffer mCorners, mSquares, mSquareIds, mTiles;
    gl::Buffer mVisibleIndices, mShadowIndices;  // element arrays of the culled sprites
    bool mCulling = true;
    std::vector<uint32_t> mVisible, mShadowVisible;  // globule indices, ascending
    std::vector<ScreenDisc> mDiscs, mLightDiscs;     // kept for their memory
    OcclusionCuller mCuller, mLightCuller;
    std::size_t mCount = 0, mSquareCount = 0, mTileVertices = 0;
};

/// Pixels across the point sprite that covers a sphere of radius @p radius whose centre
/// is @p viewCenter in view space (camera looking down -z), with the projection's focal
/// lengths in pixels per unit of x/depth and y/depth; +1 pixel for anti-aliasing.
/// Infinite when the sphere reaches the near plane @p zNear or 90 degrees off axis.
/// The point vertex shader computes the same size.
float spriteSize(Vec3 viewCenter, double radius, double focalX, double focalY, double zNear);

}  // namespace globular::detail
