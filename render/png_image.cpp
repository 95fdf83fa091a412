#include "png_image.h"

#include <png.h>

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

Image readPng(const std::filesystem::path& path) {
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
    Image image;
    std::vector<png_bytep> rows;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw IoError("cannot read " + path.string() + ": " + state.message);
    }
    png_init_io(png, file.get());
    png_set_sig_bytes(png, 8);
    png_read_info(png, info);
    // Normalise every colour type and depth to 8-bit RGBA.
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    image = Image(int(png_get_image_width(png, info)), int(png_get_image_height(png, info)));
    rows.resize(image.height);
    for (int y = 0; y < image.height; ++y) rows[y] = image.pixel(0, y);
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    return image;
}

void writePng(const std::filesystem::path& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() != std::size_t(image.width) * image.height * 4) {
        throw IoError("cannot write " + path.string() + ": the image is empty or malformed");
    }
    bool opaque = true;
    for (std::size_t i = 3; i < image.rgba.size() && opaque; i += 4) opaque = image.rgba[i] == 255;
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
        std::vector<png_bytep> rows(image.height);
        if (setjmp(png_jmpbuf(png))) {
            png_destroy_write_struct(&png, &info);
            throw IoError(state.message);
        }
        png_init_io(png, file.get());
        // Frames are large and written once: a low zlib level is the better trade.
        png_set_compression_level(png, 3);
        png_set_IHDR(png, info, image.width, image.height, 8,
                     opaque ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE,
                     PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
        png_write_info(png, info);
        // An opaque image is stored as RGB: libpng drops the fourth byte of each pixel.
        if (opaque) png_set_filler(png, 0, PNG_FILLER_AFTER);
        for (int y = 0; y < image.height; ++y) {
            rows[y] = const_cast<png_bytep>(image.pixel(0, y));
        }
        png_write_image(png, rows.data());
        png_write_end(png, info);
        png_destroy_write_struct(&png, &info);
        if (std::fflush(file.get()) != 0 || std::ferror(file.get())) {
            throw IoError(std::string("write failed: ") + std::strerror(errno));
        }
    });
}

}  // namespace globular
