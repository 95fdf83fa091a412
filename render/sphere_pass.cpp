#include "sphere_pass.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "errors.h"
#include "shaders.h"

namespace globular::detail {

namespace {

enum Array { kX, kY, kZ, kRadius, kSpeed, kVx, kVy, kVz, kMaterial };

// Sprites are chosen below this fraction of the largest size the vertex shader accepts,
// so a float difference between this file and the shader cannot lose a sphere.
constexpr float kSpriteMargin = 10;

constexpr int kTile = 16;  // pixels per side of a shading tile

void uploadFloats(const gl::Buffer& buffer, const float* data, std::size_t n) {
    glBindBuffer(GL_ARRAY_BUFFER, buffer.id());
    // Orphan and refill: the driver need not wait for the previous frame's draw.
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(n * sizeof(float)), data, GL_STREAM_DRAW);
}

// As the point vertex shader: half the projection's extent along one axis, in units of
// x/depth, about the projected centre c (tangent-cone half-angle alpha, theta the
// centre's angle): tan(theta + alpha) - tan(theta) = tan(alpha) (1 + c^2) / (1 - |c| tan(alpha)).
double axisHalfExtent(double a, double depth, double r) {
    const double c = a / depth;
    const double tanAlpha = r / std::sqrt(std::max(a * a + depth * depth - r * r, 1e-30));
    const double denominator = 1.0 - std::abs(c) * tanAlpha;
    return denominator > 0.02 ? tanAlpha * (1.0 + c * c) / denominator
                              : std::numeric_limits<double>::infinity();
}

}  // namespace

float spriteSize(Vec3 v, double r, double focalX, double focalY, double zNear) {
    const double depth = -v.z;
    if (!(depth - r > zNear)) return std::numeric_limits<float>::infinity();
    return float(2.0 * std::max(axisHalfExtent(v.x, depth, r) * focalX,
                                axisHalfExtent(v.y, depth, r) * focalY) +
                 1.0);
}

SpherePass::SpherePass(int samples)
    : mSamples(samples),
      mVisibilityPoints("sphere sprite", shaders::spherePointVertex(),
                        shaders::sphereVisibilityFragment()),
      mVisibilitySquares("sphere square", shaders::sphereQuadVertex(),
                         shaders::sphereVisibilityFragment()),
      mShade("sphere shading", shaders::tileVertex(), shaders::sphereShadeFragment(samples)),
      mShadowPoints("sphere shadow sprite", shaders::sphereShadowPointVertex(),
                    shaders::sphereShadowFragment(true)),
      mShadowSquares("sphere shadow square", shaders::sphereShadowQuadVertex(),
                     shaders::sphereShadowFragment(false)),
      mPointArray(gl::makeVertexArray()),
      mSquareArray(gl::makeVertexArray()),
      mTileArray(gl::makeVertexArray()),
      mArrays{gl::makeBuffer(), gl::makeBuffer(), gl::makeBuffer(), gl::makeBuffer(),
              gl::makeBuffer(), gl::makeBuffer(), gl::makeBuffer(), gl::makeBuffer(),
              gl::makeBuffer()},
      mTextures{gl::makeTexture(), gl::makeTexture(), gl::makeTexture(), gl::makeTexture(),
                gl::makeTexture(), gl::makeTexture(), gl::makeTexture(), gl::makeTexture(),
                gl::makeTexture()},
      mCorners(gl::makeBuffer()),
      mSquares(gl::makeBuffer()),
      mSquareIds(gl::makeBuffer()),
      mTiles(gl::makeBuffer()),
      mVisibleIndices(gl::makeBuffer()),
      mShadowIndices(gl::makeBuffer()) {
    float pointSizes[2] = {1, 64};
    glGetFloatv(GL_POINT_SIZE_RANGE, pointSizes);
    mMaxSprite = std::min(250.0f, pointSizes[1] - 2.0f);

    glBindVertexArray(mPointArray.id());
    for (GLuint i = kX; i <= kRadius; ++i) {
        glBindBuffer(GL_ARRAY_BUFFER, mArrays[i].id());
        glVertexAttribPointer(i + 1, 1, GL_FLOAT, GL_FALSE, 0, nullptr);
        glEnableVertexAttribArray(i + 1);
    }
    const float corners[] = {-1, -1, 1, -1, -1, 1, 1, 1};
    glBindVertexArray(mSquareArray.id());
    glBindBuffer(GL_ARRAY_BUFFER, mCorners.id());
    glBufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STATIC_DRAW);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, mSquares.id());
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
    glVertexAttribDivisor(1, 1);
    glEnableVertexAttribArray(1);
    glBindBuffer(GL_ARRAY_BUFFER, mSquareIds.id());
    glVertexAttribIPointer(2, 1, GL_UNSIGNED_INT, 0, nullptr);
    glVertexAttribDivisor(2, 1);
    glEnableVertexAttribArray(2);
    glBindVertexArray(mTileArray.id());
    glBindBuffer(GL_ARRAY_BUFFER, mTiles.id());
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(0);
    glBindVertexArray(0);
    gl::checkErrors("setting up the sphere passes");
}

void SpherePass::upload(const Globules& g, Value value, const FrameUniforms& f) {
    const bool withSpeed = value == Value::Speed;
    const bool withMotion = f.frameSeconds > 0;
    const std::size_t n = g.size();
    if (g.py.size() != n || g.pz.size() != n || g.radius.size() != n ||
        ((withSpeed || withMotion) &&
         (g.vx.size() != n || g.vy.size() != n || g.vz.size() != n))) {
        throw Error("render: the globules' arrays have different lengths");
    }
    mCount = n;
    uploadFloats(mArrays[kX], g.px.data(), n);
    uploadFloats(mArrays[kY], g.py.data(), n);
    uploadFloats(mArrays[kZ], g.pz.data(), n);
    uploadFloats(mArrays[kRadius], g.radius.data(), n);
    std::vector<float> speed(value != Value::None ? n : 1, 0.0f);
    for (std::size_t i = 0; withSpeed && i < n; ++i) {
        speed[i] = std::sqrt(g.vx[i] * g.vx[i] + g.vy[i] * g.vy[i] + g.vz[i] * g.vz[i]);
    }
    for (std::size_t i = 0; value == Value::Material && i < n; ++i) speed[i] = g.materialOf(i);
    if (value == Value::Temperature) {
        if (g.temperature.size() != n) throw Error("render: the globules carry no temperature");
        std::copy(g.temperature.begin(), g.temperature.end(), speed.begin());
    }
    uploadFloats(mArrays[kSpeed], speed.data(), speed.size());
    const float still = 0;
    uploadFloats(mArrays[kVx], withMotion ? g.vx.data() : &still, withMotion ? n : 1);
    uploadFloats(mArrays[kVy], withMotion ? g.vy.data() : &still, withMotion ? n : 1);
    uploadFloats(mArrays[kVz], withMotion ? g.vz.data() : &still, withMotion ? n : 1);
    // Each globule's roughness and metallic come from its material.
    mSeveralMaterials = g.material.size() == n && n > 0;
    std::vector<float> material(mSeveralMaterials ? n : 1, 0.0f);
    for (std::size_t i = 0; mSeveralMaterials && i < n; ++i) material[i] = g.material[i];
    uploadFloats(mArrays[kMaterial], material.data(), material.size());
    for (int i = kX; i <= kMaterial; ++i) {
        glBindTexture(GL_TEXTURE_BUFFER, mTextures[i].id());
        glTexBuffer(GL_TEXTURE_BUFFER, GL_R32F, mArrays[i].id());
    }
    glBindTexture(GL_TEXTURE_BUFFER, 0);

    // The sprites that may be seen, in the camera's view and the light's (sphere_culling.h);
    // the few spheres too big for a sprite in either; and the screen rectangle of every
    // sprite drawn, for the shading tiles (hidden ones lie within tiles of those drawn).
    // The camera's view and the light's are culled at the same time.
    const bool shadowCulling = mCulling && f.shadowed;
    tbb::parallel_invoke(
        [&] {
            cameraDiscs(g, f, mDiscs);
            if (mCulling) mCuller.cull(mDiscs, f.width, f.height, mVisible);
            if (!mCulling) mVisible.clear();
        },
        [&] {
            if (!shadowCulling) return;
            lightDiscs(g, f, mLightDiscs);
            mLightCuller.cull(mLightDiscs, f.shadowMapSize, f.shadowMapSize, mShadowVisible);
        });
    const std::vector<ScreenDisc>& discs = mDiscs;
    std::vector<float> squares, rects;
    std::vector<uint32_t> ids;
    const float limit = mMaxSprite - kSpriteMargin;
    bool everywhere = false;  // a sphere reaching the near plane: shade everything
    for (std::size_t i = 0; i < n; ++i) {
        const ScreenDisc& d = discs[i];
        if (!(d.half >= 0)) continue;  // not finite: the shaders skip these
        const float r = g.radius[i];
        const bool bigInLight = f.shadowed && 2.0f * r * f.texelsPerUnit + 1.0f > limit;
        if (bigInLight || !(2.0f * (d.half - 1.0f) <= limit)) {
            squares.insert(squares.end(), {g.px[i], g.py[i], g.pz[i], r});
            ids.push_back(uint32_t(i + 1));
        }
        if (std::isinf(d.half)) everywhere = true;
    }
    if (!everywhere) {
        auto addRect = [&](const ScreenDisc& d) {
            if (!(d.half >= 0)) return;
            rects.insert(rects.end(), {d.x - d.half, d.y - d.half, d.x + d.half, d.y + d.half});
        };
        rects.reserve(4 * (mCulling ? mVisible.size() : n));
        if (mCulling) {
            for (uint32_t i : mVisible) addRect(discs[i]);
        } else {
            for (const ScreenDisc& d : discs) addRect(d);
        }
    }
    if (!shadowCulling) mShadowVisible.clear();
    if (mCulling) {
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mVisibleIndices.id());
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mVisible.size() * sizeof(uint32_t)),
                     mVisible.data(), GL_STREAM_DRAW);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mShadowIndices.id());
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mShadowVisible.size() * sizeof(uint32_t)),
                     mShadowVisible.data(), GL_STREAM_DRAW);
    }
    mSquareCount = ids.size();
    glBindBuffer(GL_ARRAY_BUFFER, mSquares.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(squares.size() * sizeof(float)), squares.data(),
                 GL_STREAM_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, mSquareIds.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(ids.size() * sizeof(uint32_t)), ids.data(),
                 GL_STREAM_DRAW);
    uploadTiles(rects, everywhere, f);
    gl::checkErrors("uploading globules");
}

void SpherePass::uploadTiles(const std::vector<float>& rects, bool everywhere,
                             const FrameUniforms& f) {
    const int columns = (f.width + kTile - 1) / kTile, rows = (f.height + kTile - 1) / kTile;
    std::vector<uint8_t> marked(std::size_t(columns) * rows, everywhere ? 1 : 0);
    for (std::size_t k = 0; !everywhere && k < rects.size(); k += 4) {
        const int x0 = std::max(0, int(std::floor(rects[k] / kTile)));
        const int y0 = std::max(0, int(std::floor(rects[k + 1] / kTile)));
        const int x1 = std::min(columns - 1, int(std::floor(rects[k + 2] / kTile)));
        const int y1 = std::min(rows - 1, int(std::floor(rects[k + 3] / kTile)));
        for (int ty = y0; ty <= y1; ++ty) {
            for (int tx = x0; tx <= x1; ++tx) marked[std::size_t(ty) * columns + tx] = 1;
        }
    }
    std::vector<float> corners;
    auto ndcX = [&](int tx) { return std::min(1.0f, 2.0f * tx * kTile / f.width - 1.0f); };
    auto ndcY = [&](int ty) { return std::min(1.0f, 2.0f * ty * kTile / f.height - 1.0f); };
    for (int ty = 0; ty < rows; ++ty) {
        for (int tx = 0; tx < columns;) {
            if (!marked[std::size_t(ty) * columns + tx]) {
                ++tx;
                continue;
            }
            const int start = tx;
            while (tx < columns && marked[std::size_t(ty) * columns + tx]) ++tx;
            const float x0 = ndcX(start), x1 = ndcX(tx), y0 = ndcY(ty), y1 = ndcY(ty + 1);
            corners.insert(corners.end(), {x0, y0, x1, y0, x0, y1, x1, y0, x1, y1, x0, y1});
        }
    }
    mTileVertices = corners.size() / 2;
    glBindBuffer(GL_ARRAY_BUFFER, mTiles.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(corners.size() * sizeof(float)), corners.data(),
                 GL_STREAM_DRAW);
}

void SpherePass::drawSquares() const {
    if (mSquareCount == 0) return;
    glBindVertexArray(mSquareArray.id());
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(mSquareCount));
}

void SpherePass::drawPoints(const gl::Buffer& indices, std::size_t count) const {
    glBindVertexArray(mPointArray.id());
    if (mCulling) {
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices.id());
        // Indexed: gl_VertexID is the globule's index, as the shaders expect.
        glDrawElements(GL_POINTS, GLsizei(count), GL_UNSIGNED_INT, nullptr);
    } else {
        glDrawArrays(GL_POINTS, 0, GLsizei(mCount));
    }
}

void SpherePass::drawShadow(const FrameUniforms& f) const {
    if (mCount == 0) return;
    glEnable(GL_PROGRAM_POINT_SIZE);
    glUseProgram(mShadowPoints.id());
    setMat4(mShadowPoints, "uLightViewProj", f.lightViewProj);
    setVec3(mShadowPoints, "uLightToward", f.lightToward.front());
    glUniform1f(mShadowPoints.uniform("uTexelsPerUnit"), f.texelsPerUnit);
    glUniform1f(mShadowPoints.uniform("uMaxSprite"), mMaxSprite);
    drawPoints(mShadowIndices, mShadowVisible.size());

    glUseProgram(mShadowSquares.id());
    setMat4(mShadowSquares, "uLightViewProj", f.lightViewProj);
    setVec3(mShadowSquares, "uLightRight", f.lightRight);
    setVec3(mShadowSquares, "uLightUp", f.lightUp);
    setVec3(mShadowSquares, "uLightToward", f.lightToward.front());
    drawSquares();
    glBindVertexArray(0);
}

void SpherePass::drawVisibility(const FrameUniforms& f, const FrameTarget& target) const {
    if (mCount == 0) return;
    target.drawIds();
    const bool coverage = mSamples > 1;
    if (coverage) glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    // Mark the covered samples for the shading pass.
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glEnable(GL_PROGRAM_POINT_SIZE);
    for (const gl::Program* program : {&mVisibilityPoints, &mVisibilitySquares}) {
        glUseProgram(program->id());
        applyFrameUniforms(*program, f);
        glUniform1i(program->uniform("uAlphaCoverage"), coverage ? 1 : 0);
        glUniform1f(program->uniform("uMaxSprite"), mMaxSprite);
        if (program == &mVisibilityPoints) {
            drawPoints(mVisibleIndices, mVisible.size());
        } else {
            drawSquares();
        }
    }
    glBindVertexArray(0);
    glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    glDisable(GL_STENCIL_TEST);
    target.drawColor();
}

void SpherePass::drawShading(const FrameUniforms& f, const FrameTarget& target) const {
    if (mCount == 0) return;
    target.drawColor();
    glUseProgram(mShade.id());
    applyFrameUniforms(mShade, f);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(mSamples > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D, target.idTexture());
    glUniform1i(mShade.uniform("uIds"), 1);
    const char* names[] = {"uX", "uY", "uZ", "uRadius", "uValue", "uVx", "uVy", "uVz", "uMaterial"};
    glUniform1i(mShade.uniform("uMaterials"), mSeveralMaterials ? 2 : 1);
    for (int i = kX; i <= kMaterial; ++i) {
        glActiveTexture(GL_TEXTURE2 + i);
        glBindTexture(GL_TEXTURE_BUFFER, mTextures[i].id());
        glUniform1i(mShade.uniform(names[i]), 2 + i);
    }
    glActiveTexture(GL_TEXTURE0);
    // Each pixel a sphere covers, once: the tiles and (single-sampled) the stencil skip the
    // others before their fragment shader runs. The depth buffer keeps the spheres'
    // depth for the ground.
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glBindVertexArray(mTileArray.id());
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(mTileVertices));
    glBindVertexArray(0);
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_DEPTH_TEST);
}

}  // namespace globular::detail
