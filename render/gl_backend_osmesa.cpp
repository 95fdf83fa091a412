// The OSMesa back end: Mesa's off-screen library, llvmpipe, linked in.
#include <array>
#include <mutex>
#include <string>

#include "errors.h"
#include "gl_api.h"
#include "gl_backends.h"

namespace globular::detail {

namespace {

struct ProcessContext {
    OSMesaContext context = nullptr;
    std::array<unsigned char, 4> pixel{};  // the context's default framebuffer: unused
};

ProcessContext& processContext() {
    static ProcessContext shared;
    static std::once_flag created;
    std::call_once(created, [] {
        // clang-format off
        const int attributes[] = {
            OSMESA_FORMAT, OSMESA_RGBA,
            OSMESA_DEPTH_BITS, 0,  // frames are drawn into framebuffer objects
            OSMESA_STENCIL_BITS, 0,
            OSMESA_ACCUM_BITS, 0,
            OSMESA_PROFILE, OSMESA_CORE_PROFILE,
            OSMESA_CONTEXT_MAJOR_VERSION, kGlMajor,
            OSMESA_CONTEXT_MINOR_VERSION, kGlMinor,
            0};
        // clang-format on
        shared.context = OSMesaCreateContextAttribs(attributes, nullptr);
    });
    if (!shared.context) {
        throw Error("render: OpenGL back end \"osmesa\": OSMesa could not create an OpenGL " +
                    std::to_string(kGlMajor) + "." + std::to_string(kGlMinor) +
                    " core profile context (is Mesa's libOSMesa built with llvmpipe? "
                    "Debian: apt install libosmesa6)");
    }
    return shared;
}

}  // namespace

void makeOsMesaCurrent() {
    ProcessContext& shared = processContext();
    if (!OSMesaMakeCurrent(shared.context, shared.pixel.data(), GL_UNSIGNED_BYTE, 1, 1)) {
        throw Error("render: OpenGL back end \"osmesa\": OSMesaMakeCurrent failed");
    }
}

void releaseOsMesa() { OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0); }

}  // namespace globular::detail
