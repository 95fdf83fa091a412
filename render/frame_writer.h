#pragma once
// Writes rendered frames to their files on a worker thread, one frame in flight, so that
// encoding and compressing frame f overlaps drawing frame f + 1.

#include <filesystem>
#include <future>

#include "linear_frame.h"
#include "tone_map.h"

namespace globular {

class FrameWriter {
  public:
    FrameWriter(const ToneMapping& tone, int pngBits, bool exr)
        : mTone(tone), mPngBits(pngBits), mExr(exr) {}
    /// Waits for the frame in flight; a failure there is not thrown from a destructor
    /// (finish() is where it is reported).
    ~FrameWriter();
    FrameWriter(const FrameWriter&) = delete;
    FrameWriter& operator=(const FrameWriter&) = delete;

    /// Starts writing @p frame to @p png (and the .exr beside it when asked), after the
    /// frame before it is on disk. Exchanges @p frame with the buffers of a frame already
    /// written, for the caller to draw into next.
    /// @throw what writing the previous frame threw (IoError naming its file).
    void write(LinearFrame& frame, const std::filesystem::path& png);

    /// Waits until every frame handed over is on disk.
    /// @throw what writing the last frame threw.
    void finish();

  private:
    ToneMapping mTone;
    int mPngBits;
    bool mExr;
    LinearFrame mWriting;  // owned by the worker while mPending runs
    std::future<void> mPending;
};

}  // namespace globular
