#include "occlusion_pass.h"

#include <string>

#include "shaders.h"

namespace globular::detail {

namespace {

std::string occlusionVertex() {
    return shaders::version() + R"(
// The corners of the rectangles the pass covers, window coordinates.
layout(location = 0) in vec2 aCorner;
uniform vec2 uViewport;
void main() {
    gl_Position = vec4(aCorner / uViewport * 2.0 - 1.0, 0.0, 1.0);
}
)";
}

std::string occlusionFragment(int samples) {
    return shaders::version() + (samples > 1 ? "#define MULTISAMPLED 1\n" : "") + R"(
#ifdef MULTISAMPLED
uniform sampler2DMS uDepth;
#else
uniform sampler2D uDepth;
#endif
uniform vec3 uEye;
uniform vec3 uCamForward;  // unit
uniform vec3 uCamRight;    // reaching the image's edges at unit distance along uCamForward
uniform vec3 uCamUp;
uniform vec2 uViewport;
uniform float uNear;
uniform float uFar;
uniform mat4 uViewProj;
uniform float uRadius;     // world units
uniform float uStrength;
layout(location = 0) out vec4 fragColor;

const int kTaps = 8;

float depthAt(ivec2 p) {
    return texelFetch(uDepth, clamp(p, ivec2(0), ivec2(uViewport) - 1), 0).r;
}

// Distance along the view direction of a depth-buffer value (perspective projection).
float viewDepth(float d) {
    float z = 2.0 * d - 1.0;
    return 2.0 * uNear * uFar / (uFar + uNear - z * (uFar - uNear));
}

vec3 worldAt(ivec2 p) {
    vec2 ndc = (vec2(p) + 0.5) / uViewport * 2.0 - 1.0;
    return uEye + viewDepth(depthAt(p)) * (uCamForward + ndc.x * uCamRight + ndc.y * uCamUp);
}

// The step to the neighbour along @p axis on the nearer side: no normal is bent across a
// silhouette. At the frame's edge, to the one inside it: the one beyond would read the
// edge pixel's depth on another ray, a point off the surface, and tilt the normal.
vec3 nearerStep(ivec2 pixel, ivec2 axis, vec3 p) {
    ivec2 before = pixel - axis, after = pixel + axis;
    vec3 a = p - worldAt(before), b = worldAt(after) - p;
    if (any(lessThan(before, ivec2(0)))) return b;
    if (any(greaterThanEqual(after, ivec2(uViewport)))) return a;
    return dot(a, a) < dot(b, b) ? a : b;
}

float interleavedGradientNoise(vec2 pixel) {
    return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float d = depthAt(pixel);
    if (d >= 1.0) discard;  // the background
    vec3 p = worldAt(pixel);
    vec3 dx = nearerStep(pixel, ivec2(1, 0), p);
    vec3 dy = nearerStep(pixel, ivec2(0, 1), p);
    vec3 n = normalize(cross(dx, dy));
    if (dot(n, uEye - p) < 0.0) n = -n;
    vec3 helper = abs(n.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 t = normalize(cross(helper, n));
    vec3 b = cross(n, t);
    float depth = viewDepth(d);
    // Where the radius is under a pixel or two there is nothing to see, only noise.
    float pixels = uRadius / depth * uViewport.y / (2.0 * length(uCamUp));
    float strength = uStrength * smoothstep(1.0, 3.0, pixels);
    if (strength <= 0.0) discard;
    // The depth buffer's own step at this distance (24 bits): nothing nearer occludes.
    float bias = 0.02 * uRadius + 4.0 * (viewDepth(min(d + 4.0 / 16777216.0, 1.0)) - depth);
    float spin = 6.2831853 * interleavedGradientNoise(gl_FragCoord.xy);
    float occluded = 0.0;
    for (int k = 0; k < kTaps; ++k) {
        // A golden-angle spiral over the hemisphere, denser near the point.
        float f = (float(k) + 0.5) / float(kTaps);
        float cosTheta = 1.0 - 0.9 * f;
        float sinTheta = sqrt(1.0 - cosTheta * cosTheta);
        float phi = 2.39996323 * float(k) + spin;
        float reach = uRadius * mix(0.15, 1.0, f * f);
        vec3 q = p + reach * (sinTheta * cos(phi) * t + sinTheta * sin(phi) * b + cosTheta * n);
        vec4 c = uViewProj * vec4(q, 1.0);
        if (c.w <= uNear) continue;
        ivec2 at = ivec2(floor((c.xy / c.w * 0.5 + 0.5) * uViewport));
        // Beyond the frame nothing is known to occlude: the edge pixel's depth lies on
        // another ray (it darkened the ground along the frame's edges).
        if (any(lessThan(at, ivec2(0))) || any(greaterThanEqual(at, ivec2(uViewport)))) continue;
        float seen = viewDepth(depthAt(at));
        // Only what lies within the radius occludes (not a far wall behind a silhouette).
        float inRange = smoothstep(0.0, 1.0, uRadius / max(abs(depth - seen), 1e-6));
        occluded += (seen < c.w - bias ? 1.0 : 0.0) * inRange;
    }
    float visible = 1.0 - strength * occluded / float(kTaps);
    fragColor = vec4(vec3(visible), 1.0);
}
)";
}

}  // namespace

OcclusionPass::OcclusionPass(int samples)
    : mSamples(samples),
      mProgram("ambient occlusion", occlusionVertex(), occlusionFragment(samples)),
      mVertexArray(gl::makeVertexArray()),
      mCorners(gl::makeBuffer()) {
    glBindVertexArray(mVertexArray.id());
    glBindBuffer(GL_ARRAY_BUFFER, mCorners.id());
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void OcclusionPass::apply(const FrameUniforms& f, const FrameTarget& target, float radius,
                          float strength,
                          const std::optional<std::vector<PixelRect>>& region) const {
    if (!(strength > 0) || !(radius > 0) || (region && region->empty())) return;
    // Two triangles per rectangle, corners on pixel edges.
    const std::vector<PixelRect> whole{{0, 0, f.width - 1, f.height - 1}};
    std::vector<float> corners;
    corners.reserve((region ? region->size() : 1) * 12);
    for (const PixelRect& r : region ? *region : whole) {
        const float x0 = float(r.x0), y0 = float(r.y0), x1 = float(r.x1 + 1), y1 = float(r.y1 + 1);
        corners.insert(corners.end(), {x0, y0, x1, y0, x1, y1, x0, y0, x1, y1, x0, y1});
    }
    glBindBuffer(GL_ARRAY_BUFFER, mCorners.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(corners.size() * sizeof(float)), corners.data(),
                 GL_STREAM_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    target.bindColorOnly();
    glUseProgram(mProgram.id());
    setVec3(mProgram, "uEye", f.eye);
    setVec3(mProgram, "uCamForward", f.camForward);
    setVec3(mProgram, "uCamRight", f.camRight);
    setVec3(mProgram, "uCamUp", f.camUp);
    glUniform2f(mProgram.uniform("uViewport"), float(f.width), float(f.height));
    glUniform1f(mProgram.uniform("uNear"), f.zNear);
    glUniform1f(mProgram.uniform("uFar"), f.zFar);
    setMat4(mProgram, "uViewProj", f.viewProj);
    glUniform1f(mProgram.uniform("uRadius"), radius);
    glUniform1f(mProgram.uniform("uStrength"), strength);
    const int unit = 14;
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(mSamples > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D, target.depthTexture());
    glUniform1i(mProgram.uniform("uDepth"), unit);
    glActiveTexture(GL_TEXTURE0);
    // Multiply: colour times the visible fraction, alpha kept.
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ZERO, GL_SRC_COLOR);
    glBindVertexArray(mVertexArray.id());
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(corners.size() / 2));
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(mSamples > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
    target.bind();
}

}  // namespace globular::detail
