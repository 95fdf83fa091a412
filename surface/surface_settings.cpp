#include "surface_settings.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "errors.h"
#include "settings_schema.h"

namespace globular {

namespace {

[[noreturn]] void badKey(const std::string& key, const std::string& problem) {
    throw SceneError("[surface] key '" + key + "': " + problem);
}

std::string text(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

}  // namespace

void SurfaceSettings::describe(SettingsSection& s) {
    s.number("voxel_size", voxelSize, NumberRange::nonNegative(),
             "edge of one voxel, world units; 0 = median globule radius / voxels_per_radius")
        .number("voxels_per_radius", voxelsPerRadius, NumberRange::between(0.5, 64),
                "voxels across one globule radius when voxel_size = 0 (dimensionless)")
        .choice("kernel", kernel, kernelNames(),
                "metaball kernel: wyvill (soft objects), blinn (truncated exponential), "
                "murakami ((1 - r^2/R^2)^2)")
        .number("influence", influence, {0.0, 16.0, true, false},
                "influence radius R of a globule as a multiple of its radius (dimensionless)")
        .number("iso_value", isoValue, {0.0, 1.0, true, true},
                "field level of the surface; a lone globule's field is 1 at its centre")
        .number("blinn_sharpness", blinnSharpness, {0.0, 50.0, true, false},
                "Blinn kernel exponent a in exp(-a r^2/R^2) (dimensionless)")
        .number("band_width", bandWidth, NumberRange::between(2, 16),
                "narrow-band half width of the level set, voxels")
        .text("filters", filters,
              "level-set filters applied in order, e.g. \"gaussian:1, dilate:1, erode:1\" "
              "(gaussian:W voxels, mean_curvature:N, laplacian:N iterations, dilate:D, "
              "erode:D voxels)")
        .number("droplet_volume", dropletVolume, NumberRange::nonNegative(),
                "disconnected pieces of surface enclosing less than this are removed, "
                "world units^3; 0 keeps all")
        .flag("subtract_colliders", subtractColliders,
              "cut the colliders' solids out of the liquid, so its surface never shows "
              "through a wall")
        .number("adaptivity", adaptivity, NumberRange::between(0, 1),
                "mesh adaptivity: 0 = uniform triangles, 1 = fewest triangles on flat parts")
        .choice("mesh_format", meshFormat, {"ply", "obj"},
                "mesh file format: ply (binary, with normals) or obj (text)")
        .integer("frames_in_flight", framesInFlight, 0, 1024,
                 "frames surfaced at the same time; 0 = auto (threads and memory allow)")
        .number("memory_limit_gib", memoryLimitGiB, NumberRange::nonNegative(),
                "memory the stage may use, GiB; 0 = the memory available when it starts");
}

void SurfaceSettings::validate() const {
    // Single-key ranges again: library callers fill the struct without describe().
    if (!(voxelSize >= 0) || !std::isfinite(voxelSize)) badKey("voxel_size", "must be >= 0");
    if (!(voxelsPerRadius >= 0.5 && voxelsPerRadius <= 64)) {
        badKey("voxels_per_radius", "must be in [0.5, 64]");
    }
    const auto& names = kernelNames();
    if (std::find(names.begin(), names.end(), kernel) == names.end()) {
        badKey("kernel", "'" + kernel + "' must be one of wyvill, blinn, murakami");
    }
    if (!(influence > 0 && influence <= 16)) badKey("influence", "must be in (0, 16]");
    if (!(isoValue > 0 && isoValue < 1)) badKey("iso_value", "must be in (0, 1)");
    if (!(blinnSharpness > 0 && blinnSharpness <= 50)) {
        badKey("blinn_sharpness", "must be in (0, 50]");
    }
    if (!(bandWidth >= 2 && bandWidth <= 16)) badKey("band_width", "must be in [2, 16]");
    if (!(dropletVolume >= 0) || !std::isfinite(dropletVolume)) {
        badKey("droplet_volume", "must be >= 0");
    }
    if (!(adaptivity >= 0 && adaptivity <= 1)) badKey("adaptivity", "must be in [0, 1]");
    if (meshFormat != "ply" && meshFormat != "obj") {
        badKey("mesh_format", "'" + meshFormat + "' must be ply or obj");
    }
    if (framesInFlight < 0) badKey("frames_in_flight", "must be >= 0");
    if (!(memoryLimitGiB >= 0) || !std::isfinite(memoryLimitGiB)) {
        badKey("memory_limit_gib", "must be >= 0");
    }

    std::vector<FilterStep> chain;
    try {
        chain = parseFilterChain(filters);
    } catch (const SceneError& e) {
        badKey("filters", "\"" + filters + "\": " + e.what());
    }
    // The filters read a stencil of neighbours; beyond the narrow band they would read the
    // clamped background and flatten the surface instead of smoothing it.
    for (const auto& step : chain) {
        if (step.kind == FilterKind::Gaussian && step.amount > bandWidth) {
            badKey("filters", "gaussian:" + text(step.amount) + " reaches " + text(step.amount) +
                                  " voxels but band_width is " + text(bandWidth) +
                                  "; raise band_width or narrow the filter");
        }
    }
}

MetaballKernel SurfaceSettings::metaballKernel() const {
    return {kernelFromName(kernel), float(blinnSharpness)};
}

std::vector<FilterStep> SurfaceSettings::filterChain() const { return parseFilterChain(filters); }

double SurfaceSettings::loneSurfaceRadius(double globuleRadius) const {
    return globuleRadius * influence * metaballKernel().surfaceFraction(isoValue);
}

double resolveVoxelSize(const SurfaceSettings& settings, const Globules& globules) {
    if (settings.voxelSize > 0) return settings.voxelSize;
    std::vector<float> radii;
    radii.reserve(globules.size());
    for (float r : globules.radius) {
        if (r > 0 && std::isfinite(r)) radii.push_back(r);
    }
    if (radii.empty()) return 1.0 / settings.voxelsPerRadius;
    auto middle = radii.begin() + radii.size() / 2;
    std::nth_element(radii.begin(), middle, radii.end());
    return double(*middle) / settings.voxelsPerRadius;
}

}  // namespace globular
