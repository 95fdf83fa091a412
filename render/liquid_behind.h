#pragma once
// Internal to render/: what a liquid refracts. The frame drawn so far (ground, set,
// opaque content) resolved into a texture the liquid's shaders look up, and the uniforms
// of the liquid library (liquid_shaders.cpp).

#include "frame_uniforms.h"
#include "gl_objects.h"
#include "liquid_optics.h"

namespace globular::detail {

/// Where the liquid's refracted rays end: the ground plane (exact), else the frame.
struct LiquidLook {
    double ior = 1.33;
    bool ground = true;       ///< the ground plane is drawn
    double groundHeight = 0;  ///< world units
};

class BehindTexture {
  public:
    BehindTexture();
    /// Resolves the colour of the framebuffer bound for drawing (the frame target, its
    /// colour in attachment 0) into the texture; that framebuffer stays bound.
    void capture(int width, int height);
    void bind(int unit) const;

  private:
    gl::Texture mTexture;
    gl::Framebuffer mFramebuffer;
    int mWidth = 0, mHeight = 0;
};

/// Sets the liquid library's uniforms of @p program (in use); the behind texture on unit 1.
void applyLiquidUniforms(const gl::Program& program, const FrameUniforms& frame,
                         const LiquidLook& look);

/// A single-sampled texture to draw into, with a depth buffer when asked.
struct TextureTarget {
    gl::Texture texture = gl::makeTexture();
    gl::Framebuffer framebuffer = gl::makeFramebuffer();
    gl::Renderbuffer depth = gl::makeRenderbuffer();
    int width = 0, height = 0;
    /// (Re)allocates when the size changes; binds it and sets the viewport.
    void bind(int w, int h, GLenum format, bool withDepth, bool linear);
};

}  // namespace globular::detail
