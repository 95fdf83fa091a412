#pragma once
// Internal to render/: the GLSL of the liquid look (fluid_pass.h, liquid_mesh_pass.h):
// liquidShade(), Fresnel reflection of the environment plus transmission of what lies
// behind, refracted and absorbed (Beer-Lambert), and the passes of the screen-space
// fluid.

#include <string>

namespace globular::shaders {

/// A full-screen triangle (no vertex arrays needed: three vertices from gl_VertexID).
std::string fullScreenVertex();

/// One point sprite per globule, sized to its sphere's exact screen extent, carrying the
/// absorption of its material; materials drawn opaque are left out.
std::string fluidPointVertex();
/// The sphere's front: its view depth (distance along the view axis), depth-tested.
std::string fluidDepthFragment();
/// Additive: the chord of each sphere along the eye ray, and that chord times its
/// material's absorption (optical depth, rgb).
std::string fluidThicknessFragment();
/// One separable step of the bilateral filter of the view depth.
std::string fluidSmoothFragment();
/// Normals from the smoothed depth, thickness, and the liquid's shading.
std::string fluidCompositeFragment();

std::string liquidMeshVertex();
/// Additive: minus the eye distance of front faces, plus that of back faces, so the sum
/// over a closed mesh is the length of the eye ray inside it.
std::string liquidMeshThicknessFragment();
/// Deferred (triangle_visibility.h): each pixel the front faces cover, shaded once.
/// @param samples of the frame target.
std::string liquidMeshFragment(int samples);

}  // namespace globular::shaders
