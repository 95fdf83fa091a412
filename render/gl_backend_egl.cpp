// The EGL back end: a surfaceless display (EGL_MESA_platform_surfaceless), so no window
// system and no GPU device node are needed; Mesa picks llvmpipe where there is no GPU
// and the GPU's driver where there is one. libEGL is opened at run time, so the program
// runs (with OSMesa) on machines without it. The OpenGL entry points stay libOSMesa's:
// both libraries dispatch through Mesa's shared libglapi, to whichever context is current.
#include <dlfcn.h>

#define EGL_NO_X11 1
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>

#include "errors.h"
#include "gl_backends.h"

namespace globular::detail {

namespace {

struct Egl {
    PFNEGLGETPROCADDRESSPROC getProcAddress = nullptr;
    PFNEGLQUERYSTRINGPROC queryString = nullptr;
    PFNEGLGETERRORPROC getError = nullptr;
    PFNEGLINITIALIZEPROC initialize = nullptr;
    PFNEGLBINDAPIPROC bindApi = nullptr;
    PFNEGLCREATECONTEXTPROC createContext = nullptr;
    PFNEGLMAKECURRENTPROC makeCurrent = nullptr;
    PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay = nullptr;
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    std::string failure;  // why there is no context, for every later call
};

[[noreturn]] void fail(const std::string& why) {
    throw Error("render: OpenGL back end \"egl\": " + why +
                " (use the default [render] gl = \"osmesa\", or unset GLOBULAR_GL)");
}

std::string hexError(Egl& egl) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%04X", unsigned(egl.getError()));
    return std::string("EGL error ") + text;
}

/// Loads libEGL and creates the context; on failure leaves egl.failure set.
void create(Egl& egl) {
    // GLOBULAR_EGL_LIBRARY names another library (a vendor's libEGL; tests name a missing
    // one to see the error).
    const char* override = std::getenv("GLOBULAR_EGL_LIBRARY");
    const std::string name = override && *override ? override : "libEGL.so.1";
    void* library = dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!library) {
        egl.failure = name + " cannot be loaded (" + std::string(dlerror()) +
                      "; Debian: apt install libegl1 libegl-mesa0)";
        return;
    }
    egl.getProcAddress =
        reinterpret_cast<PFNEGLGETPROCADDRESSPROC>(dlsym(library, "eglGetProcAddress"));
    if (!egl.getProcAddress) {
        egl.failure = "libEGL.so.1 has no eglGetProcAddress";
        return;
    }
    auto load = [&](auto& function, const char* name) {
        function = reinterpret_cast<std::remove_reference_t<decltype(function)>>(
            egl.getProcAddress(name));
        if (!function) egl.failure = std::string("libEGL.so.1 lacks ") + name;
    };
    load(egl.queryString, "eglQueryString");
    load(egl.getError, "eglGetError");
    load(egl.initialize, "eglInitialize");
    load(egl.bindApi, "eglBindAPI");
    load(egl.createContext, "eglCreateContext");
    load(egl.makeCurrent, "eglMakeCurrent");
    load(egl.getPlatformDisplay, "eglGetPlatformDisplayEXT");
    if (!egl.failure.empty()) return;
    const char* extensions = egl.queryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!extensions || std::string(extensions).find("EGL_MESA_platform_surfaceless") == std::string::npos) {
        egl.failure = "this EGL has no surfaceless platform (EGL_MESA_platform_surfaceless)";
        return;
    }
    egl.display = egl.getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY,
                                         nullptr);
    EGLint major = 0, minor = 0;
    if (egl.display == EGL_NO_DISPLAY || !egl.initialize(egl.display, &major, &minor)) {
        egl.failure = "the surfaceless display cannot be initialised (" + hexError(egl) + ")";
        return;
    }
    if (!egl.bindApi(EGL_OPENGL_API)) {
        egl.failure = "desktop OpenGL is not available through EGL (" + hexError(egl) + ")";
        return;
    }
    // clang-format off
    const EGLint attributes[] = {
        EGL_CONTEXT_MAJOR_VERSION, kGlMajor,
        EGL_CONTEXT_MINOR_VERSION, kGlMinor,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
        EGL_NONE};
    // clang-format on
    // No config: the context draws only into framebuffer objects (EGL_KHR_no_config_context).
    egl.context = egl.createContext(egl.display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (egl.context == EGL_NO_CONTEXT) {
        egl.failure = "no OpenGL " + std::to_string(kGlMajor) + "." + std::to_string(kGlMinor) +
                      " core profile context (" + hexError(egl) + ")";
    }
}

Egl& processEgl() {
    static Egl egl;
    static std::once_flag created;
    std::call_once(created, [] { create(egl); });
    if (!egl.failure.empty()) fail(egl.failure);
    return egl;
}

}  // namespace

void makeEglCurrent() {
    Egl& egl = processEgl();
    if (!egl.makeCurrent(egl.display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl.context)) {
        fail("eglMakeCurrent failed (" + hexError(egl) + ")");
    }
}

void releaseEgl() {
    Egl& egl = processEgl();
    egl.makeCurrent(egl.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

}  // namespace globular::detail
