#include "png_image.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "errors.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
    fs::path dir = fs::temp_directory_path() / ("globular_png_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir / name;
}

TEST(PngImage, RoundTripIsExact) {
    Image image(5, 3);
    for (std::size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = uint8_t(i * 37 % 256);
    const fs::path path = scratch("round_trip.png");
    writePng(path, image);
    const Image back = readPng(path);
    EXPECT_EQ(back.width, 5);
    EXPECT_EQ(back.height, 3);
    EXPECT_EQ(back.rgba, image.rgba);
}

TEST(PngImage, OpaqueImagesRoundTripThroughRgb) {
    Image image(4, 4);
    for (std::size_t i = 0; i < image.rgba.size(); ++i) {
        image.rgba[i] = i % 4 == 3 ? 255 : uint8_t(i * 11);
    }
    const fs::path path = scratch("opaque.png");
    writePng(path, image);
    EXPECT_EQ(readPng(path).rgba, image.rgba);
}

TEST(PngImage, LeavesNoTemporaryBehind) {
    const fs::path path = scratch("clean/frame.png");
    writePng(path, Image(2, 2));
    int files = 0;
    for (const auto& entry : fs::directory_iterator(path.parent_path())) {
        (void)entry;
        ++files;
    }
    EXPECT_EQ(files, 1);
}

TEST(PngImage, MissingFileNamesThePath) {
    try {
        readPng(scratch("nothing_here.png"));
        FAIL();
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("nothing_here.png"), std::string::npos);
    }
}

TEST(PngImage, NotAPngIsAnIoError) {
    const fs::path path = scratch("text.png");
    std::ofstream(path) << "hello, not a png";
    EXPECT_THROW(readPng(path), IoError);
}

TEST(PngImage, TruncatedPngIsAnIoError) {
    Image image(64, 64);
    const fs::path path = scratch("whole.png");
    writePng(path, image);
    const auto size = fs::file_size(path);
    fs::resize_file(path, size / 2);
    EXPECT_THROW(readPng(path), IoError);
}

TEST(PngImage, MalformedImageIsRefused) {
    Image image(4, 4);
    image.rgba.resize(3);
    EXPECT_THROW(writePng(scratch("bad.png"), image), IoError);
}

}  // namespace
}  // namespace globular
