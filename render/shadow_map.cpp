#include "shadow_map.h"

#include <algorithm>
#include <cmath>

#include "errors.h"

namespace globular::detail {

ShadowMap::ShadowMap(int maxSize)
    : mMaxSize(maxSize), mDepth(gl::makeTexture()), mFramebuffer(gl::makeFramebuffer()) {
    allocate(std::min(512, maxSize));
}

int ShadowMap::sizeFor(double worldSize, double pixelWorldSize) const {
    const double texel = std::max(pixelWorldSize, 1e-12);
    const double wanted = std::ceil(worldSize / texel / 64) * 64;
    return int(std::clamp(wanted, double(std::min(512, mMaxSize)), double(mMaxSize)));
}

void ShadowMap::allocate(int size) {
    mSize = size;
    glBindTexture(GL_TEXTURE_2D, mDepth.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, size, size, 0, GL_DEPTH_COMPONENT,
                 GL_UNSIGNED_INT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    // Outside the map nothing casts a shadow: the border is the far plane.
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
    const float far[] = {1, 1, 1, 1};
    glTexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, far);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glBindFramebuffer(GL_FRAMEBUFFER, mFramebuffer.id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, mDepth.id(), 0);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        throw Error("render: the shadow map framebuffer is incomplete");
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::checkErrors("creating the shadow map");
}

void ShadowMap::beginDrawing(int size) {
    if (size != mSize) allocate(size);
    glBindFramebuffer(GL_FRAMEBUFFER, mFramebuffer.id());
    glViewport(0, 0, mSize, mSize);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
}

TexelRect ShadowMap::drawnTexels() {
    mReadBack.resize(std::size_t(mSize) * std::size_t(mSize));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, mFramebuffer.id());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, mSize, mSize, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, mReadBack.data());
    gl::checkErrors("reading the shadow map back");
    // The cleared far plane reads as the largest value; anything drawn is nearer.
    constexpr uint32_t kFar = 0xffffffffu;
    TexelRect drawn{mSize, mSize, -1, -1};
    for (int y = 0; y < mSize; ++y) {
        const uint32_t* row = mReadBack.data() + std::size_t(y) * std::size_t(mSize);
        // A branch-free pass first: most rows hold nothing.
        uint32_t nearest = kFar;
        for (int x = 0; x < mSize; ++x) nearest = std::min(nearest, row[x]);
        if (nearest == kFar) continue;
        int first = 0, last = mSize - 1;
        while (row[first] == kFar) ++first;
        while (row[last] == kFar) --last;
        drawn = {std::min(drawn.x0, first), std::min(drawn.y0, y), std::max(drawn.x1, last), y};
    }
    return drawn.empty() ? TexelRect{} : drawn;
}

void ShadowMap::bindForSampling() const {
    glActiveTexture(GL_TEXTURE0 + kShadowMapUnit);
    glBindTexture(GL_TEXTURE_2D, mDepth.id());
    glActiveTexture(GL_TEXTURE0);
}

}  // namespace globular::detail
