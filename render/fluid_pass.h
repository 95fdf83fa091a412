#pragma once
// Internal to render/: render.mode = "fluid", a liquid surface straight from the
// globules with no mesh, after van der Laan, Green and Sainz, "Screen space fluid
// rendering with curvature flow" (I3D 2009):
//  1. the front depth of the union of the globules' spheres (point sprites that ray-cast
//     their sphere; view depth into a float buffer, depth-tested);
//  2. the depth of the liquid along each eye ray: from that front to the farthest back
//     of a sphere (the same splat, depth-tested the other way); and each sphere's chord
//     along the eye ray summed with its material's absorption times the chord (additive,
//     half resolution), whose ratio is the absorption where materials mix;
//  3. the depth smoothed by a separable bilateral filter whose reach is a world radius
//     (render.fluid_smoothing globule radii) at each pixel's depth, twice over;
//  4. normals from the smoothed depth, and the liquid shading of liquid_shaders.h into
//     the frame, over what was drawn before (ground, set), which it refracts.
// In the key light's shadow map the globules are discs, as in the sphere pass.

#include <vector>

#include "frame_uniforms.h"
#include "gl_objects.h"
#include "globules.h"
#include "liquid_behind.h"
#include "liquid_optics.h"

namespace globular::detail {

struct FluidLook {
    LiquidLook liquid;
    std::vector<LiquidOptics> materials;  ///< by material index; missing: the default liquid
    double smoothing = 2;                 ///< the filter's reach, in mean globule radii
};

class FluidPass {
  public:
    FluidPass();
    /// Uploads positions, radii, materials and, with @p velocities (the motion pass),
    /// velocities.
    void upload(const Globules& globules, bool velocities);
    void drawShadow(const FrameUniforms& frame) const;
    /// Draws into the framebuffer bound for drawing (the frame target, @p frame's size),
    /// refracting what it holds; that framebuffer is bound again afterwards.
    void draw(const FrameUniforms& frame, const FluidLook& look);

  private:
    void drawPoints() const;

    float mMaxSprite;
    gl::Program mDepth, mThickness, mSmooth, mComposite, mShadow;
    gl::VertexArray mPoints, mEmpty;
    gl::Buffer mX, mY, mZ, mRadius, mMaterial, mVx, mVy, mVz;
    gl::Texture mVelocity;  // the nearest sphere's velocity, beside mFront's depth
    int mVelocityWidth = 0, mVelocityHeight = 0;
    BehindTexture mBehind;
    TextureTarget mFront, mBack, mDepths, mPing, mPong;
    std::size_t mCount = 0;
    double mMeanRadius = 1;
};

}  // namespace globular::detail
