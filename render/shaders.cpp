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

// The environment: the light arriving from every direction (the procedural sky, or an HDR
// file), prepared on the CPU (environment.h): a cube map pre-filtered by roughness for
// specular light, 9 spherical-harmonic coefficients of the irradiance for diffuse light.
// environmentRadiance() is the seam other passes (reflections, refraction) call; its
// signature stays as it is.
const char* const kEnvironmentLibrary = R"(
const float PI = 3.14159265358979;
uniform samplerCube uEnvironmentMap;  // level l: GGX roughness l / uEnvironmentMaxLod
uniform float uEnvironmentMaxLod;
uniform vec3 uIrradianceSH[9];        // E(n) polynomial coefficients (environment.h)
uniform float uEnvironmentIntensity;

// Radiance arriving from @p worldDirection (unit, pointing away from the surface),
// averaged over a GGX lobe of perceptual @p roughness (0 = mirror, 1 = fully rough).
vec3 environmentRadiance(vec3 worldDirection, float roughness) {
    float lod = clamp(roughness, 0.0, 1.0) * uEnvironmentMaxLod;
    return uEnvironmentIntensity * textureLod(uEnvironmentMap, worldDirection, lod).rgb;
}

// Irradiance on a surface of unit normal @p n: the environment's radiance times the
// clamped cosine, integrated over the sphere (Ramamoorthi and Hanrahan 2001).
vec3 environmentIrradiance(vec3 n) {
    vec3 e = uIrradianceSH[0] + uIrradianceSH[1] * n.y + uIrradianceSH[2] * n.z +
             uIrradianceSH[3] * n.x + uIrradianceSH[4] * (n.x * n.y) +
             uIrradianceSH[5] * (n.y * n.z) + uIrradianceSH[6] * (3.0 * n.z * n.z - 1.0) +
             uIrradianceSH[7] * (n.x * n.z) + uIrradianceSH[8] * (n.x * n.x - n.y * n.y);
    return uEnvironmentIntensity * max(e, vec3(0.0));
}
)";

// Physically based shading (metallic workflow), each formula once, named after its
// paper as in Filament (Guy and Agopian, "Physically Based Rendering in Filament").
const char* const kBrdfLibrary = R"(
// Walter, Marschner, Li and Torrance, "Microfacet Models for Refraction through Rough
// Surfaces", EGSR 2007: the GGX (Trowbridge-Reitz) distribution of normals; a = roughness^2.
float D_GGX(float NoH, float a) {
    float a2 = a * a;
    float f = (NoH * a2 - NoH) * NoH + 1.0;
    return a2 / (PI * f * f);
}

// Heitz, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT
// 2014: Smith's height-correlated masking-shadowing, as V = G / (4 NoV NoL).
float V_SmithGGXCorrelated(float NoV, float NoL, float a) {
    float a2 = a * a;
    float lambdaV = NoL * sqrt((NoV - NoV * a2) * NoV + a2);
    float lambdaL = NoV * sqrt((NoL - NoL * a2) * NoL + a2);
    return 0.5 / max(lambdaV + lambdaL, 1e-7);
}

// Schlick, "An Inexpensive BRDF Model for Physically-based Rendering", Computer Graphics
// Forum 1994: Fresnel reflectance from its value at normal incidence f0 to f90 at grazing.
vec3 F_Schlick(vec3 f0, float f90, float VoH) {
    float x = 1.0 - VoH;
    float x2 = x * x;
    return f0 + (vec3(f90) - f0) * (x2 * x2 * x);
}

// Lambert: a perfectly diffuse surface of albedo 1 reflects E / pi in every direction.
float Fd_Lambert() { return 1.0 / PI; }

// Wrapped diffuse (Green, "Real-Time Approximations to Subsurface Scattering", GPU Gems,
// 2004, ch. 16), normalised as Filament's cloth model does: the cosine factor of Lambert
// becomes max(NoL + w, 0) / (1 + w)^2, so light reaches w past the shadow line, the side
// facing the light dims to 1 / (1 + w), and a sphere reflects in all exactly what a
// Lambert sphere does (the integral over the sphere is pi for any w). w = 0: max(NoL, 0).
float Fd_Wrap(float NoL, float w) { return max(NoL + w, 0.0) / ((1.0 + w) * (1.0 + w)); }

// Karis, "Physically Based Shading on Mobile" (Unreal Engine blog, 2014): an analytic fit
// of the split-sum environment BRDF (Karis, "Real Shading in Unreal Engine 4", SIGGRAPH
// 2013): the specular reflectance under uniform light is f0 * x + f90 * y.
vec2 environmentBrdf(float NoV, float roughness) {
    const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
    const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
    vec4 r = roughness * c0 + c1;
    float a004 = min(r.x * r.x, exp2(-9.28 * NoV)) * r.x + r.y;
    return vec2(-1.04, 1.04) * a004 + r.zw;
}
)";

// The key light with a soft shadow map, optional fill lights, the environment, and
// ambient occlusion, through the BRDFs above.
const char* const kShadingLibrary = R"(
uniform vec3 uEye;
uniform int uLightCount;
uniform vec3 uLightToward[MAX_LIGHTS];    // unit, from the surface towards the light
uniform vec3 uLightRadiance[MAX_LIGHTS];  // linear colour times intensity
uniform float uSpecular;                  // dielectrics' reflectance: f0 = 0.16 specular^2
uniform float uMaterialRoughness[16];     // perceptual, by material index
uniform float uMaterialMetallic[16];
uniform float uMaterialSubsurface[16];   // diffuse wrap w (Fd_Wrap)
uniform int uShadowed;                    // the first light casts shadows
uniform sampler2DShadow uShadowMap;
uniform mat4 uLightViewProj;
uniform float uShadowTexel;               // world units per shadow texel
uniform float uShadowBias;                // in shadow-map depth units
uniform float uShadowSoftness;            // penumbra radius, shadow texels

// Jimenez, "Next Generation Post Processing in Call of Duty: Advanced Warfare", SIGGRAPH
// 2014: interleaved gradient noise, a per-pixel rotation that dithers without patterns.
float interleavedGradientNoise(vec2 pixel) {
    return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

float keyLightVisibility(vec3 p, vec3 n) {
#ifdef KEY_LIGHT_UNSHADOWED
    // Drawn only where no caster's shadow reaches (ground_shadow_region.h): there every
    // tap below compares against the cleared map, and the filter returns exactly 1.
    return 1.0;
#else
    if (uShadowed == 0) return 1.0;
    // Normal offset: sample a little off the surface so it does not shadow itself.
    vec4 c = uLightViewProj * vec4(p + n * ((1.5 + 0.5 * uShadowSoftness) * uShadowTexel), 1.0);
    vec3 s = c.xyz * 0.5 + 0.5;
    if (s.z >= 1.0) return 1.0;
    float ref = s.z - uShadowBias;
    vec2 texel = vec2(1.0) / vec2(textureSize(uShadowMap, 0));
    // Percentage-closer filtering over a Poisson disc of radius uShadowSoftness texels,
    // rotated per pixel; each tap is itself a bilinear 2x2 comparison.
    const vec2 kDisc[8] = vec2[8](vec2(-0.613, 0.617), vec2(0.170, -0.040),
                                  vec2(-0.299, -0.792), vec2(0.645, 0.493),
                                  vec2(-0.651, -0.135), vec2(0.421, -0.658),
                                  vec2(0.030, 0.920), vec2(0.980, -0.100));
    float angle = 6.2831853 * interleavedGradientNoise(gl_FragCoord.xy);
    mat2 rotate = mat2(cos(angle), sin(angle), -sin(angle), cos(angle));
    float radius = max(uShadowSoftness, 0.75);
    float sum = 0.0;
    for (int k = 0; k < 8; ++k) {
        vec2 offset = rotate * kDisc[k] * radius * texel;
        sum += texture(uShadowMap, vec3(s.xy + offset, ref));
    }
    return sum / 8.0;
#endif
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

// Outgoing radiance towards the eye from point p of unit normal n, base colour (linear),
// perceptual roughness and metallic in [0, 1]. Metallic workflow: dielectrics reflect
// f0 = 0.16 uSpecular^2 (4% by default) and diffuse the rest; metals reflect their base
// colour and diffuse nothing. Light intensity 1 lights a white diffuse surface facing it
// to 1 (its irradiance is pi).
vec3 shade(vec3 p, vec3 n, vec3 baseColor, float roughness, float metallic, float subsurface) {
    vec3 v = normalize(uEye - p);
    float NoV = max(dot(n, v), 1e-4);
    float r = clamp(roughness, 0.045, 1.0);  // below it the lobe is thinner than a float
    float a = r * r;
    vec3 diffuseColor = (1.0 - metallic) * baseColor;
    vec3 f0 = mix(vec3(0.16 * uSpecular * uSpecular), baseColor, metallic);
    // No reflectance at all (specular = 0, dielectric) means none at grazing angles either.
    float f90 = clamp(50.0 * dot(f0, vec3(0.33)), 0.0, 1.0);
    // Image-based light, split sum: what the specular lobe takes is not diffused.
    vec2 dfg = environmentBrdf(NoV, r);
    vec3 specularAlbedo = f0 * dfg.x + f90 * dfg.y;
    vec3 color = diffuseColor * (1.0 - specularAlbedo) * Fd_Lambert() * environmentIrradiance(n) +
                 specularAlbedo * environmentRadiance(reflect(-v, n), r);
    for (int i = 0; i < uLightCount; ++i) {
        vec3 l = uLightToward[i];
        float NoL = dot(n, l);
        float wrapped = Fd_Wrap(NoL, subsurface);
        if (wrapped <= 0.0) continue;
        // Past the shadow line the surface would shadow itself: the lookup's normal offset
        // leans towards the light as far as the wrap reaches.
        vec3 offsetNormal = subsurface > 0.0 ? normalize(n + subsurface * l) : n;
        float visible = i == 0 ? keyLightVisibility(p, offsetNormal) : 1.0;
        vec3 h = normalize(l + v);
        float NoH = clamp(dot(n, h), 0.0, 1.0);
        float VoH = clamp(dot(v, h), 0.0, 1.0);
        vec3 F = F_Schlick(f0, f90, VoH);
        vec3 specular = NoL > 0.0 ? D_GGX(NoH, a) * V_SmithGGXCorrelated(NoV, NoL, a) * F * NoL
                                  : vec3(0.0);
        vec3 diffuse = diffuseColor * (1.0 - F) * Fd_Lambert() * wrapped;
        color += visible * uLightRadiance[i] * PI * (diffuse + specular);
    }
    return color;
}

// As above with the roughness and metallic of material @p material (an index).
vec3 shadeMaterial(vec3 p, vec3 n, vec3 baseColor, float material) {
    int k = clamp(int(material + 0.5), 0, 15);
    return shade(p, n, baseColor, uMaterialRoughness[k], uMaterialMetallic[k],
                 uMaterialSubsurface[k]);
}
)";

}  // namespace

std::string version() { return kVersion; }
std::string fragment(const std::string& body) { return fragment(body, ""); }
std::string fragment(const std::string& body, const std::string& defines) {
    return version() + defines + kColorLibrary + kEnvironmentLibrary + kBrdfLibrary + kShadingLibrary + body;
}
std::string vertex(const std::string& body) { return version() + kColorLibrary + body; }

// Deferred (triangle_visibility.h): each pixel the mesh covers shaded once. The base
// colour is the vertices' colours (each its value through the ramp) interpolated, as the
// rasteriser interpolated them; the material is the triangle's last vertex's, as a flat
// attribute's (GL's provoking vertex).
std::string meshFragment(int samples) {
    return fragment(cameraRayLibrary() + triangleHitLibrary(samples) + R"(
uniform samplerBuffer uValues;     // material or temperature per vertex, when uHasValues
uniform samplerBuffer uMaterials;  // material index per vertex, when uHasMaterials
uniform int uHasValues;
uniform int uHasMaterials;
layout(location = 0) out vec4 fragColor;

vec3 vertexAlbedo(uint k) {
    float value = uColorMode == 2    ? texelFetch(uPositions, int(k)).y
                  : uHasValues != 0 ? texelFetch(uValues, int(k)).r
                                    : 0.0;
    return albedoFor(value);
}

// Two-sided: an open or inward-wound mesh still shades from the side we see.
vec3 shadeHit(TriangleHit hit) {
    vec3 albedo = hit.weights.x * vertexAlbedo(hit.vertices.x) +
                  hit.weights.y * vertexAlbedo(hit.vertices.y) +
                  hit.weights.z * vertexAlbedo(hit.vertices.z);
    float material = uHasMaterials != 0 ? texelFetch(uMaterials, int(hit.vertices.z)).r : 0.0;
    return shadeMaterial(hit.world, hit.normal, albedo, material);
}

void main() {
    uint ids[SAMPLES];
    int seen[SAMPLES];
    int count = pixelTriangles(ids, seen);
    if (count == 0) discard;
    vec3 color = vec3(0.0);
    int covered = 0, most = 0;
    TriangleHit passes;
    for (int i = 0; i < count; ++i) {
        TriangleHit hit = triangleHit(ids[i]);
        color += float(seen[i]) * shadeHit(hit);
        covered += seen[i];
        if (seen[i] > most) {
            most = seen[i];
            passes = hit;
        }
    }
    fragColor = vec4(color / float(covered), 1.0);
    writePasses(passes.world, passes.normal, vec3(0.0), 1.0);
}
)");
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
std::string groundFragment(bool keyLightShadowed) {
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
    // A matte studio floor: rough, dielectric.
    vec3 color = shade(vWorld, vec3(0.0, 1.0, 0.0), albedo, 0.8, 0.0, 0.0);
    float fade = smoothstep(uFade.x, uFade.y, length(vWorld.xz - uFadeCenter));
    // Premultiplied: over a transparent background the ground fades into alpha.
    float alpha = mix(1.0, uBackgroundAlpha, fade);
    fragColor = vec4(mix(color, uBackground * uBackgroundAlpha, fade), alpha);
    writePasses(vWorld, vec3(0.0, 1.0, 0.0), vec3(0.0), alpha);
}
)",
                    keyLightShadowed ? "" : "#define KEY_LIGHT_UNSHADOWED\n");
}

}  // namespace globular::shaders
