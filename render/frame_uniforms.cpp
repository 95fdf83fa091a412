#include "frame_uniforms.h"

#include <algorithm>

#include "color_ramp.h"
#include "environment_light.h"
#include "shadow_map.h"
#include "shaders.h"

namespace globular::detail {

void setVec3(const gl::Program& program, const char* name, Vec3 v) {
    glUniform3f(program.uniform(name), float(v.x), float(v.y), float(v.z));
}

void setMat4(const gl::Program& program, const char* name, const Mat4& m) {
    glUniformMatrix4fv(program.uniform(name), 1, GL_FALSE, m.m.data());
}

namespace {

void setVec3Array(const gl::Program& program, const char* name, const std::vector<Vec3>& values) {
    std::vector<float> flat;
    for (const Vec3& v : values) flat.insert(flat.end(), {float(v.x), float(v.y), float(v.z)});
    if (!values.empty()) glUniform3fv(program.uniform(name), GLsizei(values.size()), flat.data());
}

}  // namespace

void applyFrameUniforms(const gl::Program& p, const FrameUniforms& f) {
    setMat4(p, "uView", f.view);
    setMat4(p, "uViewProj", f.viewProj);
    setVec3(p, "uEye", f.eye);
    setVec3(p, "uCamForward", f.camForward);
    setVec3(p, "uCamRight", f.camRight);
    setVec3(p, "uCamUp", f.camUp);
    glUniform2f(p.uniform("uViewport"), float(f.width), float(f.height));
    glUniform1f(p.uniform("uNear"), f.zNear);
    glUniform1f(p.uniform("uPixelAngle"), f.pixelAngle);
    glUniform2f(p.uniform("uFocalPixels"), f.focalPixels[0], f.focalPixels[1]);
    const int lights = std::min<int>(int(f.lightToward.size()), shaders::kMaxLights);
    glUniform1i(p.uniform("uLightCount"), lights);
    setVec3Array(p, "uLightToward", {f.lightToward.begin(), f.lightToward.begin() + lights});
    setVec3Array(p, "uLightRadiance", {f.lightRadiance.begin(), f.lightRadiance.begin() + lights});
    glUniform1f(p.uniform("uSpecular"), f.specular);
    glUniform1fv(p.uniform("uMaterialRoughness"), 16, f.roughness.data());
    glUniform1fv(p.uniform("uMaterialMetallic"), 16, f.metallic.data());
    glUniform1fv(p.uniform("uMaterialSubsurface"), 16, f.subsurface.data());
    setVec3Array(p, "uIrradianceSH", {f.irradianceSH.begin(), f.irradianceSH.end()});
    glUniform1i(p.uniform("uEnvironmentMap"), kEnvironmentUnit);
    glUniform1f(p.uniform("uEnvironmentMaxLod"), f.environmentMaxLod);
    glUniform1f(p.uniform("uEnvironmentIntensity"), f.environmentIntensity);
    glUniform1f(p.uniform("uShadowSoftness"), f.shadowSoftness);
    glUniform1i(p.uniform("uShadowed"), f.shadowed ? 1 : 0);
    glUniform1i(p.uniform("uShadowMap"), kShadowMapUnit);
    setMat4(p, "uLightViewProj", f.lightViewProj);
    glUniform1f(p.uniform("uShadowTexel"), f.shadowTexel);
    glUniform1f(p.uniform("uShadowBias"), f.shadowBias);
    glUniform1i(p.uniform("uColorMode"), f.colorMode);
    setVec3(p, "uBaseColor", f.baseColor);
    setVec3Array(p, "uPalette", f.palette);
    const RampStops& stops = f.colorMode == 4 ? blackbodyStops() : rampStops();
    setVec3Array(p, "uRamp", {stops.begin(), stops.end()});
    glUniform2f(p.uniform("uRampRange"), f.rampMin, f.rampMax);
    setMat4(p, "uPassViewProj", f.viewProj);
    glUniform2f(p.uniform("uPassViewport"), float(f.width), float(f.height));
    glUniform1f(p.uniform("uFrameSeconds"), f.frameSeconds);
}

}  // namespace globular::detail
