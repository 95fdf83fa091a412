// GLSL of the sphere passes (see sphere_pass.h for how they fit together).
#include <string>

#include "shaders.h"

namespace globular::shaders {

namespace {

// The eye ray through a window position, and its meeting with a sphere.
const char* const kRayLibrary = R"(
uniform vec3 uCamForward;  // unit view direction
uniform vec3 uCamRight;    // scaled so that +-1 reaches the image's right and left edges
uniform vec3 uCamUp;       // ... and its top and bottom edges
uniform vec2 uViewport;    // pixels

vec3 cameraRay(vec2 windowPosition) {
    vec2 ndc = windowPosition / uViewport * 2.0 - 1.0;
    return normalize(uCamForward + ndc.x * uCamRight + ndc.y * uCamUp);
}

// Distance along the eye ray `dir` to the sphere's front, or to the ray's closest
// approach when it misses. `outside`: how far the ray passes outside the sphere
// (negative when it hits); `along`: distance to the closest approach.
float sphereHitDistance(vec3 eye, vec3 dir, vec3 center, float radius,
                        out float outside, out float along) {
    vec3 toCenter = center - eye;
    along = dot(toCenter, dir);
    vec3 miss = toCenter - along * dir;
    float b2 = dot(miss, miss);
    float r2 = radius * radius;
    outside = sqrt(b2) - radius;
    return b2 < r2 ? along - sqrt(r2 - b2) : along;
}
)";

const char* const kBadGlobule = R"(
bool drawable(vec3 c, float r) {
    return r > 0.0 && !isinf(r) && !any(isnan(c)) && !any(isinf(c));
}
const vec4 kNowhere = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: not drawn

// Half the extent, in x/depth units, of the sphere's projection along one axis, about
// the projected centre c = a / depth: with tan(alpha) the tangent cone's half-angle,
// tan(theta + alpha) - tan(theta) = tan(alpha) (1 + c^2) / (1 - |c| tan(alpha)).
float axisHalfExtent(float a, float depth, float r) {
    float c = a / depth;
    float tanAlpha = r / sqrt(max(a * a + depth * depth - r * r, 1e-30));
    float denominator = 1.0 - abs(c) * tanAlpha;
    return denominator > 0.02 ? tanAlpha * (1.0 + c * c) / denominator : 1e9;
}
)";

}  // namespace

std::string cameraRayLibrary() { return kRayLibrary; }
std::string globuleSpriteLibrary() { return kBadGlobule; }

// Point sprites: one vertex per globule, the square sized to the exact screen extent of
// the sphere (sphere_pass.cpp computes the same size to pick sprites or squares).
std::string spherePointVertex() {
    return version() + kBadGlobule + R"(
layout(location = 1) in float aX;
layout(location = 2) in float aY;
layout(location = 3) in float aZ;
layout(location = 4) in float aRadius;
uniform mat4 uView;
uniform mat4 uViewProj;
uniform vec2 uFocalPixels;  // pixels per unit of x/depth and y/depth
uniform float uNear;
uniform float uMaxSprite;   // pixels
flat out vec3 vCenter;
flat out float vRadius;
flat out uint vId;


void main() {
    vec3 c = vec3(aX, aY, aZ);
    vCenter = c;
    vRadius = aRadius;
    vId = uint(gl_VertexID) + 1u;
    vec3 v = (uView * vec4(c, 1.0)).xyz;
    float depth = -v.z;
    float size = 1e9;
    if (drawable(c, aRadius) && depth - aRadius > uNear) {
        size = 2.0 * max(axisHalfExtent(v.x, depth, aRadius) * uFocalPixels.x,
                         axisHalfExtent(v.y, depth, aRadius) * uFocalPixels.y) + 1.0;
    }
    // Too big for a sprite: drawn as a square (sphereQuadVertex) instead.
    gl_Position = size <= uMaxSprite ? uViewProj * vec4(c, 1.0) : kNowhere;
    gl_PointSize = min(size, uMaxSprite);
}
)";
}

// Squares facing the eye, sized to the cone tangent to the sphere: for the few spheres
// too big on screen for a sprite.
std::string sphereQuadVertex() {
    return version() + kBadGlobule + R"(
layout(location = 0) in vec2 aCorner;  // (+-1, +-1)
layout(location = 1) in vec4 aSphere;  // centre, radius
layout(location = 2) in uint aId;      // index + 1
uniform mat4 uViewProj;
uniform vec3 uEye;
flat out vec3 vCenter;
flat out float vRadius;
flat out uint vId;

void main() {
    vec3 c = aSphere.xyz;
    float r = aSphere.w;
    vCenter = c;
    vRadius = r;
    vId = aId;
    vec3 toCenter = c - uEye;
    float d = length(toCenter);
    if (!drawable(c, r) || !(d > 1.001 * r)) {  // around the eye: nothing sensible to see
        gl_Position = kNowhere;
        return;
    }
    float halfSize = r * d / sqrt(d * d - r * r);
    vec3 z = toCenter / d;
    vec3 helper = abs(z.y) > 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    vec3 x = normalize(cross(z, helper));
    vec3 y = cross(x, z);
    gl_Position = uViewProj * vec4(c + halfSize * (aCorner.x * x + aCorner.y * y), 1.0);
}
)";
}

// Visibility: the exact depth of the nearest sphere and its id, nothing else; shading
// happens once per pixel afterwards, however many spheres overlap.
std::string sphereVisibilityFragment() {
    return version() + kRayLibrary + R"(
flat in vec3 vCenter;
flat in float vRadius;
flat in uint vId;
uniform vec3 uEye;
uniform mat4 uViewProj;
uniform float uPixelAngle;   // a pixel's width at unit distance, world units
uniform int uAlphaCoverage;  // multisampled: edge coverage becomes a sample mask
layout(location = 0) out vec4 fragCoverage;
layout(location = 1) out uint fragId;

void main() {
    vec3 dir = cameraRay(gl_FragCoord.xy);
    float outside, along;
    float t = sphereHitDistance(uEye, dir, vCenter, vRadius, outside, along);
    // Signed distance of the pixel centre from the silhouette, in pixels: an analytic
    // coverage that alpha-to-coverage turns into multisample anti-aliasing.
    float coverage = uAlphaCoverage != 0 ? clamp(0.5 - outside / (uPixelAngle * along), 0.0, 1.0)
                                         : (outside < 0.0 ? 1.0 : 0.0);
    if (coverage <= 0.0) discard;
    vec4 clip = uViewProj * vec4(uEye + t * dir, 1.0);
    gl_FragDepth = 0.5 + 0.5 * clip.z / clip.w;
    fragCoverage = vec4(0.0, 0.0, 0.0, coverage);
    fragId = vId;
}
)";
}

// Screen rectangles, in normalised device coordinates, around the spheres.
std::string tileVertex() {
    return version() + R"(
layout(location = 0) in vec2 aCorner;
void main() { gl_Position = vec4(aCorner, 0.0, 1.0); }
)";
}

// Shading: one invocation per pixel, over the screen tiles that hold spheres. Samples
// that saw a sphere are shaded with the first such sphere; the others are left (through
// gl_SampleMask) for the ground.
std::string sphereShadeFragment(int samples) {
    return fragment("#define SAMPLES " + std::to_string(samples) + "\n" + kRayLibrary + R"(
// The stencil test (samples a sphere covers) before the shader: the rest are skipped.
layout(early_fragment_tests) in;
#if SAMPLES > 1
uniform usampler2DMS uIds;
#else
uniform usampler2D uIds;
#endif
uniform samplerBuffer uX;
uniform samplerBuffer uY;
uniform samplerBuffer uZ;
uniform samplerBuffer uRadius;
uniform samplerBuffer uValue;
uniform samplerBuffer uVx;  // velocity, world units/s (zero without the motion pass)
uniform samplerBuffer uVy;
uniform samplerBuffer uVz;
uniform samplerBuffer uMaterial;  // material index (one element, 0, with one material)
uniform int uMaterials;           // 1: one material, uMaterial not read
layout(location = 0) out vec4 fragColor;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    uint id = 0u;
#if SAMPLES > 1
    int mask = 0;
    for (int s = 0; s < SAMPLES; ++s) {
        uint sampleId = texelFetch(uIds, p, s).r;
        if (sampleId != 0u) {
            mask |= 1 << s;
            if (id == 0u) id = sampleId;
        }
    }
    gl_SampleMask[0] = mask;
#else
    id = texelFetch(uIds, p, 0).r;
#endif
    if (id == 0u) discard;
    int k = int(id - 1u);
    vec3 c = vec3(texelFetch(uX, k).r, texelFetch(uY, k).r, texelFetch(uZ, k).r);
    float r = texelFetch(uRadius, k).r;
    vec3 albedo = albedoFor(uColorMode == 2 ? c.y : texelFetch(uValue, k).r);
    vec3 dir = cameraRay(gl_FragCoord.xy);
    float outside, along;
    vec3 hit = uEye + sphereHitDistance(uEye, dir, c, r, outside, along) * dir;
    vec3 n = normalize(hit - c);
    float material = uMaterials > 1 ? texelFetch(uMaterial, k).r : 0.0;
    fragColor = vec4(shadeMaterial(hit, n, albedo, material), 1.0);
    vec3 velocity = uFrameSeconds > 0.0 ? vec3(texelFetch(uVx, k).r, texelFetch(uVy, k).r,
                                               texelFetch(uVz, k).r)
                                          : vec3(0.0);
    writePasses(hit, n, velocity, 1.0);
}
)");
}

// In the key light's orthographic view a sphere is a disc whose front depth is exact.
std::string sphereShadowPointVertex() {
    return version() + kBadGlobule + R"(
layout(location = 1) in float aX;
layout(location = 2) in float aY;
layout(location = 3) in float aZ;
layout(location = 4) in float aRadius;
uniform mat4 uLightViewProj;
uniform vec3 uLightToward;    // unit, towards the light
uniform float uTexelsPerUnit;
uniform float uMaxSprite;     // texels
flat out float vCenterDepth;
flat out float vRadiusDepth;
flat out float vSpriteScale;  // sprite half-size over the radius

void main() {
    vec3 c = vec3(aX, aY, aZ);
    float size = drawable(c, aRadius) ? 2.0 * aRadius * uTexelsPerUnit + 1.0 : 1e9;
    vCenterDepth = (uLightViewProj * vec4(c, 1.0)).z;
    vRadiusDepth = (uLightViewProj * vec4(aRadius * uLightToward, 0.0)).z;
    vSpriteScale = size / (2.0 * aRadius * uTexelsPerUnit);
    gl_Position = size <= uMaxSprite ? uLightViewProj * vec4(c, 1.0) : kNowhere;
    gl_PointSize = min(size, uMaxSprite);
}
)";
}

std::string sphereShadowQuadVertex() {
    return version() + kBadGlobule + R"(
layout(location = 0) in vec2 aCorner;
layout(location = 1) in vec4 aSphere;
uniform mat4 uLightViewProj;
uniform vec3 uLightRight;   // world unit vectors spanning the light's image plane
uniform vec3 uLightUp;
uniform vec3 uLightToward;  // unit, towards the light
out vec2 vLocal;
flat out float vCenterDepth;
flat out float vRadiusDepth;

void main() {
    vec3 c = aSphere.xyz;
    float r = aSphere.w;
    vLocal = aCorner;
    vCenterDepth = (uLightViewProj * vec4(c, 1.0)).z;
    vRadiusDepth = (uLightViewProj * vec4(r * uLightToward, 0.0)).z;
    gl_Position = drawable(c, r) ? uLightViewProj * vec4(c + r * (aCorner.x * uLightRight +
                                                                  aCorner.y * uLightUp), 1.0)
                                 : kNowhere;
}
)";
}

std::string sphereShadowFragment(bool points) {
    return version() + (points ? "#define POINTS 1\n" : "") + R"(
flat in float vCenterDepth;
flat in float vRadiusDepth;
#ifdef POINTS
flat in float vSpriteScale;
#else
in vec2 vLocal;
#endif

void main() {
#ifdef POINTS
    vec2 local = (gl_PointCoord * 2.0 - 1.0) * vSpriteScale;
#else
    vec2 local = vLocal;
#endif
    float rho2 = dot(local, local);
    if (rho2 > 1.0) discard;
    gl_FragDepth = 0.5 + 0.5 * (vCenterDepth + vRadiusDepth * sqrt(1.0 - rho2));
}
)";
}

}  // namespace globular::shaders
