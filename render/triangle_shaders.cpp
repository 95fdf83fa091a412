// GLSL of a triangle mesh's deferred shading (triangle_visibility.h).
#include <string>

#include "shaders.h"

namespace globular::shaders {

std::string positionVertex() {
    return version() + R"(
layout(location = 0) in vec3 aPosition;
uniform mat4 uViewProj;
void main() { gl_Position = uViewProj * vec4(aPosition, 1.0); }
)";
}

std::string triangleIdFragment() {
    return version() + R"(
layout(location = 1) out uint fragId;
void main() { fragId = uint(gl_PrimitiveID) + 1u; }
)";
}

std::string screenRectangleVertex() {
    return version() + R"(
uniform vec4 uRectangle;  // x0, y0, x1, y1 in normalised device coordinates
void main() {
    gl_Position = vec4((gl_VertexID & 1) != 0 ? uRectangle.z : uRectangle.x,
                       gl_VertexID >= 2 ? uRectangle.w : uRectangle.y, 0.0, 1.0);
}
)";
}

std::string triangleHitLibrary(int samples) {
    return "#define SAMPLES " + std::to_string(samples) + "\n" + R"(
// The stencil test (samples the mesh covers) before the shader: the rest are skipped.
layout(early_fragment_tests) in;
#if SAMPLES > 1
uniform usampler2DMS uIds;  // 1 + the triangle seen at each sample, 0 for none
#else
uniform usampler2D uIds;
#endif
uniform usamplerBuffer uTriangles;  // the vertex indices, a triangle per texel
uniform samplerBuffer uPositions;
uniform samplerBuffer uNormals;     // read when uHasNormals
uniform int uHasNormals;

struct TriangleHit {
    uvec3 vertices;  // the triangle's
    vec3 weights;    // the point's barycentric coordinates, one per vertex
    vec3 world;      // the point
    vec3 normal;     // unit, facing the eye: interpolated, or the face's without normals
    vec3 dir;        // the pixel centre's eye ray, unit
};

// The distinct triangles the pixel's samples saw (@p ids, 1 + their index) and how many
// samples saw each; returns how many there are, 0 for none. Limits the pixel's writes to
// its covered samples. A shader shades each and weighs it by its samples, as the
// multisampled rasteriser would have, once per triangle where most pixels of a fine mesh
// see two or three.
int pixelTriangles(out uint ids[SAMPLES], out int seen[SAMPLES]) {
    ivec2 p = ivec2(gl_FragCoord.xy);
    int count = 0;
#if SAMPLES > 1
    int mask = 0;
    for (int s = 0; s < SAMPLES; ++s) {
        uint id = texelFetch(uIds, p, s).r;
        if (id == 0u) continue;
        mask |= 1 << s;
        int k = 0;
        while (k < count && ids[k] != id) ++k;
        if (k == count) {
            ids[count] = id;
            seen[count] = 0;
            ++count;
        }
        ++seen[k];
    }
    gl_SampleMask[0] = mask;
#else
    ids[0] = texelFetch(uIds, p, 0).r;
    seen[0] = 1;
    count = ids[0] != 0u ? 1 : 0;
#endif
    return count;
}

// Which of the pixel's @p count triangles the most of its samples saw (the first of
// those tied).
int mostSeen(int seen[SAMPLES], int count) {
    int best = 0;
    for (int i = 1; i < count; ++i) {
        if (seen[i] > seen[best]) best = i;
    }
    return best;
}

// Triangle @p id (1 + its index) where the pixel centre's eye ray meets its plane (Moller
// and Trumbore), kept within the triangle. That is what the rasteriser interpolates, but
// for the clamp: it keeps a sliver seen edge-on, whose plane the ray meets far away, from
// being shaded somewhere else (GLSL's centroid qualifier exists for the same reason).
TriangleHit triangleHit(uint id) {
    TriangleHit hit;
    uvec3 k = texelFetch(uTriangles, int(id - 1u)).xyz;
    vec3 a = texelFetch(uPositions, int(k.x)).xyz;
    vec3 e1 = texelFetch(uPositions, int(k.y)).xyz - a;
    vec3 e2 = texelFetch(uPositions, int(k.z)).xyz - a;
    vec3 dir = cameraRay(gl_FragCoord.xy);
    vec3 across = cross(dir, e2);
    float det = dot(e1, across);
    vec3 fromA = uEye - a;
    vec2 uv = abs(det) > 1e-30 ? vec2(dot(fromA, across), dot(dir, cross(fromA, e1))) / det
                               : vec2(1.0 / 3.0);  // seen exactly edge-on: its centre
    uv = max(uv, vec2(0.0));
    uv /= max(uv.x + uv.y, 1.0);
    hit.vertices = k;
    hit.weights = vec3(1.0 - uv.x - uv.y, uv);
    hit.world = a + uv.x * e1 + uv.y * e2;
    hit.dir = dir;
    vec3 interpolated = vec3(0.0);
    if (uHasNormals != 0) {
        interpolated = hit.weights.x * texelFetch(uNormals, int(k.x)).xyz +
                       hit.weights.y * texelFetch(uNormals, int(k.y)).xyz +
                       hit.weights.z * texelFetch(uNormals, int(k.z)).xyz;
    }
    vec3 n = dot(interpolated, interpolated) > 0.25 ? normalize(interpolated)
                                                    : normalize(cross(e1, e2));
    hit.normal = dot(n, dir) > 0.0 ? -n : n;
    return hit;
}
)";
}

}  // namespace globular::shaders
