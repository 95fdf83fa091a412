#include "contact_sheet.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "color_ramp.h"
#include "errors.h"

namespace globular {

namespace {

const std::array<float, 256>& linearTable() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) t[i] = float(srgbToLinear(i / 255.0));
        return t;
    }();
    return table;
}

uint8_t toByte(double linear) { return uint8_t(std::lround(255.0 * linearToSrgb(linear))); }

/// For each output column (or row) of @p outSize over @p inSize source pixels: the source
/// pixels it covers and the fraction of each.
struct Span {
    int first = 0;
    std::vector<float> weights;
};

std::vector<Span> spans(int inSize, int outSize) {
    std::vector<Span> out(outSize);
    const double scale = double(inSize) / outSize;
    for (int o = 0; o < outSize; ++o) {
        double lo = o * scale, hi = (o + 1) * scale;
        if (scale < 1) {  // enlarging: a one-pixel window centred on the sample (bilinear)
            const double centre = (o + 0.5) * scale;
            lo = centre - 0.5;
            hi = centre + 0.5;
        }
        const int first = std::max(0, int(std::floor(lo)));
        const int last = std::min(inSize - 1, int(std::ceil(hi)) - 1);
        Span& s = out[o];
        s.first = first;
        double total = 0;
        for (int i = first; i <= last; ++i) {
            const double w = std::min(hi, i + 1.0) - std::max(lo, double(i));
            s.weights.push_back(float(std::max(w, 0.0)));
            total += std::max(w, 0.0);
        }
        if (s.weights.empty()) {
            s.first = std::clamp(int(lo), 0, inSize - 1);
            s.weights = {1.0f};
            total = 1;
        }
        for (float& w : s.weights) w = float(w / total);
    }
    return out;
}

}  // namespace

Image resizeImage(const Image& in, int width, int height) {
    if (width < 1 || height < 1 || in.width < 1 || in.height < 1) {
        throw Error("render: cannot resize an image to or from zero size");
    }
    const auto& lin = linearTable();
    const std::vector<Span> xs = spans(in.width, width), ys = spans(in.height, height);
    // Horizontal pass into linear floats, then vertical pass into bytes.
    std::vector<float> rows(std::size_t(in.height) * width * 4);
    for (int y = 0; y < in.height; ++y) {
        for (int x = 0; x < width; ++x) {
            float sum[4] = {0, 0, 0, 0};
            const Span& s = xs[x];
            for (std::size_t k = 0; k < s.weights.size(); ++k) {
                const uint8_t* p = in.pixel(s.first + int(k), y);
                for (int c = 0; c < 3; ++c) sum[c] += s.weights[k] * lin[p[c]];
                sum[3] += s.weights[k] * p[3] / 255.0f;
            }
            std::copy(sum, sum + 4, &rows[(std::size_t(y) * width + x) * 4]);
        }
    }
    Image out(width, height);
    for (int y = 0; y < height; ++y) {
        const Span& s = ys[y];
        for (int x = 0; x < width; ++x) {
            double sum[4] = {0, 0, 0, 0};
            for (std::size_t k = 0; k < s.weights.size(); ++k) {
                const float* p = &rows[((s.first + k) * width + x) * 4];
                for (int c = 0; c < 4; ++c) sum[c] += s.weights[k] * p[c];
            }
            uint8_t* o = out.pixel(x, y);
            for (int c = 0; c < 3; ++c) o[c] = toByte(sum[c]);
            o[3] = uint8_t(std::lround(255.0 * std::clamp(sum[3], 0.0, 1.0)));
        }
    }
    return out;
}

Image contactSheet(const std::vector<Image>& frames, int columns, int tileWidth) {
    if (frames.empty()) throw Error("render: a contact sheet needs at least one frame");
    if (columns < 1 || tileWidth < 1) {
        throw Error("render: a contact sheet needs at least one column and one pixel per tile");
    }
    columns = std::min<int>(columns, int(frames.size()));
    const int rows = (int(frames.size()) + columns - 1) / columns;
    std::vector<Image> tiles;
    std::vector<int> rowHeight(rows, 0);
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const Image& f = frames[i];
        const int h = std::max(1, int(std::lround(double(tileWidth) * f.height / f.width)));
        tiles.push_back(resizeImage(f, tileWidth, h));
        rowHeight[i / columns] = std::max(rowHeight[i / columns], h);
    }
    int height = kContactGutter;
    for (int h : rowHeight) height += h + kContactGutter;
    Image sheet(kContactGutter + columns * (tileWidth + kContactGutter), height);
    std::fill(sheet.rgba.begin(), sheet.rgba.end(), uint8_t(255));
    int top = kContactGutter;
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < columns && r * columns + c < int(tiles.size()); ++c) {
            const Image& tile = tiles[r * columns + c];
            const int left = kContactGutter + c * (tileWidth + kContactGutter);
            for (int y = 0; y < tile.height; ++y) {
                std::copy(tile.pixel(0, y), tile.pixel(0, y) + std::size_t(tile.width) * 4,
                          sheet.pixel(left, top + y));
            }
        }
        top += rowHeight[r] + kContactGutter;
    }
    return sheet;
}

void writeContactSheet(const std::vector<std::filesystem::path>& framePngs, int columns,
                       int tileWidth, const std::filesystem::path& out) {
    std::vector<Image> frames;
    for (const auto& path : framePngs) frames.push_back(readPng(path));
    writePng(out, contactSheet(frames, columns, tileWidth));
}

std::vector<int> evenlySpacedFrames(int first, int last, int count) {
    std::vector<int> frames;
    const int available = last - first + 1;
    if (count <= 0 || available <= 0) return frames;
    if (count >= available || count == 1) {
        for (int f = first; f <= last && int(frames.size()) < std::max(count, 1); ++f) {
            frames.push_back(f);
        }
        return frames;
    }
    for (int i = 0; i < count; ++i) {
        frames.push_back(first + int(std::lround(double(i) * (last - first) / (count - 1))));
    }
    return frames;
}

int automaticColumns(int frameCount) {
    if (frameCount <= 4) return std::max(frameCount, 1);
    // Rows for a sheet of roughly 16:9 frames that is itself about 16:9 wide.
    const int rows = std::max(1, int(std::lround(std::sqrt(frameCount * 9.0 / 16.0))));
    return (frameCount + rows - 1) / rows;
}

}  // namespace globular
