#include "gl_objects.h"

#include <cstdio>
#include <vector>

#include "errors.h"

namespace globular::gl {

namespace {

template <typename Handle, void (*Generate)(GLsizei, GLuint*)>
Handle generate() {
    GLuint id = 0;
    Generate(1, &id);
    return Handle(id);
}

GLuint compile(const std::string& name, GLenum stage, const std::string& source) {
    GLuint shader = glCreateShader(stage);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::vector<char> log(std::size_t(length) + 1, '\0');
        glGetShaderInfoLog(shader, length, nullptr, log.data());
        glDeleteShader(shader);
        throw Error("render: the " + name + (stage == GL_VERTEX_SHADER ? " vertex" : " fragment") +
                    " shader does not compile: " + log.data());
    }
    return shader;
}

}  // namespace

Buffer makeBuffer() { return generate<Buffer, glGenBuffers>(); }
VertexArray makeVertexArray() { return generate<VertexArray, glGenVertexArrays>(); }
Texture makeTexture() { return generate<Texture, glGenTextures>(); }
Framebuffer makeFramebuffer() { return generate<Framebuffer, glGenFramebuffers>(); }
Renderbuffer makeRenderbuffer() { return generate<Renderbuffer, glGenRenderbuffers>(); }

Program::Program(const std::string& name, const std::string& vertexSource,
                 const std::string& fragmentSource) {
    GLuint vertex = compile(name, GL_VERTEX_SHADER, vertexSource);
    GLuint fragment = 0;
    try {
        fragment = compile(name, GL_FRAGMENT_SHADER, fragmentSource);
    } catch (...) {
        glDeleteShader(vertex);
        throw;
    }
    mId = glCreateProgram();
    glAttachShader(mId, vertex);
    glAttachShader(mId, fragment);
    glLinkProgram(mId);
    glDeleteShader(vertex);
    glDeleteShader(fragment);
    GLint ok = 0;
    glGetProgramiv(mId, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(mId, GL_INFO_LOG_LENGTH, &length);
        std::vector<char> log(std::size_t(length) + 1, '\0');
        glGetProgramInfoLog(mId, length, nullptr, log.data());
        glDeleteProgram(mId);
        throw Error("render: the " + name + " shader program does not link: " + log.data());
    }
}

Program::~Program() {
    if (mId) glDeleteProgram(mId);
}

void checkErrors(const char* what) {
    GLenum error = glGetError();
    if (error == GL_NO_ERROR) return;
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", error);
    while (glGetError() != GL_NO_ERROR) {
    }
    throw Error(std::string("render: OpenGL error ") + code + " while " + what);
}

}  // namespace globular::gl
