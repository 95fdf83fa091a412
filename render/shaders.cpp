#include "shaders.h"

namespace globular::shaders {

namespace {

const char* const kVersion = "#version 420 core\n#define MAX_LIGHTS 8\n";

// Maps a per-globule or per-vertex value to a base colour (linear light).
const char* const kColorLibrary = R"(
uniform int uColorMode;     // 0 constant, 1 by value (speed), 2 by height, 3 by material,
                            // 4 by value (temperature; uRamp holds the blackbody stops)
uniform vec3 uPalette[16];  // linear, by material (value = the material's index)
uniform vec3 uBaseColor;    // linear
uniform vec3 uRamp[11];     // sRGB stops, evenly spaced
uniform vec2 uRampRange;    // value at the ramp's start and end

vec3 srgbToLinear(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}

vec3 albedoFor(float value) {
    if (uColorMode == 0) return uBaseColor;
    if (uColorMode == 3) return uPalette[clamp(int(value + 0.5), 0, 15)];
    float span = max(uRampRange.y - uRampRange.x, 1e-20);
    float t = clamp((value - uRampRange.x) / span, 0.0, 1.0) * 10.0;
    int i = min(int(t), 9);
    return srgbToLinear(mix(uRamp[i], uRamp[i + 1], t - float(i)));
}
)";

// The environment: the light arriving from every direction (sky, or an HDR file).
// environmentRadiance() is the seam other passes (reflections, refraction) call; its
// signature stays as it is.
const char* const kEnvironmentLibrary = R"(
const float PI = 3.14159265358979;
uniform vec3 uSkyZenith;        // linear radiance straight up
uniform vec3 uSkyHorizon;       // ... at the horizon
uniform vec3 uSkyGround;        // ... from below (the ground's bounce)
uniform float uEnvironmentIntensity;

// Radiance arriving from @p worldDirection (unit, pointing away from the surface),
// averaged over a GGX lobe of perceptual @p roughness (0 = mirror, 1 = fully rough).
vec3 environmentRadiance(vec3 worldDirection, float roughness) {
    float y = worldDirection.y;
    vec3 sky = mix(uSkyHorizon, uSkyZenith, sqrt(max(y, 0.0)));
    return uEnvironmentIntensity * mix(uSkyGround, sky, smoothstep(-0.05, 0.05, y));
}
)";

// One key light with a shadow map, optional fill lights, and a sky term; Blinn-Phong.
const char* const kShadingLibrary = R"(
uniform vec3 uEye;
uniform int uLightCount;
uniform vec3 uLightToward[MAX_LIGHTS];    // unit, from the surface towards the light
uniform vec3 uLightRadiance[MAX_LIGHTS];  // linear colour times intensity
uniform float uAmbient;
uniform int uShadowed;                    // the first light casts shadows
uniform sampler2DShadow uShadowMap;
uniform mat4 uLightViewProj;
uniform float uShadowTexel;               // world units per shadow texel
uniform float uShadowBias;                // in shadow-map depth units

float keyLightVisibility(vec3 p, vec3 n) {
    if (uShadowed == 0) return 1.0;
    // Normal offset: sample a little off the surface so it does not shadow itself.
    vec4 c = uLightViewProj * vec4(p + n * (1.5 * uShadowTexel), 1.0);
    vec3 s = c.xyz * 0.5 + 0.5;
    if (s.z >= 1.0) return 1.0;
    float ref = s.z - uShadowBias;
    vec2 texel = vec2(1.0) / vec2(textureSize(uShadowMap, 0));
    // Four bilinear (2x2) comparisons a texel apart: a soft 4x4 percentage-closer edge.
    float sum = texture(uShadowMap, vec3(s.xy + vec2(-0.75, -0.75) * texel, ref))
              + texture(uShadowMap, vec3(s.xy + vec2( 0.75, -0.75) * texel, ref))
              + texture(uShadowMap, vec3(s.xy + vec2(-0.75,  0.75) * texel, ref))
              + texture(uShadowMap, vec3(s.xy + vec2( 0.75,  0.75) * texel, ref));
    return 0.25 * sum;
}

// The compositing passes (frame_target.h), weighted by the colour's alpha so the resolve
// can divide the pixel's average by its coverage: the world normal, the distance from the
// eye, and the screen-space motion of a point moving at `velocity` (world units/s) over
// one frame (uFrameSeconds), pixels, x right and y up. Draw buffers 2 to 4 are off unless
// the frame asks for passes.
layout(location = 2) out vec4 fragNormal;
layout(location = 3) out float fragDistance;
layout(location = 4) out vec2 fragMotion;
uniform mat4 uPassViewProj;
uniform vec2 uPassViewport;  // pixels
uniform float uFrameSeconds;
void writePasses(vec3 p, vec3 n, vec3 velocity, float weight) {
    fragNormal = vec4(n * weight, weight);
    fragDistance = length(p - uEye) * weight;
    vec4 now = uPassViewProj * vec4(p, 1.0);
    vec4 next = uPassViewProj * vec4(p + velocity * uFrameSeconds, 1.0);
    fragMotion = (next.xy / next.w - now.xy / now.w) * 0.5 * uPassViewport * weight;
}

vec3 shade(vec3 p, vec3 n, vec3 albedo, float specular) {
    // Sky light: full from above, 60% from below (the ground returns some).
    vec3 color = albedo * uAmbient * (0.8 + 0.2 * n.y);
    vec3 v = normalize(uEye - p);
    for (int i = 0; i < uLightCount; ++i) {
        float ndl = dot(n, uLightToward[i]);
        if (ndl <= 0.0) continue;
        float visible = i == 0 ? keyLightVisibility(p, n) : 1.0;
        vec3 h = normalize(uLightToward[i] + v);
        float highlight = specular * pow(max(dot(n, h), 0.0), 60.0);
        color += visible * uLightRadiance[i] * (albedo * ndl + vec3(highlight));
    }
    return color;
}
)";

}  // namespace

std::string version() { return kVersion; }
std::string fragment(const std::string& body) {
    return version() + kColorLibrary + kEnvironmentLibrary + kShadingLibrary + body;
}
std::string vertex(const std::string& body) { return version() + kColorLibrary + body; }

std::string meshVertex() {
    return vertex(R"(
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;  // (0, 0, 0) when the mesh has none
layout(location = 2) in float aValue;  // material or temperature; 0 when the mesh has none
uniform mat4 uViewProj;
out vec3 vWorld;
out vec3 vNormal;
out vec3 vAlbedo;
void main() {
    vWorld = aPosition;
    vNormal = aNormal;
    vAlbedo = albedoFor(uColorMode == 2 ? aPosition.y : aValue);
    gl_Position = uViewProj * vec4(aPosition, 1.0);
}
)");
}

std::string meshFragment() {
    return fragment(R"(
in vec3 vWorld;
in vec3 vNormal;
in vec3 vAlbedo;
uniform float uSpecular;
layout(location = 0) out vec4 fragColor;
void main() {
    vec3 n = dot(vNormal, vNormal) > 0.25 ? normalize(vNormal)
                                          : normalize(cross(dFdx(vWorld), dFdy(vWorld)));
    // Two-sided: an open or inward-wound mesh still shades from the side we see.
    if (dot(n, uEye - vWorld) < 0.0) n = -n;
    fragColor = vec4(shade(vWorld, n, vAlbedo, uSpecular), 1.0);
    writePasses(vWorld, n, vec3(0.0), 1.0);
}
)");
}

std::string meshShadowVertex() {
    return version() + R"(
layout(location = 0) in vec3 aPosition;
uniform mat4 uLightViewProj;
void main() { gl_Position = uLightViewProj * vec4(aPosition, 1.0); }
)";
}

std::string depthOnlyFragment() { return version() + "void main() {}\n"; }

std::string groundVertex() {
    return version() + R"(
layout(location = 0) in vec3 aPosition;
uniform mat4 uViewProj;
out vec3 vWorld;
void main() {
    vWorld = aPosition;
    gl_Position = uViewProj * vec4(aPosition, 1.0);
}
)";
}

// A box-filtered checker (exact area average over the pixel's footprint), so the far
// ground greys out smoothly instead of shimmering, fading into the background.
// \see Inigo Quilez, "Filtering procedurals: checkerboard" (iquilezles.org).
std::string groundFragment() {
    return fragment(R"(
in vec3 vWorld;
uniform vec3 uGroundColor;   // linear
uniform float uCheckerSize;  // world units
uniform float uCheckerContrast;
uniform vec2 uFadeCenter;    // xz
uniform vec2 uFade;          // start and end distance of the fade into the background
uniform vec3 uBackground;    // linear
uniform float uBackgroundAlpha;  // 0: transparent background (premultiplied: colour 0)
layout(location = 0) out vec4 fragColor;

float filteredChecker(vec2 p) {
    vec2 w = max(abs(dFdx(p)) + abs(dFdy(p)), vec2(1e-4));
    vec2 i = 2.0 * (abs(fract((p - 0.5 * w) * 0.5) - 0.5) -
                    abs(fract((p + 0.5 * w) * 0.5) - 0.5)) / w;
    return 0.5 - 0.5 * i.x * i.y;
}

void main() {
    float checker = filteredChecker(vWorld.xz / uCheckerSize);
    vec3 albedo = uGroundColor * (1.0 - uCheckerContrast * checker);
    vec3 color = shade(vWorld, vec3(0.0, 1.0, 0.0), albedo, 0.0);
    float fade = smoothstep(uFade.x, uFade.y, length(vWorld.xz - uFadeCenter));
    // Premultiplied: over a transparent background the ground fades into alpha.
    float alpha = mix(1.0, uBackgroundAlpha, fade);
    fragColor = vec4(mix(color, uBackground * uBackgroundAlpha, fade), alpha);
    writePasses(vWorld, vec3(0.0, 1.0, 0.0), vec3(0.0), alpha);
}
)");
}

}  // namespace globular::shaders
