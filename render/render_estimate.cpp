#include "render_estimate.h"

#include "errors.h"
#include "surface_estimate.h"

namespace globular {

namespace {

// Per pixel and sample: RGBA16F colour (8 bytes) and 24-bit depth with stencil (4).
constexpr uint64_t kBytesPerSample = 8 + 4;
// Per pixel once: the resolve target (8), the float read-back and the linear frame
// (16 + 16), OSMesa's colour buffer (16), the 8-bit image and a PNG row copy (8).
constexpr uint64_t kBytesPerPixel = 8 + 16 + 16 + 16 + 8;
// With png_bits = 16: the 16-bit image.
constexpr uint64_t kBytesPerPixel16 = 8;
// With exr (passes): per sample the normal (RGBA16F, 8), distance (R32F, 4) and motion
// (RG16F, 4); per pixel their resolve (16), read-back (28), the frame's depth, normal and
// motion (24) and the EXR's half copies of colour, normal and motion (18).
constexpr uint64_t kBytesPerSamplePasses = 8 + 4 + 4;
constexpr uint64_t kBytesPerPixelPasses = 16 + 28 + 24 + 18;
// Per sphere: instance attributes (position, radius, colour: 32), their copy in the GL
// driver (32), and the culling pass's per-sphere arrays (about 48).
constexpr uint64_t kBytesPerSphere = 32 + 32 + 48;
// Per mesh vertex (position and normal, 24) and triangle (12), kept twice.
constexpr uint64_t kBytesPerVertex = 2 * 24, kBytesPerTriangle = 2 * 12;

}  // namespace

uint64_t estimateImageBytes(const RenderSettings& s) {
    const uint64_t pixels = uint64_t(s.width) * uint64_t(s.height);
    const uint64_t shadow = uint64_t(s.shadowMapSize) * uint64_t(s.shadowMapSize) * 4;
    const uint64_t perSample = kBytesPerSample + (s.exr ? kBytesPerSamplePasses : 0);
    const uint64_t perPixel = kBytesPerPixel + (s.pngBits == 16 ? kBytesPerPixel16 : 0) +
                              (s.exr ? kBytesPerPixelPasses : 0);
    return pixels * (perSample * uint64_t(s.samples) + perPixel) + shadow;
}

uint64_t estimateSphereBytes(std::size_t globules) { return uint64_t(globules) * kBytesPerSphere; }

uint64_t estimateMeshBytes(std::size_t vertices, std::size_t triangles) {
    return uint64_t(vertices) * kBytesPerVertex + uint64_t(triangles) * kBytesPerTriangle;
}

void checkRenderMemory(const RenderSettings& settings, uint64_t contentBytes, uint64_t available,
                       const std::string& what) {
    const uint64_t image = estimateImageBytes(settings);
    if (available == 0 || image + contentBytes <= available) return;
    throw ResourceError(
        "cannot render " + what + ": a " + std::to_string(settings.width) + "x" +
        std::to_string(settings.height) + " image at " + std::to_string(settings.samples) +
        " samples needs about " + formatBytes(image) +
        (contentBytes > 0 ? " and its content " + formatBytes(contentBytes) : std::string()) +
        ", but only " + formatBytes(available) +
        " is available; lower [render] width, height, samples or shadow_map_size");
}

}  // namespace globular
