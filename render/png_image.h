#pragma once
// 8-bit RGBA images and their PNG files (libpng).

#include <cstdint>
#include <filesystem>
#include <vector>

namespace globular {

struct Image {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;  ///< rows top to bottom, 4 bytes per pixel, sRGB

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgba(std::size_t(w) * h * 4, 0) {}
    const uint8_t* pixel(int x, int y) const { return &rgba[(std::size_t(y) * width + x) * 4]; }
    uint8_t* pixel(int x, int y) { return &rgba[(std::size_t(y) * width + x) * 4]; }
};

/// Reads any PNG (palette, grey, 16-bit, with or without alpha) as 8-bit RGBA.
/// @throw IoError naming @p path when it is missing or not a valid PNG.
Image readPng(const std::filesystem::path& path);

/// Writes @p image as an 8-bit RGBA PNG, atomically (a temporary file renamed into place).
/// @throw IoError naming @p path.
void writePng(const std::filesystem::path& path, const Image& image);

}  // namespace globular
