#pragma once
// How much memory rendering takes, known before any buffer is allocated, so a 16k
// image at 16 samples or a frame of a billion spheres is refused with the numbers up
// front instead of ending in std::bad_alloc (or an OSMesa failure) midway.

#include <cstddef>
#include <cstdint>
#include <string>

#include "render_settings.h"

namespace globular {

/// The image's buffers: the multisampled colour (RGBA16F) and depth-stencil target, its
/// resolve, the float read-back, the 8-bit image and its PNG rows, OSMesa's own colour
/// buffer, and the shadow map.
uint64_t estimateImageBytes(const RenderSettings& settings);

/// One frame's drawable content: sphere instances with their culling data, or a mesh's
/// vertex and index buffers (kept by the renderer and by the GL driver).
uint64_t estimateSphereBytes(std::size_t globules);
uint64_t estimateMeshBytes(std::size_t vertices, std::size_t triangles);

/// @throw ResourceError naming @p what ("frame 12", "the image") when the image's buffers
///        plus @p contentBytes exceed @p available bytes (0 = unknown: no check).
void checkRenderMemory(const RenderSettings& settings, uint64_t contentBytes, uint64_t available,
                       const std::string& what);

}  // namespace globular
