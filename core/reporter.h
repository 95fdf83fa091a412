#pragma once
// How library code talks to the user: no printf in libraries, only this interface.
// The CLI implements it with a progress bar or plain log lines; tests use NullReporter.

#include <string_view>

namespace globular {

class Reporter {
public:
    virtual ~Reporter() = default;
    virtual void info(std::string_view message) = 0;
    virtual void warn(std::string_view message) = 0;
    /// @param stage "sim", "surface", "render"; @param done units finished of @p total.
    virtual void progress(std::string_view stage, long done, long total) = 0;
};

/// Discards everything; for tests and library callers that want silence.
class NullReporter final : public Reporter {
public:
    void info(std::string_view) override {}
    void warn(std::string_view) override {}
    void progress(std::string_view, long, long) override {}
};

}  // namespace globular
