#pragma once
// The CLI's Reporter: a progress bar with ETA on a terminal, plain log lines otherwise
// (a render farm's log), warnings always, nothing but warnings with --quiet.

#include <chrono>
#include <cstdio>
#include <string>

#include "reporter.h"

namespace globular {

class ConsoleReporter final : public Reporter {
public:
    /// @param stream where messages go (stderr); the bar is used only when it is a TTY.
    ConsoleReporter(std::FILE* stream, bool quiet);
    ~ConsoleReporter() override;

    void info(std::string_view message) override;
    void warn(std::string_view message) override;
    void progress(std::string_view stage, long done, long total) override;

private:
    void endBar();

    std::FILE* mStream;
    bool mQuiet, mTerminal, mBarOpen = false;
    std::string mStage;
    long mStartDone = 0, mLastTenth = -1;
    std::chrono::steady_clock::time_point mStart;
};

}  // namespace globular
