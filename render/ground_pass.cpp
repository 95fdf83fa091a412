#include "ground_pass.h"

#include <algorithm>
#include <array>
#include <vector>

#include "shaders.h"

namespace globular::detail {

GroundPass::GroundPass()
    : mShadowed("ground", shaders::groundVertex(), shaders::groundFragment(true)),
      mLit("ground (lit)", shaders::groundVertex(), shaders::groundFragment(false)),
      mVertexArray(gl::makeVertexArray()),
      mCorners(gl::makeBuffer()) {}

void GroundPass::draw(const FrameUniforms& f, const GroundLook& look,
                      const std::optional<GroundRect>& shadowRegion) const {
    const double reach = look.fadeEnd * 1.02;
    const GroundRect square{look.center.x - reach, look.center.z - reach,
                            look.center.x + reach, look.center.z + reach};
    const float y = float(look.height);
    // Corners counter-clockwise from (x0, z0); every triangle below is a list of three.
    auto cornersOf = [](const GroundRect& r) {
        return std::array<std::array<float, 2>, 4>{{{float(r.x0), float(r.z0)},
                                                    {float(r.x1), float(r.z0)},
                                                    {float(r.x1), float(r.z1)},
                                                    {float(r.x0), float(r.z1)}}};
    };
    std::vector<float> shadowed, lit;
    auto add = [&](std::vector<float>& to, const std::array<float, 2>& c) {
        to.insert(to.end(), {c[0], y, c[1]});
    };
    auto addQuad = [&](std::vector<float>& to, const std::array<float, 2>& a,
                       const std::array<float, 2>& b, const std::array<float, 2>& c,
                       const std::array<float, 2>& d) {
        for (const auto* corner : {&a, &b, &c, &a, &c, &d}) add(to, *corner);
    };
    const auto outer = cornersOf(square);
    GroundRect inner;
    if (shadowRegion) {
        inner = {std::max(square.x0, shadowRegion->x0), std::max(square.z0, shadowRegion->z0),
                 std::min(square.x1, shadowRegion->x1), std::min(square.z1, shadowRegion->z1)};
    }
    if (!shadowRegion) {
        addQuad(shadowed, outer[0], outer[1], outer[2], outer[3]);
    } else if (inner.empty()) {
        addQuad(lit, outer[0], outer[1], outer[2], outer[3]);
    } else {
        // The region, and around it four trapezoids between its corners and the square's
        // (convex, as both rectangles are axis-aligned and one holds the other): edges
        // shared corner to corner, which the rasteriser covers exactly once.
        const auto in = cornersOf(inner);
        addQuad(shadowed, in[0], in[1], in[2], in[3]);
        for (int k = 0; k < 4; ++k) {
            const int next = (k + 1) % 4;
            addQuad(lit, outer[std::size_t(k)], outer[std::size_t(next)], in[std::size_t(next)],
                    in[std::size_t(k)]);
        }
    }
    // Whatever lies on the floor (a container's base) wins the depth test against it:
    // without the offset the two fought, and which won followed the floor's triangles.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
    if (!shadowed.empty()) drawTriangles(mShadowed, f, look, shadowed.data(), int(shadowed.size() / 3));
    if (!lit.empty()) drawTriangles(mLit, f, look, lit.data(), int(lit.size() / 3));
    glDisable(GL_POLYGON_OFFSET_FILL);
}

void GroundPass::drawTriangles(const gl::Program& program, const FrameUniforms& f,
                               const GroundLook& look, const float* corners,
                               int cornerCount) const {
    glBindVertexArray(mVertexArray.id());
    glBindBuffer(GL_ARRAY_BUFFER, mCorners.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(sizeof(float) * 3 * std::size_t(cornerCount)),
                 corners, GL_STREAM_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(0);

    glUseProgram(program.id());
    applyFrameUniforms(program, f);
    setVec3(program, "uGroundColor", look.color);
    glUniform1f(program.uniform("uCheckerSize"), float(look.checkerSize));
    glUniform1f(program.uniform("uCheckerContrast"), float(look.checkerContrast));
    glUniform2f(program.uniform("uFadeCenter"), float(look.center.x), float(look.center.z));
    glUniform2f(program.uniform("uFade"), float(look.fadeStart), float(look.fadeEnd));
    setVec3(program, "uBackground", look.background);
    glUniform1f(program.uniform("uBackgroundAlpha"), float(look.backgroundAlpha));
    glDrawArrays(GL_TRIANGLES, 0, cornerCount);
    glBindVertexArray(0);
}

}  // namespace globular::detail
