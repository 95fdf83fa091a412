#pragma once
// Internal to render/: the per-frame values every pass's shaders share, computed once
// from the frame setup, and the function that hands them to a program.

#include <array>
#include <vector>

#include "gl_objects.h"
#include "transform.h"
#include "vec3.h"

namespace globular::detail {

struct FrameUniforms {
    int width = 0, height = 0;  ///< pixels
    Mat4 view, viewProj;
    Vec3 eye;
    Vec3 camForward;                  ///< unit view direction
    Vec3 camRight, camUp;             ///< scaled to reach the image's edges at unit distance
    float zNear = 0, zFar = 0;        ///< world units
    float pixelAngle = 0;             ///< a pixel's width at unit distance, world units
    float focalPixels[2] = {0, 0};    ///< pixels per unit of x/depth and of y/depth
    std::vector<Vec3> lightToward;    ///< unit, towards each light
    std::vector<Vec3> lightRadiance;  ///< linear colour times intensity
    float specular = 0;        ///< dielectrics' reflectance (f0 = 0.16 specular^2)
    std::array<float, 16> roughness{};  ///< perceptual, by material index
    std::array<float, 16> metallic{};   ///< by material index
    std::array<float, 16> subsurface{};  ///< diffuse wrap, by material index
    std::array<Vec3, 9> irradianceSH{};  ///< the environment's irradiance (environment.h)
    float environmentMaxLod = 0;         ///< the pre-filtered cube's roughest level
    float environmentIntensity = 0;
    float shadowSoftness = 0;            ///< penumbra radius, shadow texels
    bool shadowed = false;
    Mat4 lightViewProj;
    Vec3 lightRight, lightUp;  ///< the key light's image plane, world unit vectors
    float shadowTexel = 0;     ///< world units
    int shadowMapSize = 0;     ///< texels per side this frame
    float texelsPerUnit = 0;   ///< shadow-map texels per world unit
    float shadowBias = 0;      ///< shadow-map depth units
    int colorMode = 0;         ///< 0 constant, 1 speed, 2 height, 3 material, 4 temperature
    std::vector<Vec3> palette = std::vector<Vec3>(16);  ///< linear, by material index
    Vec3 baseColor;            ///< linear
    float rampMin = 0, rampMax = 1;
    float frameSeconds = 0;    ///< the motion pass's interval (1/fps); 0: no motion pass
};

/// Sets the shared uniforms of @p program (which must be in use); the shadow map on
/// kShadowMapUnit (shadow_map.h), the environment's cube map on kEnvironmentUnit
/// (environment_light.h).
void applyFrameUniforms(const gl::Program& program, const FrameUniforms& frame);

void setVec3(const gl::Program& program, const char* name, Vec3 value);
void setMat4(const gl::Program& program, const char* name, const Mat4& value);

}  // namespace globular::detail
