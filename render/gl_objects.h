#pragma once
// Internal to render/ (includes the GL headers): owning handles for OpenGL objects and a
// shader program that reports compile and link errors with the driver's log.

#include <string>
#include <utility>

#include "gl_api.h"

namespace globular::gl {

/// An OpenGL object name freed by @p Delete (glDeleteBuffers and friends). Move-only.
template <void (*Delete)(GLsizei, const GLuint*)>
class Name {
  public:
    Name() = default;
    explicit Name(GLuint id) : mId(id) {}
    Name(Name&& other) noexcept : mId(std::exchange(other.mId, 0)) {}
    Name& operator=(Name&& other) noexcept {
        std::swap(mId, other.mId);
        return *this;
    }
    Name(const Name&) = delete;
    Name& operator=(const Name&) = delete;
    ~Name() {
        if (mId) Delete(1, &mId);
    }
    GLuint id() const { return mId; }

  private:
    GLuint mId = 0;
};

using Buffer = Name<glDeleteBuffers>;
using VertexArray = Name<glDeleteVertexArrays>;
using Texture = Name<glDeleteTextures>;
using Framebuffer = Name<glDeleteFramebuffers>;
using Renderbuffer = Name<glDeleteRenderbuffers>;

Buffer makeBuffer();
VertexArray makeVertexArray();
Texture makeTexture();
Framebuffer makeFramebuffer();
Renderbuffer makeRenderbuffer();

class Program {
  public:
    /// Compiles and links; @p name appears in error messages.
    /// @throw Error with the driver's log when compiling or linking fails.
    Program(const std::string& name, const std::string& vertexSource,
            const std::string& fragmentSource);
    Program(Program&& other) noexcept : mId(std::exchange(other.mId, 0)) {}
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;
    ~Program();

    GLuint id() const { return mId; }
    /// -1 when the uniform does not exist or was optimised away (GL then ignores sets).
    GLint uniform(const char* name) const { return glGetUniformLocation(mId, name); }

  private:
    GLuint mId = 0;
};

/// @throw Error naming @p what and the GL error code when the GL reports an error.
void checkErrors(const char* what);

}  // namespace globular::gl
