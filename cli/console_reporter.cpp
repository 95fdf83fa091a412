#include "console_reporter.h"

#include <unistd.h>

#include <cmath>

namespace globular {

namespace {

std::string formatDuration(double seconds) {
    const long s = long(std::lround(seconds));
    char text[32];
    std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
    return text;
}

}  // namespace

ConsoleReporter::ConsoleReporter(std::FILE* stream, bool quiet)
    : mStream(stream), mQuiet(quiet), mTerminal(::isatty(::fileno(stream)) == 1) {}

ConsoleReporter::~ConsoleReporter() { endBar(); }

void ConsoleReporter::endBar() {
    if (mBarOpen) std::fputc('\n', mStream);
    mBarOpen = false;
}

void ConsoleReporter::info(std::string_view message) {
    if (mQuiet) return;
    endBar();
    std::fprintf(mStream, "%.*s\n", int(message.size()), message.data());
}

void ConsoleReporter::warn(std::string_view message) {
    endBar();
    std::fprintf(mStream, "warning: %.*s\n", int(message.size()), message.data());
}

void ConsoleReporter::progress(std::string_view stage, long done, long total) {
    if (mQuiet || total <= 0) return;
    const auto now = std::chrono::steady_clock::now();
    if (stage != mStage) {
        endBar();
        mStage = stage;
        mStart = now;
        mStartDone = done;
        mLastTenth = -1;
    }
    const double elapsed = std::chrono::duration<double>(now - mStart).count();
    const long work = done - mStartDone, left = total - done;
    const std::string eta =
        work > 0 ? formatDuration(elapsed / double(work) * double(left)) : std::string("?");
    if (mTerminal) {
        constexpr int kWidth = 30;
        const int filled = int(kWidth * done / total);
        std::string bar(std::size_t(filled), '#');
        bar.resize(kWidth, '.');
        std::fprintf(mStream, "\r%-7s [%s] frame %ld/%ld  elapsed %s  ETA %s ", mStage.c_str(),
                     bar.c_str(), done, total, formatDuration(elapsed).c_str(), eta.c_str());
        std::fflush(mStream);
        mBarOpen = true;
        if (done == total) endBar();
        return;
    }
    // Plain lines: one per tenth of the work, so a log stays readable.
    const long tenth = done * 10 / total;
    if (tenth == mLastTenth && done != total) return;
    mLastTenth = tenth;
    std::fprintf(mStream, "%s: frame %ld/%ld, elapsed %s, ETA %s\n", mStage.c_str(), done, total,
                 formatDuration(elapsed).c_str(), eta.c_str());
    std::fflush(mStream);
}

}  // namespace globular
