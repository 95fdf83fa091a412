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

}  // namespace globular
