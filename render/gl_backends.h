#pragma once
// Internal to render/: the two back ends behind gl_context.h. Each creates its context
// once per process; makeCurrent() binds it to the calling thread, release() unbinds it
// so the other back end can take over the thread.

namespace globular::detail {

/// The OpenGL version asked for: core 4.2 is what the renderer uses (GLSL 420: early
/// fragment tests, gl_SampleMask, buffer textures, multisample textures); Mesa hands out
/// its newest core version for it (4.5 on Debian 12's Mesa 22.3).
inline constexpr int kGlMajor = 4;
inline constexpr int kGlMinor = 2;

void makeOsMesaCurrent();
void releaseOsMesa();
void makeEglCurrent();
void releaseEgl();

}  // namespace globular::detail
