#pragma once
// Per-frame globule caches. The VDB cache is an OpenVDB PointDataGrid named "globules"
// with attributes P, v (Vec3f), pscale (radius, float), id (int32), mass (float) and
// material (int32): the names Houdini reads, and temperature (float) when the globules
// carry one. The PLY cache (binary little endian, vertex properties x y z vx vy vz radius
// id mass material, then temperature when carried) is what Blender imports (the add-on
// in blender/). Both are written atomically
// (atomic_file.h).
// OpenVDB headers stay inside globule_cache.cpp: this header is cheap to include.

#include <filesystem>

#include "globules.h"

namespace globular {

/// Frame metadata stored beside the globules.
struct CacheInfo {
    int frame = 0;
    double time = 0;  ///< seconds since the start of the simulation
};

/// Positions are stored at full float precision in a point grid whose voxel is twice the
/// largest radius; CacheInfo is grid metadata "frame" (int) and "time" (double).
/// @throw IoError naming @p path when it cannot be written, or when a position or a
///        temperature is not finite or a mass not positive and finite (then nothing is
///        written).
void writeGlobuleVdb(const std::filesystem::path& path, const Globules& globules,
                     const CacheInfo& info);
/// Reads a cache written by writeGlobuleVdb (or any PointDataGrid "globules" with P;
/// v, pscale, id, mass optional: defaults 0, 1, index, 1 (caches written before mass was
/// stored read as mass 1); temperature read when present, else left empty; a non-finite
/// temperature or a mass that is not positive and finite is an error). Globules come back
/// ordered by id. The file is checked before OpenVDB parses it (which would abort on a
/// truncated file): its layout always, and for files written by writeGlobuleVdb a
/// checksum kept in the file-level metadata "globular_checksum".
/// @throw IoError naming @p path when it is missing, truncated or corrupt.
Globules readGlobuleVdb(const std::filesystem::path& path, CacheInfo* info = nullptr);

/// Binary PLY: x y z vx vy vz radius (float) id (int) mass (float) material (int),
/// temperature (float) when the globules carry one.
/// @throw IoError naming @p path, also for a non-finite temperature or a mass that is
///        not positive and finite.
void writeGlobulePly(const std::filesystem::path& path, const Globules& globules);
/// Reads a PLY point cloud (ascii, binary little or big endian; ply_reader.h). Vertex
/// properties x y z are required; vx vy vz radius id mass optional (defaults: 0,
/// @p defaultRadius, index, 1); temperature read when present, else left empty.
/// Material is not read (a scene assigns it).
/// @throw IoError naming @p path and what is wrong, also for a globule with a
///        non-finite position, velocity or temperature or a radius or mass that is not
///        positive and finite.
Globules readGlobulePly(const std::filesystem::path& path, float defaultRadius = 1.0f);

}  // namespace globular
