#pragma once
// One run at a time in an output folder. Two runs writing one folder would interleave
// frames of both scenes with one's scene.toml and the other's checkpoint, and both exit
// 0. A run that simulates holds the folder exclusively; runs that only surface or render
// share it (farm chunks of one shot, on disjoint frames), but never with a simulation.
// The lock is a POSIX record lock on DIR/.globular.lock: the kernel drops it when the
// process ends, however it ends, so a crash never leaves the folder locked.

#include <filesystem>

namespace globular {

class OutputLock {
public:
    enum class Mode { Exclusive, Shared };

    /// Locks @p dir (which must exist) at once or not at all.
    /// @throw IoError naming the folder and the process that holds it (its pid and
    ///        command line), or why the lock file cannot be used.
    OutputLock(const std::filesystem::path& dir, Mode mode);
    ~OutputLock();
    OutputLock(const OutputLock&) = delete;
    OutputLock& operator=(const OutputLock&) = delete;

private:
    int mFd = -1;
};

}  // namespace globular
