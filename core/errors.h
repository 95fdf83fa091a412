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

/// @p text as an error message may quote it: control characters and bytes that are not
/// UTF-8 escaped (a newline would break the message's one line; a damaged file's bytes
/// would garble the terminal) and cut after @p limit bytes, so a megabyte of garbage in a
/// value never floods the terminal.
inline std::string quoteForMessage(const std::string& text, std::size_t limit = 200) {
    static const char* kHex = "0123456789abcdef";
    std::string out;
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    std::size_t i = 0;
    while (i < text.size() && i < limit) {
        const unsigned char c = byte(i);
        // Length of a well-formed UTF-8 sequence starting here, or 0.
        std::size_t n = c < 0x80 ? 1 : (c >= 0xC2 && c <= 0xDF) ? 2 : (c >= 0xE0 && c <= 0xEF) ? 3
                                                    : (c >= 0xF0 && c <= 0xF4) ? 4 : 0;
        for (std::size_t k = 1; k < n; ++k) {
            if (i + k >= text.size() || (byte(i + k) & 0xC0) != 0x80) n = 0;
        }
        if (c == '\n') {
            out += "\\n";
        } else if (n == 0 || c < 0x20 || c == 0x7f) {
            out += std::string("\\x") + kHex[c >> 4] + kHex[c & 15];
            n = 1;
        } else {
            out.append(text, i, n);
        }
        i += n == 0 ? 1 : n;
    }
    if (text.size() > limit) {
        out += "... (" + std::to_string(text.size()) + " bytes)";
    }
    return out;
}

}  // namespace globular
