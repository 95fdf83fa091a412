#pragma once
// Scene statistics of one frame: what stats.csv records, and what the paper's outcomes
// (spill, clumping, explosion) are measured with. Rows can be read back to compare runs.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "globules.h"
#include "vec3.h"

namespace globular {

struct FrameStats {
    int frame = 0;
    double time = 0;                    ///< seconds
    std::size_t count = 0;              ///< globules
    double kineticEnergy = 0;           ///< sum of 0.5 m |v|^2
    double maxSpeed = 0;                ///< largest |v|, world units per second
    Vec3 centroid;                      ///< unweighted mean position
    double maxHeight = 0;               ///< largest y of a globule centre
    double horizontalSpread = 0;        ///< RMS distance in x-z from the centroid's x-z
    std::size_t clusterCount = 0;       ///< connected groups of overlapping globules
    double largestClusterFraction = 0;  ///< globules in the largest group / count
};

/// @brief Measures @p globules. Two globules belong to one cluster when they overlap
/// (centre distance < r_i + r_j), transitively. Horizontal spread is
/// sqrt(mean((x - cx)^2 + (z - cz)^2)): how far a pile has spilled over the ground.
/// An empty set gives count 0, no clusters and zeros elsewhere. Non-finite positions
/// give non-finite moments and count as clusters of their own; the result does not
/// depend on the thread count.
FrameStats computeFrameStats(const Globules& globules, int frame, double time);

/// The CSV header line (no newline): frame,time,count,kinetic_energy,max_speed,
/// centroid_x,centroid_y,centroid_z,max_height,horizontal_spread,cluster_count,
/// largest_cluster_fraction
std::string statsCsvHeader();
/// One CSV row (no newline), reals with 9 significant digits.
std::string statsCsvRow(const FrameStats& stats);

/// @brief Reads a stats.csv: the header (columns in any order; unknown columns ignored)
/// and one row per line. Blank lines are skipped.
/// @throw IoError naming the file and line when it is missing, a column is missing or a
///        row is malformed.
std::vector<FrameStats> readStatsCsv(const std::filesystem::path& path);

}  // namespace globular
