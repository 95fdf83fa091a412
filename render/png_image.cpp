#include "png_image.h"

#include <png.h>
#include <zlib.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "atomic_file.h"
#include "errors.h"

namespace globular {

namespace {

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// libpng reports errors through a callback that must not return; throwing from it
// unwinds through C frames, which libpng does not support, so we longjmp as it intends
// and turn the saved message into an exception afterwards.
struct ErrorState {
    std::string message;
};

void onPngError(png_structp png, png_const_charp message) {
    static_cast<ErrorState*>(png_get_error_ptr(png))->message = message;
    png_longjmp(png, 1);
}
void onPngWarning(png_structp, png_const_charp) {}

}  // namespace

namespace {

/// Reads @p path, normalised to RGBA at @p bits (8 or 16) per channel; @p allocate(w, h)
/// returns the row pointers to read into.
template <typename Allocate>
void readPngInto(const std::filesystem::path& path, int bits, int* fileBits, Allocate&& allocate) {
    File file(std::fopen(path.c_str(), "rb"));
    if (!file) throw IoError("cannot open " + path.string() + ": " + std::strerror(errno));
    png_byte signature[8];
    if (std::fread(signature, 1, 8, file.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
        throw IoError(path.string() + " is not a PNG file");
    }
    ErrorState state;
    png_structp png =
        png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, onPngError, onPngWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info) {
        png_destroy_read_struct(&png, nullptr, nullptr);
        throw IoError("cannot read " + path.string() + ": out of memory");
    }
    std::vector<png_bytep> rows;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw IoError("cannot read " + path.string() + ": " + state.message);
    }
    png_init_io(png, file.get());
    png_set_sig_bytes(png, 8);
    png_read_info(png, info);
    if (fileBits) *fileBits = png_get_bit_depth(png, info);
    // Normalise every colour type and depth to RGBA at the asked depth.
    png_set_expand(png);
    if (bits == 8) {
        png_set_strip_16(png);
    } else {
        png_set_expand_16(png);
        png_set_swap(png);  // PNG stores 16-bit values big-endian
    }
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, bits == 8 ? 0xff : 0xffff, PNG_FILLER_AFTER);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    rows = allocate(int(png_get_image_width(png, info)), int(png_get_image_height(png, info)));
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
}

/// Writes RGBA rows at @p bits per channel (RGB when @p opaque), atomically.
void writePngRows(const std::filesystem::path& path, int width, int height, int bits,
                  bool opaque, const std::vector<png_bytep>& rows) {
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        File file(std::fopen(temporary.c_str(), "wb"));
        if (!file) throw IoError(std::strerror(errno));
        ErrorState state;
        png_structp png =
            png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, onPngError, onPngWarning);
        png_infop info = png ? png_create_info_struct(png) : nullptr;
        if (!info) {
            png_destroy_write_struct(&png, nullptr);
            throw IoError("out of memory");
        }
        if (setjmp(png_jmpbuf(png))) {
            png_destroy_write_struct(&png, &info);
            throw IoError(state.message);
        }
        png_init_io(png, file.get());
        // Frames are large and written once. zlib's run-length strategy over the Sub
        // filter (each byte less its left neighbour) encodes a rendered full-HD frame 2.9x
        // as fast as level 3 with libpng's adaptive choice among all five filters, into a
        // file as small or smaller (docs/performance.md, "Nineteenth pass").
        png_set_compression_level(png, 3);
        png_set_compression_strategy(png, Z_RLE);
        png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
        png_set_IHDR(png, info, width, height, bits,
                     opaque ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE,
                     PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
        png_write_info(png, info);
        if (bits == 16) png_set_swap(png);  // our values are host (little-endian) order
        // An opaque image is stored as RGB: libpng drops the fourth value of each pixel.
        if (opaque) png_set_filler(png, 0, PNG_FILLER_AFTER);
        png_write_image(png, const_cast<png_bytepp>(rows.data()));
        png_write_end(png, info);
        png_destroy_write_struct(&png, &info);
        if (std::fflush(file.get()) != 0 || std::ferror(file.get())) {
            throw IoError(std::string("write failed: ") + std::strerror(errno));
        }
    });
}

template <typename AnyImage>
void checkShape(const std::filesystem::path& path, const AnyImage& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() != std::size_t(image.width) * image.height * 4) {
        throw IoError("cannot write " + path.string() + ": the image is empty or malformed");
    }
}

template <typename AnyImage>
std::vector<png_bytep> rowsOf(AnyImage& image) {
    std::vector<png_bytep> rows(image.height);
    for (int y = 0; y < image.height; ++y) rows[y] = reinterpret_cast<png_bytep>(image.pixel(0, y));
    return rows;
}

template <typename AnyImage, typename Value>
bool isOpaque(const AnyImage& image, Value full) {
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) {
        if (image.rgba[i] != full) return false;
    }
    return true;
}

}  // namespace

Image readPng(const std::filesystem::path& path) {
    Image image;
    readPngInto(path, 8, nullptr, [&](int w, int h) {
        image = Image(w, h);
        return rowsOf(image);
    });
    return image;
}

Image16 readPng16(const std::filesystem::path& path, int* bitDepth) {
    Image16 image;
    readPngInto(path, 16, bitDepth, [&](int w, int h) {
        image = Image16(w, h);
        return rowsOf(image);
    });
    return image;
}

void writePng(const std::filesystem::path& path, const Image& image) {
    checkShape(path, image);
    writePngRows(path, image.width, image.height, 8, isOpaque(image, uint8_t(255)),
                 rowsOf(const_cast<Image&>(image)));
}

void writePng(const std::filesystem::path& path, const Image16& image) {
    checkShape(path, image);
    writePngRows(path, image.width, image.height, 16, isOpaque(image, uint16_t(65535)),
                 rowsOf(const_cast<Image16&>(image)));
}

}  // namespace globular
