#pragma once
// The process's offscreen OpenGL contexts, behind one seam with two back ends chosen at
// run time: OSMesa (the default; Mesa's llvmpipe, no display, no driver) and EGL
// surfaceless (EGL_MESA_platform_surfaceless: llvmpipe here, the GPU's driver on a
// machine that has one). Frames are drawn into framebuffer objects, so neither needs a
// window or a default framebuffer. No GL headers here: callers of the render library
// need not see them.

#include <string>

namespace globular {

enum class GlBackend { OSMesa, Egl };

/// "osmesa" or "egl" (as the scene's [render] gl and GLOBULAR_GL spell them).
const char* glBackendName(GlBackend backend);

/// The back end for a scene's [render] gl = @p setting ("osmesa" or "egl"): the
/// environment variable GLOBULAR_GL wins when set (a machine with a GPU sets it once).
/// @throw Error naming GLOBULAR_GL when it holds another value.
GlBackend chooseGlBackend(const std::string& setting);

/// The back end makeGlContextCurrent() uses from now on (initially
/// chooseGlBackend("osmesa")). Renderers keep the one selected when they were made.
void selectGlBackend(GlBackend backend);
GlBackend selectedGlBackend();

/// Creates @p backend's OpenGL core profile context on first use (once per process and
/// back end) and makes it current on the calling thread. Not for concurrent use from
/// several threads.
/// @throw Error naming the back end when its library or an OpenGL 4.2 core context is
///        not available (e.g. libEGL missing, or no surfaceless platform).
void makeGlContextCurrent(GlBackend backend);
void makeGlContextCurrent();  ///< the selected back end

/// "4.5 (Core Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits)": for logs and docs.
std::string glContextDescription(GlBackend backend);
std::string glContextDescription();  ///< the selected back end

}  // namespace globular
