#include "gl_context.h"

#include <array>
#include <mutex>

#include "errors.h"
#include "gl_api.h"

namespace globular {

namespace {

// Core 4.2 is what the renderer uses (GLSL 420: early fragment tests, gl_SampleMask,
// buffer textures, multisample textures); asking for it lets Mesa hand out its newest
// core version (4.5 on Debian 12's Mesa 22.3).
constexpr int kMajor = 4;
constexpr int kMinor = 2;

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
            OSMESA_CONTEXT_MAJOR_VERSION, kMajor,
            OSMESA_CONTEXT_MINOR_VERSION, kMinor,
            0};
        // clang-format on
        shared.context = OSMesaCreateContextAttribs(attributes, nullptr);
    });
    if (!shared.context) {
        throw Error("render: OSMesa could not create an OpenGL " + std::to_string(kMajor) + "." +
                    std::to_string(kMinor) +
                    " core profile context (is Mesa's libOSMesa built with llvmpipe? "
                    "Debian: apt install libosmesa6)");
    }
    return shared;
}

}  // namespace

void makeGlContextCurrent() {
    ProcessContext& shared = processContext();
    if (OSMesaGetCurrentContext() == shared.context) return;
    if (!OSMesaMakeCurrent(shared.context, shared.pixel.data(), GL_UNSIGNED_BYTE, 1, 1)) {
        throw Error("render: OSMesaMakeCurrent failed for the OpenGL core context");
    }
}

std::string glContextDescription() {
    makeGlContextCurrent();
    auto text = [](GLenum name) {
        const GLubyte* s = glGetString(name);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    return text(GL_VERSION) + ", " + text(GL_RENDERER);
}

}  // namespace globular
