#include "frame_writer.h"

#include <utility>

#include "exr_image.h"
#include "png_image.h"

namespace globular {

FrameWriter::~FrameWriter() {
    if (mPending.valid()) mPending.wait();
}

void FrameWriter::finish() {
    if (mPending.valid()) mPending.get();
}

void FrameWriter::write(LinearFrame& frame, const std::filesystem::path& png) {
    finish();
    std::swap(frame, mWriting);
    mPending = std::async(std::launch::async, [this, png] {
        if (mPngBits == 16) {
            writePng(png, encode16(mWriting, mTone));
        } else {
            writePng(png, encode8(mWriting, mTone));
        }
        if (mExr) {
            std::filesystem::path exr = png;
            writeExr(exr.replace_extension(".exr"), mWriting);
        }
    });
}

}  // namespace globular
