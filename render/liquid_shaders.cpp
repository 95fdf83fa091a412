// GLSL of the liquid look (liquid_shaders.h).
#include "liquid_shaders.h"

#include "shaders.h"

namespace globular::shaders {

namespace {

// The liquid's look at a point of its front surface.
const char* const kLiquid = R"(
uniform sampler2D uBehind;  // what lies behind the liquid: the frame drawn so far, resolved
                            // (linear, premultiplied), unit 1
uniform float uIor;         // index of refraction
uniform int uGroundDrawn;   // the ground plane is in uBehind
uniform float uGroundHeight;
uniform mat4 uBehindViewProj;

// What uBehind shows at the pixel of a world point.
vec4 behindAt(vec3 world) {
    vec4 c = uBehindViewProj * vec4(world, 1.0);
    vec2 uv = c.w > 0.0 ? c.xy / c.w * 0.5 + 0.5 : vec2(0.5);
    return textureLod(uBehind, clamp(uv, vec2(0.0), vec2(1.0)), 0.0);
}

// Schlick's approximation of the Fresnel reflectance of a dielectric of index ior.
float schlick(float cosine, float ior) {
    float f0 = (ior - 1.0) / (ior + 1.0);
    f0 *= f0;
    return f0 + (1.0 - f0) * pow(1.0 - clamp(cosine, 0.0, 1.0), 5.0);
}

// The liquid seen along `dir` (unit, from the eye) where the ray enters it at `p`, normal
// `n` (unit, towards the eye); `depth`: the eye ray's length inside it; `sigma`:
// absorption per world unit; `keyVisibility`: the key light's there, its glint's shadow
// (keyLightVisibility). Returns premultiplied colour and coverage.
vec4 liquidShade(vec3 p, vec3 n, vec3 dir, float depth, vec3 sigma, float keyVisibility) {
    float cosine = clamp(-dot(dir, n), 0.0, 1.0);
    float fresnel = schlick(cosine, uIor);
    vec3 r = refract(dir, n, 1.0 / uIor);
    float path = max(depth, 0.0);
    vec3 far;
    float toGround = uGroundDrawn != 0 && r.y < 0.0 ? max((uGroundHeight - p.y) / r.y, 0.0) : -1.0;
    if (toGround >= 0.0 && toGround <= path) {
        // The refracted ray meets the floor inside the liquid: exact for the ground.
        path = toGround;
        far = p + r * toGround;
    } else {
        // It leaves through the back. The back's normal is taken as the front's mirrored
        // across the plane facing the eye (exact for a slab, a sphere or a cylinder seen
        // side-on), and refracts the ray again: a slab shifts what lies behind, a drop or
        // a stream bends it as a lens does. Then on to the ground, or what shows there.
        vec3 exit = p + r * path;
        vec3 back = n - 2.0 * dot(n, dir) * dir;  // outward, facing away from the eye
        vec3 leaving = refract(r, -back, uIor);
        if (dot(leaving, leaving) == 0.0) leaving = reflect(r, -back);  // total internal reflection
        float beyond = uGroundDrawn != 0 && leaving.y < 0.0 ? (uGroundHeight - exit.y) / leaving.y : -1.0;
        far = exit + leaving * (beyond > 0.0 ? beyond : max(4.0 * path, 1e-3));
    }
    vec4 behind = behindAt(far);
    vec3 transmittance = exp(-sigma * path);
    vec3 color = (1.0 - fresnel) * transmittance * behind.rgb +
                 fresnel * environmentRadiance(reflect(dir, n), 0.02);
    // Glints of the lights: a sharp normalised Blinn-Phong lobe weighted by Fresnel.
    const float kShininess = 600.0;
    for (int i = 0; i < uLightCount; ++i) {
        float ndl = dot(n, uLightToward[i]);
        if (ndl <= 0.0) continue;
        vec3 h = normalize(uLightToward[i] - dir);
        float lobe = (kShininess + 8.0) / (8.0 * PI_LIQUID) * pow(max(dot(n, h), 0.0), kShininess);
        float visible = i == 0 ? keyVisibility : 1.0;
        color += visible * uLightRadiance[i] * schlick(dot(h, -dir), uIor) * lobe * ndl;
    }
    float through = (1.0 - fresnel) * dot(transmittance, vec3(1.0 / 3.0));
    return vec4(color, 1.0 - through * (1.0 - behind.a));
}
)";

std::string liquidFragment(const std::string& body) {
    return fragment(cameraRayLibrary() +
                    "const float PI_LIQUID = 3.14159265358979;\n" + kLiquid + body);
}

}  // namespace

std::string fullScreenVertex() {
    return version() + R"(
void main() {
    vec2 corner = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
    gl_Position = vec4(corner, 0.0, 1.0);
}
)";
}

std::string fluidPointVertex() {
    return version() + globuleSpriteLibrary() + R"(
layout(location = 1) in float aX;
layout(location = 2) in float aY;
layout(location = 3) in float aZ;
layout(location = 4) in float aRadius;
layout(location = 5) in uint aMaterial;
layout(location = 6) in float aVx;  // velocity, world units/s (0 without the motion pass)
layout(location = 7) in float aVy;
layout(location = 8) in float aVz;
uniform mat4 uView;
uniform mat4 uViewProj;
uniform vec2 uFocalPixels;  // pixels per unit of x/depth and y/depth
uniform float uNear;
uniform float uMaxSprite;   // pixels
uniform vec3 uSigma[16];    // absorption per world unit by material
uniform int uLiquid[16];    // 0: the material is drawn opaque, not here
flat out vec3 vCenter;
flat out float vRadius;
flat out vec3 vSigma;
flat out vec3 vVelocity;


void main() {
    vec3 c = vec3(aX, aY, aZ);
    int material = int(min(aMaterial, 15u));
    vCenter = c;
    vRadius = aRadius;
    vSigma = uSigma[material];
    vVelocity = vec3(aVx, aVy, aVz);
    vec3 v = (uView * vec4(c, 1.0)).xyz;
    float depth = -v.z;
    float size = 1e9;
    if (uLiquid[material] != 0 && drawable(c, aRadius) && depth - aRadius > uNear) {
        size = 2.0 * max(axisHalfExtent(v.x, depth, aRadius) * uFocalPixels.x,
                         axisHalfExtent(v.y, depth, aRadius) * uFocalPixels.y) + 1.0;
    }
    gl_Position = size <= uMaxSprite ? uViewProj * vec4(c, 1.0) : kNowhere;
    gl_PointSize = min(size, uMaxSprite);
}
)";
}

std::string fluidDepthFragment() {
    return version() + cameraRayLibrary() + R"(
flat in vec3 vCenter;
flat in float vRadius;
flat in vec3 vSigma;
flat in vec3 vVelocity;
uniform vec3 uEye;
uniform mat4 uViewProj;
uniform float uSide;  // -1: the spheres' fronts (nearest kept); +1: their backs (farthest)
layout(location = 0) out float fragViewDepth;
layout(location = 1) out vec4 fragVelocity;  // the fronts' pass only
void main() {
    vec3 dir = cameraRay(gl_FragCoord.xy);
    vec3 toCenter = vCenter - uEye;
    float along = dot(toCenter, dir);
    vec3 miss = toCenter - along * dir;
    float h2 = vRadius * vRadius - dot(miss, miss);
    if (h2 <= 0.0) discard;
    float t = along + uSide * sqrt(h2);
    vec4 clip = uViewProj * vec4(uEye + t * dir, 1.0);
    gl_FragDepth = 0.5 + 0.5 * clip.z / clip.w;
    fragViewDepth = t * dot(dir, uCamForward);
    fragVelocity = vec4(vVelocity, 1.0);
}
)";
}

std::string fluidThicknessFragment() {
    return version() + cameraRayLibrary() + R"(
flat in vec3 vCenter;
flat in float vRadius;
flat in vec3 vSigma;
uniform vec3 uEye;
layout(location = 0) out vec4 fragDepths;  // optical depth rgb, thickness
void main() {
    vec3 dir = cameraRay(gl_FragCoord.xy);
    vec3 toCenter = vCenter - uEye;
    vec3 miss = toCenter - dot(toCenter, dir) * dir;
    float h2 = vRadius * vRadius - dot(miss, miss);
    if (h2 <= 0.0) discard;
    float chord = 2.0 * sqrt(h2);
    fragDepths = vec4(vSigma * chord, chord);
}
)";
}

// Bilateral: a Gaussian in screen space whose width is a world radius at the pixel's
// depth, times a Gaussian of the depth difference, so separate sheets do not blend and
// silhouettes stay where they are (empty pixels are left out).
std::string fluidSmoothFragment() {
    return version() + R"(
uniform sampler2D uDepth;     // view depth; 0 = no liquid
uniform ivec2 uAxis;          // (1, 0) or (0, 1)
uniform float uWorldRadius;   // the filter's reach, world units
uniform float uFocal;         // pixels per unit of x/depth
uniform float uMaxPixels;
layout(location = 0) out float fragViewDepth;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(uDepth, 0);
    float z = texelFetch(uDepth, p, 0).r;
    fragViewDepth = z;
    if (z <= 0.0) return;
    float reach = min(uWorldRadius * uFocal / z, uMaxPixels);
    if (reach < 1.0) return;
    const float kTaps = 24.0;  // per side at most: beyond, the taps spread out
    float stride = max(reach / kTaps, 1.0);
    int n = int(ceil(reach / stride));
    float spatial = -0.5 / (0.25 * reach * reach);
    float range = -0.5 / (4.0 * uWorldRadius * uWorldRadius);  // sigma: twice the reach
    float sum = 0.0, weights = 0.0;
    for (int i = -n; i <= n; ++i) {
        float x = round(float(i) * stride);
        ivec2 q = p + int(x) * uAxis;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
        float zi = texelFetch(uDepth, q, 0).r;
        if (zi <= 0.0) continue;
        float dz = zi - z;
        float w = exp(spatial * x * x + range * dz * dz);
        sum += w * zi;
        weights += w;
    }
    fragViewDepth = sum / weights;
}
)";
}

std::string fluidCompositeFragment() {
    return liquidFragment(R"(
uniform sampler2D uSmoothed;   // view depth, unit 2
uniform sampler2D uDepths;     // optical depth rgb and chord sum, unit 3 (coarser)
uniform sampler2D uFront;      // view depth of the nearest front, unit 4
uniform sampler2D uBack;       // view depth of the farthest back, unit 5
uniform sampler2D uVelocity;   // the nearest sphere's velocity, unit 6
uniform float uEdgeThickness;  // world units
uniform mat4 uViewProj;
layout(location = 0) out vec4 fragColor;

vec3 worldAt(ivec2 q, float z) {
    vec3 d = cameraRay(vec2(q) + 0.5);
    return uEye + d * (z / dot(d, uCamForward));
}

// The surface's tangent along `step`: from the neighbours on both sides, or from the
// one nearer in depth at a silhouette, so the normal does not bend there.
vec3 tangent(ivec2 p, ivec2 step, vec3 at, float z, vec3 fallback) {
    ivec2 size = textureSize(uSmoothed, 0);
    ivec2 a = p + step, b = p - step;
    float za = all(greaterThanEqual(a, ivec2(0))) && all(lessThan(a, size)) ? texelFetch(uSmoothed, a, 0).r : 0.0;
    float zb = all(greaterThanEqual(b, ivec2(0))) && all(lessThan(b, size)) ? texelFetch(uSmoothed, b, 0).r : 0.0;
    float da = abs(za - z), db = abs(z - zb);
    // Central unless a side jumps by more than two globule radii (another sheet, or
    // nothing): a choice by the sides' ratio alternated from pixel to pixel on a slope.
    float jump = 2.0 * uEdgeThickness;
    bool okA = za > 0.0 && da < jump, okB = zb > 0.0 && db < jump;
    if (okA && okB) return 0.5 * (worldAt(a, za) - worldAt(b, zb));
    if (okA != okB) return okA ? worldAt(a, za) - at : at - worldAt(b, zb);
    bool useA = za > 0.0 && (zb <= 0.0 || da <= db);
    if (useA) return worldAt(a, za) - at;
    if (zb > 0.0) return at - worldAt(b, zb);
    return fallback;
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float z = texelFetch(uSmoothed, p, 0).r;
    if (z <= 0.0) discard;
    vec3 at = worldAt(p, z);
    vec3 dx = tangent(p, ivec2(2, 0), at, z, uCamRight);
    vec3 dy = tangent(p, ivec2(0, 2), at, z, uCamUp);
    vec3 n = normalize(cross(dx, dy));
    vec3 dir = normalize(at - uEye);
    if (dot(n, dir) > 0.0) n = -n;
    // Thickness varies sphere by sphere; a small blur (five bilinear taps of the
    // half-resolution buffer, about 6 pixels across) leaves its large-scale variation.
    vec2 uv = gl_FragCoord.xy / uViewport, texel = 1.5 / vec2(textureSize(uDepths, 0));
    vec4 depths = 0.4 * textureLod(uDepths, uv, 0.0) +
                  0.15 * (textureLod(uDepths, uv + vec2(texel.x, 0.0), 0.0) +
                          textureLod(uDepths, uv - vec2(texel.x, 0.0), 0.0) +
                          textureLod(uDepths, uv + vec2(0.0, texel.y), 0.0) +
                          textureLod(uDepths, uv - vec2(0.0, texel.y), 0.0));
    // The absorption: the chord-weighted mean of the globules' materials. The depth: from
    // the nearest front to the farthest back (summed chords would count every overlap of
    // the globules, several times the liquid's real depth).
    vec3 sigma = depths.a > 0.0 ? depths.rgb / depths.a : vec3(0.0);
    float span = max(texelFetch(uBack, p, 0).r - texelFetch(uFront, p, 0).r, 0.0);
    float thickness = span / dot(dir, uCamForward);
    // Where the liquid thins out to its silhouette (less than uEdgeThickness deep), it
    // fades into what lies behind: the smoothed depth is least reliable there, and the
    // edge is soft instead of stair-stepped.
    float edge = smoothstep(0.0, uEdgeThickness, depths.a);  // the blurred chords: soft
    fragColor = mix(textureLod(uBehind, uv, 0.0),
                    liquidShade(at, n, dir, thickness, sigma, keyLightVisibility(at, n)), edge);
    vec4 clip = uViewProj * vec4(at, 1.0);
    gl_FragDepth = 0.5 + 0.5 * clip.z / clip.w;
    writePasses(at, n, texelFetch(uVelocity, p, 0).xyz, 1.0);
}
)");
}

std::string liquidMeshVertex() {
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

std::string liquidMeshThicknessFragment() {
    return version() + R"(
in vec3 vWorld;
uniform vec3 uEye;
layout(location = 0) out float fragSignedDistance;
void main() {
    float d = length(vWorld - uEye);
    fragSignedDistance = gl_FrontFacing ? -d : d;
}
)";
}

std::string liquidMeshFragment(int samples) {
    return liquidFragment(triangleHitLibrary(samples) + R"(
uniform sampler2D uThickness;  // unit 2: the eye ray's length inside the mesh, per pixel
uniform vec3 uMeshSigma;       // absorption per world unit
layout(location = 0) out vec4 fragColor;
void main() {
    uint ids[SAMPLES];
    int seen[SAMPLES];
    int count = pixelTriangles(ids, seen);
    if (count == 0) discard;
    float depth = texelFetch(uThickness, ivec2(gl_FragCoord.xy), 0).r;
    // The triangle most samples saw: the compositing passes show it, and the key light's
    // shadow on the glints is looked up there, once for all the pixel's triangles. Its
    // filter (eight bilinear taps) was a third of this pass, run for each triangle as
    // often as the most any pixel of a block sees; the glints are a few pixels wide, and
    // the pour's frames came out byte-identical (docs/performance.md, twentieth pass).
    TriangleHit passes = triangleHit(ids[mostSeen(seen, count)]);
    float keyVisibility = keyLightVisibility(passes.world, passes.normal);
    vec4 color = vec4(0.0);
    int covered = 0;
    for (int i = 0; i < count; ++i) {
        TriangleHit hit = triangleHit(ids[i]);
        color += float(seen[i]) *
                 liquidShade(hit.world, hit.normal, hit.dir, depth, uMeshSigma, keyVisibility);
        covered += seen[i];
    }
    fragColor = color / float(covered);
    writePasses(passes.world, passes.normal, vec3(0.0), 1.0);
}
)");
}

}  // namespace globular::shaders
