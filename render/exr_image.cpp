#include "exr_image.h"

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <half.h>

#include <exception>
#include <string>
#include <vector>

#include "atomic_file.h"
#include "errors.h"

namespace globular {

namespace {

/// @p count interleaved channels of @p values, converted to half.
std::vector<half> toHalf(const std::vector<float>& values) {
    std::vector<half> out(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) out[i] = half(values[i]);
    return out;
}

}  // namespace

void writeExr(const std::filesystem::path& path, const LinearFrame& frame) {
    const std::size_t pixels = std::size_t(frame.width) * frame.height;
    if (frame.width <= 0 || frame.height <= 0 || frame.rgba.size() != 4 * pixels ||
        (frame.hasPasses() && (frame.depth.size() != pixels || frame.normal.size() != 3 * pixels)) ||
        (!frame.motion.empty() && (!frame.hasPasses() || frame.motion.size() != 2 * pixels))) {
        throw IoError("cannot write " + path.string() + ": the frame is empty or malformed");
    }
    const std::vector<half> rgba = toHalf(frame.rgba);
    const std::vector<half> normal = toHalf(frame.normal);
    const std::vector<half> motion = toHalf(frame.motion);
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        try {
            Imf::Header header(frame.width, frame.height);
            header.compression() = Imf::ZIP_COMPRESSION;
            Imf::FrameBuffer buffer;
            const std::size_t halfPixel = 4 * sizeof(half);
            const char* names[] = {"R", "G", "B", "A"};
            for (int c = 0; c < 4; ++c) {
                header.channels().insert(names[c], Imf::Channel(Imf::HALF));
                buffer.insert(names[c],
                              Imf::Slice(Imf::HALF, (char*)(rgba.data() + c), halfPixel,
                                         halfPixel * frame.width));
            }
            if (frame.hasPasses()) {
                header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
                buffer.insert("Z", Imf::Slice(Imf::FLOAT, (char*)frame.depth.data(),
                                              sizeof(float), sizeof(float) * frame.width));
                const char* axes[] = {"N.x", "N.y", "N.z"};
                for (int c = 0; c < 3; ++c) {
                    header.channels().insert(axes[c], Imf::Channel(Imf::HALF));
                    buffer.insert(axes[c],
                                  Imf::Slice(Imf::HALF, (char*)(normal.data() + c),
                                             3 * sizeof(half), 3 * sizeof(half) * frame.width));
                }
            }
            if (!frame.motion.empty()) {
                const char* axes[] = {"forward.u", "forward.v"};
                for (int c = 0; c < 2; ++c) {
                    header.channels().insert(axes[c], Imf::Channel(Imf::HALF));
                    buffer.insert(axes[c],
                                  Imf::Slice(Imf::HALF, (char*)(motion.data() + c),
                                             2 * sizeof(half), 2 * sizeof(half) * frame.width));
                }
            }
            Imf::OutputFile file(temporary.c_str(), header);
            file.setFrameBuffer(buffer);
            file.writePixels(frame.height);
        } catch (const std::exception& e) {
            throw IoError(e.what());
        }
    });
}

}  // namespace globular
