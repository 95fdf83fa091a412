#pragma once
// Typed exceptions thrown by the globular libraries. Only the CLI catches them, prints
// the message and sets the exit status.

#include <stdexcept>
#include <string>

namespace globular {

/// Base of every error globular reports to a user.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A scene file or override is malformed or out of range. The message names the file,
/// line, column and key.
class SceneError : public Error {
public:
    using Error::Error;
};

/// Reading or writing a file failed (missing, truncated, corrupt, disk full, ...).
/// The message names the file.
class IoError : public Error {
public:
    using Error::Error;
};

/// The simulation became invalid (non-finite state, runaway speed).
class SimulationError : public Error {
public:
    using Error::Error;
};

/// A request exceeds the machine: memory estimate or size limits.
class ResourceError : public Error {
public:
    using Error::Error;
};

/// @p text as an error message may quote it: control characters escaped (a newline
/// would break the message's one line) and cut after @p limit characters, so a
/// megabyte of garbage in a value never floods the terminal.
inline std::string quoteForMessage(const std::string& text, std::size_t limit = 200) {
    std::string out;
    for (std::size_t i = 0; i < text.size() && i < limit; ++i) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (c == '\n') {
            out += "\\n";
        } else if (c < 0x20 || c == 0x7f) {
            static const char* kHex = "0123456789abcdef";
            out += std::string("\\x") + kHex[c >> 4] + kHex[c & 15];
        } else {
            out += char(c);
        }
    }
    if (text.size() > limit) {
        out += "... (" + std::to_string(text.size()) + " characters)";
    }
    return out;
}

}  // namespace globular
