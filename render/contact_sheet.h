#pragma once
// Several frames tiled into one PNG, like the paper's figure strips (Figs. 1, 5-7).

#include <filesystem>
#include <vector>

#include "png_image.h"

namespace globular {

/// Tiles @p framePngs row by row, @p columns per row, each scaled to @p tileWidth pixels
/// wide (heights keep each frame's aspect; a row is as tall as its tallest tile), with a
/// white gutter of kContactGutter pixels around and between tiles. Written atomically.
/// @throw IoError naming a frame that cannot be read or @p out when it cannot be written;
///        Error when @p framePngs is empty or @p columns or @p tileWidth is below 1.
void writeContactSheet(const std::vector<std::filesystem::path>& framePngs, int columns,
                       int tileWidth, const std::filesystem::path& out);

/// The tiling of writeContactSheet for images already in memory.
Image contactSheet(const std::vector<Image>& frames, int columns, int tileWidth);

/// @p image scaled to @p width x @p height by averaging the source area under each output
/// pixel in linear light (no aliasing when shrinking; smooth when enlarging).
Image resizeImage(const Image& image, int width, int height);

/// Evenly spaced frames of [first, last]: @p count of them including both ends, or every
/// frame when the range holds fewer.
std::vector<int> evenlySpacedFrames(int first, int last, int count);

/// Tiles per row when the scene leaves it to us: a single strip up to 4 frames, otherwise
/// the columns of a sheet about as wide as a frame (6 frames: 3 x 2; 12: 4 x 3).
int automaticColumns(int frameCount);

inline constexpr int kContactGutter = 8;  ///< pixels

}  // namespace globular
