#pragma once
// 8- and 16-bit RGBA images and their PNG files (libpng).

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

/// 16 bits per channel, for masters: the same layout as Image.
struct Image16 {
    int width = 0, height = 0;
    std::vector<uint16_t> rgba;  ///< rows top to bottom, 4 values per pixel, sRGB

    Image16() = default;
    Image16(int w, int h) : width(w), height(h), rgba(std::size_t(w) * h * 4, 0) {}
    const uint16_t* pixel(int x, int y) const { return &rgba[(std::size_t(y) * width + x) * 4]; }
    uint16_t* pixel(int x, int y) { return &rgba[(std::size_t(y) * width + x) * 4]; }
};

/// Reads any PNG (palette, grey, 16-bit, with or without alpha) as 8-bit RGBA.
/// @throw IoError naming @p path when it is missing or not a valid PNG.
Image readPng(const std::filesystem::path& path);
/// Reads any PNG as 16-bit RGBA (8-bit files scaled by 257); @p bitDepth, when given,
/// receives the file's own bits per channel.
Image16 readPng16(const std::filesystem::path& path, int* bitDepth = nullptr);

/// Writes @p image as an 8-bit RGBA PNG, atomically (a temporary file renamed into place).
/// @throw IoError naming @p path.
void writePng(const std::filesystem::path& path, const Image& image);
/// Writes @p image as a 16-bit RGBA PNG (RGB when every alpha is 65535), atomically.
void writePng(const std::filesystem::path& path, const Image16& image);

}  // namespace globular
