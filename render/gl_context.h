#pragma once
// The process's one offscreen OpenGL context (OSMesa, Mesa's llvmpipe rasteriser).
// No GL headers here: callers of the render library need not see them.

#include <string>

namespace globular {

/// Creates the OpenGL core profile context on first use (once per process) and makes it
/// current on the calling thread. Rendering happens into framebuffer objects; the
/// context's own buffer is a single pixel. Not for concurrent use from several threads.
/// @throw Error explaining that OSMesa could not create an OpenGL core context.
void makeGlContextCurrent();

/// "4.5 (Core Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits)": for logs and docs.
std::string glContextDescription();

}  // namespace globular
