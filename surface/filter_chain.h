#pragma once
// The chain of level-set filters a scene applies after the metaball field has become a
// level set, written as one string because scene values are numbers, strings, booleans
// or vectors, never tables:
//
//     filters = "gaussian:2, dilate:1, erode:1"
//
// Syntax: steps separated by commas, applied left to right; each step is NAME or
// NAME:AMOUNT (spaces are ignored, an empty string means no filtering):
//   gaussian[:W]        Gaussian smoothing, stencil half-width W voxels (integer 1-8; 1)
//   mean_curvature[:N]  N iterations of mean-curvature flow (integer 1-100; 1)
//   laplacian[:N]       N iterations of Laplacian flow (integer 1-100; 1)
//   dilate[:D]          move the surface outward by D voxels (number in (0, 64]; 1)
//   erode[:D]           move the surface inward by D voxels (number in (0, 64]; 1)
// "dilate:1, erode:1" is a morphological closing: it fills thin cracks between globules.

#include <string>
#include <vector>

namespace globular {

enum class FilterKind { Gaussian, MeanCurvature, Laplacian, Dilate, Erode };

struct FilterStep {
    FilterKind kind = FilterKind::Gaussian;
    double amount = 1;  ///< width or iterations (integers) or a distance in voxels

    friend bool operator==(const FilterStep&, const FilterStep&) = default;
};

/// Parses @p text (syntax above).
/// @throw SceneError saying which step is wrong and why (unknown name with a suggestion,
///        bad or out-of-range amount, empty step); the caller prefixes the key.
std::vector<FilterStep> parseFilterChain(const std::string& text);

/// The canonical text of @p chain, which parseFilterChain reads back unchanged.
std::string formatFilterChain(const std::vector<FilterStep>& chain);

/// "gaussian", "mean_curvature", ...
const char* filterName(FilterKind kind);

}  // namespace globular
