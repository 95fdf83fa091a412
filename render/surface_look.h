#pragma once
// How a material's surface reflects light (shaders.cpp's shade()): its perceptual
// roughness, metallic and subsurface wrap, from the scene's [material] / [[material]] sections.

#include "material.h"

namespace globular {

struct SurfaceLook {
    double roughness = 0.35;  ///< perceptual roughness, 0 = mirror, 1 = fully rough
    double metallic = 0;      ///< 0 = dielectric, 1 = metal (reflects its base colour)
    /// Wrap w of the diffuse light past the shadow line (shaders.cpp's Fd_Wrap), the
    /// soft look of light scattered under the surface; 0 = Lambert.
    double subsurface = 0;
};

inline SurfaceLook surfaceLook(const MaterialSettings& material) {
    return {material.roughness, material.metallic, material.subsurface};
}

}  // namespace globular
