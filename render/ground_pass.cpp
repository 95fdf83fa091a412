#include "ground_pass.h"

#include "shaders.h"

namespace globular::detail {

GroundPass::GroundPass()
    : mProgram("ground", shaders::groundVertex(), shaders::groundFragment()),
      mVertexArray(gl::makeVertexArray()),
      mCorners(gl::makeBuffer()) {}

void GroundPass::draw(const FrameUniforms& f, const GroundLook& look) const {
    const float reach = float(look.fadeEnd * 1.02);
    const float cx = float(look.center.x), cz = float(look.center.z), y = float(look.height);
    const float corners[] = {cx - reach, y, cz - reach, cx + reach, y, cz - reach,
                             cx - reach, y, cz + reach, cx + reach, y, cz + reach};
    glBindVertexArray(mVertexArray.id());
    glBindBuffer(GL_ARRAY_BUFFER, mCorners.id());
    glBufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STREAM_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(0);

    glUseProgram(mProgram.id());
    applyFrameUniforms(mProgram, f);
    setVec3(mProgram, "uGroundColor", look.color);
    glUniform1f(mProgram.uniform("uCheckerSize"), float(look.checkerSize));
    glUniform1f(mProgram.uniform("uCheckerContrast"), float(look.checkerContrast));
    glUniform2f(mProgram.uniform("uFadeCenter"), cx, cz);
    glUniform2f(mProgram.uniform("uFade"), float(look.fadeStart), float(look.fadeEnd));
    setVec3(mProgram, "uBackground", look.background);
    glUniform1f(mProgram.uniform("uBackgroundAlpha"), float(look.backgroundAlpha));
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glBindVertexArray(0);
}

}  // namespace globular::detail
