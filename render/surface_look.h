#pragma once
// How a material's surface reflects light (shaders.cpp's shade()): its perceptual
// roughness and metallic, from the scene's [material] / [[material]] sections.

#include "material.h"

namespace globular {

struct SurfaceLook {
    double roughness = 0.35;  ///< perceptual roughness, 0 = mirror, 1 = fully rough
    double metallic = 0;      ///< 0 = dielectric, 1 = metal (reflects its base colour)
};

inline SurfaceLook surfaceLook(const MaterialSettings& material) {
    return {material.roughness, material.metallic};
}

}  // namespace globular
