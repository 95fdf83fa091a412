#pragma once
// The [surface] section of a scene: how globules become one continuous surface.
// A plain struct with defaults; describe() binds each TOML key to its field (types,
// ranges, docs with units), validate() checks what one key alone cannot.
//
//   [surface]
//   voxel_size = 0            # world units; 0 = median globule radius / voxels_per_radius
//   kernel = "wyvill"         # wyvill | blinn | murakami (metaball_kernel.h)
//   influence = 2.0           # influence radius as a multiple of the globule radius
//   iso_value = 0.5           # field level of the surface; a lone globule peaks at 1
//   filters = "gaussian:1"    # level-set filter chain, syntax in filter_chain.h
//   droplet_volume = 0.5      # drop disconnected pieces smaller than this (world units^3)
//   subtract_colliders = true # cut the colliders' solids out of the liquid (collider_cut.h)
//   mesh_format = "ply"       # ply | obj
//
// With the defaults (Wyvill, influence 2, iso 0.5) a lone globule's surface lies exactly
// at its radius, and two globules closer than about 2.66 radii merge into one surface.

#include <cstdint>
#include <string>
#include <vector>

#include "filter_chain.h"
#include "globules.h"
#include "metaball_kernel.h"

namespace globular {

class SettingsSection;

struct SurfaceSettings {
    double voxelSize = 0.0;          ///< world units; 0 = medianRadius / voxelsPerRadius
    double voxelsPerRadius = 4.0;    ///< voxels across one globule radius when auto
    std::string kernel = "wyvill";   ///< "wyvill" | "blinn" | "murakami"
    double influence = 2.0;          ///< influence radius / globule radius
    double isoValue = 0.5;           ///< field level of the surface, in (0, 1)
    double blinnSharpness = 4.0;     ///< Blinn's 'a' (exp(-a r^2/R^2)), dimensionless
    double bandWidth = 3.0;          ///< narrow-band half width, voxels
    std::string filters;             ///< level-set filter chain (filter_chain.h)
    double dropletVolume = 0.0;      ///< world units^3; pieces below are removed; 0 keeps all
    bool subtractColliders = true;   ///< cut the colliders' solids out of the liquid
    double adaptivity = 0.0;         ///< mesh adaptivity in [0, 1]; 0 = uniform
    std::string meshFormat = "ply";  ///< "ply" | "obj"
    int64_t framesInFlight = 0;      ///< frames surfaced at once; 0 = auto (threads, memory)
    double memoryLimitGiB = 0.0;     ///< GiB a frame may use; 0 = the memory now available

    /// Binds every [surface] key to its field.
    void describe(SettingsSection& section);
    /// @throw SceneError naming the key when a value or a combination is unusable.
    void validate() const;

    MetaballKernel metaballKernel() const;
    std::vector<FilterStep> filterChain() const;
    /// Distance from a lone globule's centre to its surface, world units.
    double loneSurfaceRadius(double globuleRadius) const;
};

/// The voxel size a frame is surfaced at: voxelSize when set, else the median positive
/// globule radius / voxelsPerRadius (1 / voxelsPerRadius when no globule has a radius).
/// The median, not the mean, so a few emitted giants do not coarsen the whole frame.
double resolveVoxelSize(const SurfaceSettings& settings, const Globules& globules);

}  // namespace globular
