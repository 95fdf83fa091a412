#pragma once
// Internal to render/: the GLSL sources of every pass, assembled from a shared shading
// library so spheres, meshes and the ground are lit identically.

#include <string>

namespace globular::shaders {

inline constexpr int kMaxLights = 8;

/// "#version 420 core" and the defines every source starts with.
std::string version();
/// @p body after the version, the colour ramp and the lighting functions (shade()).
std::string fragment(const std::string& body);
/// As above with @p defines ("#define NAME\n" lines) before the libraries.
std::string fragment(const std::string& body, const std::string& defines);
/// @p body after the version and the colour ramp (albedoFor()).
std::string vertex(const std::string& body);

/// A mesh's shading, deferred (triangle_visibility.h). @param samples of the frame target.
std::string meshFragment(int samples);
std::string depthOnlyFragment();
std::string groundVertex();
/// @param keyLightShadowed false: the key light's shadow filter left out (visibility 1),
/// for the ground outside the casters' shadow region (ground_shadow_region.h).
std::string groundFragment(bool keyLightShadowed);

// triangle_shaders.cpp: a mesh's deferred shading (triangle_visibility.h)
/// Positions (attribute 0) through uViewProj: a mesh's faces in the camera's view or, with
/// the light's matrix, in the shadow map.
std::string positionVertex();
/// 1 + the triangle's index (gl_PrimitiveID) at location 1, the id buffer.
std::string triangleIdFragment();
/// A rectangle of the screen (uniform uRectangle, NDC) as a four-vertex triangle strip.
std::string screenRectangleVertex();
/// pixelTriangles(): the triangles the id buffer holds at the pixel, and triangleHit():
/// one of them interpolated where the pixel's eye ray meets it. Needs cameraRayLibrary()
/// and uEye before it.
/// @param samples of the id buffer it reads (1: not multisampled).
std::string triangleHitLibrary(int samples);

// sphere_shaders.cpp
/// cameraRay(windowPosition) through uCamForward/Right/Up and uViewport, and
/// sphereHitDistance(): the eye ray and its meeting with a sphere.
std::string cameraRayLibrary();
/// drawable(centre, radius), kNowhere and axisHalfExtent(): sizing a globule's sprite
/// to its sphere's exact screen extent.
std::string globuleSpriteLibrary();
std::string spherePointVertex();
std::string sphereQuadVertex();
std::string sphereVisibilityFragment();
std::string tileVertex();
/// @param samples of the id buffer it reads (1: not multisampled).
std::string sphereShadeFragment(int samples);
std::string sphereShadowPointVertex();
std::string sphereShadowQuadVertex();
/// @param points sprites (the disc from gl_PointCoord) or squares (from the vertex shader).
std::string sphereShadowFragment(bool points);

}  // namespace globular::shaders
