#include "gl_context.h"

#include <cstdlib>
#include <optional>

#include "errors.h"
#include "gl_api.h"
#include "gl_backends.h"

namespace globular {

namespace {

std::optional<GlBackend> parse(const std::string& name) {
    if (name == "osmesa") return GlBackend::OSMesa;
    if (name == "egl") return GlBackend::Egl;
    return std::nullopt;
}

std::optional<GlBackend>& selected() {
    static std::optional<GlBackend> backend;
    return backend;
}

// The back end whose context is current on this thread, if any: the two keep their own
// notion of "current", so switching releases the other first.
thread_local std::optional<GlBackend> current;

}  // namespace

const char* glBackendName(GlBackend backend) {
    return backend == GlBackend::Egl ? "egl" : "osmesa";
}

GlBackend chooseGlBackend(const std::string& setting) {
    if (const char* env = std::getenv("GLOBULAR_GL"); env && *env) {
        if (const auto b = parse(env)) return *b;
        throw Error(std::string("render: GLOBULAR_GL = \"") + env +
                    "\": the OpenGL back end must be \"osmesa\" or \"egl\"");
    }
    if (const auto b = parse(setting)) return *b;
    throw Error("render: OpenGL back end \"" + setting + "\": must be \"osmesa\" or \"egl\"");
}

void selectGlBackend(GlBackend backend) { selected() = backend; }

GlBackend selectedGlBackend() {
    if (!selected()) selected() = chooseGlBackend("osmesa");
    return *selected();
}

void makeGlContextCurrent(GlBackend backend) {
    if (current == backend) return;
    if (current == GlBackend::OSMesa) detail::releaseOsMesa();
    if (current == GlBackend::Egl) detail::releaseEgl();
    current.reset();
    if (backend == GlBackend::Egl) {
        detail::makeEglCurrent();
    } else {
        detail::makeOsMesaCurrent();
    }
    current = backend;
}

void makeGlContextCurrent() { makeGlContextCurrent(selectedGlBackend()); }

std::string glContextDescription(GlBackend backend) {
    makeGlContextCurrent(backend);
    auto text = [](GLenum name) {
        const GLubyte* s = glGetString(name);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    return text(GL_VERSION) + ", " + text(GL_RENDERER);
}

std::string glContextDescription() { return glContextDescription(selectedGlBackend()); }

}  // namespace globular
