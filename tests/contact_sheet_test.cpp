#include "contact_sheet.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "errors.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

Image solid(int w, int h, uint8_t r, uint8_t g, uint8_t b) {
    Image image(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            uint8_t* p = image.pixel(x, y);
            p[0] = r, p[1] = g, p[2] = b, p[3] = 255;
        }
    }
    return image;
}

TEST(ResizeImage, SolidStaysSolid) {
    const Image out = resizeImage(solid(37, 21, 10, 128, 250), 8, 5);
    for (int y = 0; y < 5; ++y) {
        for (int x = 0; x < 8; ++x) {
            EXPECT_EQ(out.pixel(x, y)[0], 10);
            EXPECT_EQ(out.pixel(x, y)[1], 128);
            EXPECT_EQ(out.pixel(x, y)[2], 250);
        }
    }
}

TEST(ResizeImage, HalvingAveragesInLinearLight) {
    // Black and white columns halve to the sRGB value of 50% linear grey (188), not 128.
    Image stripes = solid(4, 2, 0, 0, 0);
    for (int y = 0; y < 2; ++y) {
        for (int x = 1; x < 4; x += 2) {
            uint8_t* p = stripes.pixel(x, y);
            p[0] = p[1] = p[2] = 255;
        }
    }
    const Image out = resizeImage(stripes, 2, 1);
    EXPECT_EQ(out.pixel(0, 0)[0], 188);
    EXPECT_EQ(out.pixel(1, 0)[1], 188);
}

TEST(ContactSheet, TilesRowByRowWithGutters) {
    std::vector<Image> frames = {solid(40, 20, 255, 0, 0), solid(40, 20, 0, 255, 0),
                                 solid(40, 20, 0, 0, 255)};
    const Image sheet = contactSheet(frames, 2, 20);
    const int g = kContactGutter;
    EXPECT_EQ(sheet.width, g + 2 * (20 + g));
    EXPECT_EQ(sheet.height, g + 2 * (10 + g));
    auto colour = [&](int x, int y) {
        const uint8_t* p = sheet.pixel(x, y);
        return std::array<int, 3>{p[0], p[1], p[2]};
    };
    EXPECT_EQ(colour(g + 10, g + 5), (std::array<int, 3>{255, 0, 0}));
    EXPECT_EQ(colour(2 * g + 20 + 10, g + 5), (std::array<int, 3>{0, 255, 0}));
    EXPECT_EQ(colour(g + 10, 2 * g + 10 + 5), (std::array<int, 3>{0, 0, 255}));
    EXPECT_EQ(colour(g / 2, g / 2), (std::array<int, 3>{255, 255, 255}));            // gutter
    EXPECT_EQ(colour(2 * g + 30, 2 * g + 15), (std::array<int, 3>{255, 255, 255}));  // empty slot
}

TEST(ContactSheet, WritesAFileFromFramePngs) {
    const fs::path dir = fs::temp_directory_path() / "globular_sheet" / std::to_string(::getpid());
    std::vector<fs::path> pngs;
    for (int i = 0; i < 4; ++i) {
        pngs.push_back(dir / std::string("f").append(std::to_string(i)).append(".png"));
        writePng(pngs.back(), solid(64, 48, uint8_t(60 * i), 0, 0));
    }
    writeContactSheet(pngs, 4, 32, dir / "sheet.png");
    const Image sheet = readPng(dir / "sheet.png");
    EXPECT_EQ(sheet.width, kContactGutter + 4 * (32 + kContactGutter));
    EXPECT_EQ(sheet.height, 24 + 2 * kContactGutter);
    EXPECT_EQ(sheet.pixel(kContactGutter + 3 * (32 + kContactGutter) + 5, 12)[0], 180);
    fs::remove_all(dir);
}

TEST(ContactSheet, BadArgumentsAreErrors) {
    EXPECT_THROW(contactSheet({}, 2, 20), Error);
    EXPECT_THROW(contactSheet({solid(4, 4, 0, 0, 0)}, 0, 20), Error);
    EXPECT_THROW(writeContactSheet({"/nonexistent/frame.png"}, 1, 20, "/tmp/x.png"), IoError);
}

TEST(ContactSheet, EvenlySpacedFramesIncludeBothEnds) {
    EXPECT_EQ(evenlySpacedFrames(1, 100, 4), (std::vector<int>{1, 34, 67, 100}));
    EXPECT_EQ(evenlySpacedFrames(5, 7, 6), (std::vector<int>{5, 6, 7}));
    EXPECT_EQ(evenlySpacedFrames(3, 9, 1), (std::vector<int>{3}));
    EXPECT_TRUE(evenlySpacedFrames(1, 10, 0).empty());
}

TEST(ContactSheet, AutomaticColumns) {
    EXPECT_EQ(automaticColumns(1), 1);
    EXPECT_EQ(automaticColumns(4), 4);
    EXPECT_EQ(automaticColumns(6), 3);
    EXPECT_EQ(automaticColumns(12), 4);
}

}  // namespace
}  // namespace globular
