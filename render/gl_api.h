#pragma once
// Internal to render/: include only from .cpp files, never from a public header.
// Mesa's libOSMesa exports every core OpenGL entry point (checked with nm -D), so the
// prototypes of glext.h link directly and no loader is needed.

#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
// osmesa.h includes GL/gl.h; glext.h adds the OpenGL 3-4.5 prototypes.
#include <GL/glext.h>
