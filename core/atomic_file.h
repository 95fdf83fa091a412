#pragma once
// Every output file is written under a temporary name in the same directory, flushed to
// disk and renamed over its final name, so a crash or a full disk never leaves a
// half-written frame under a final name.

#include <filesystem>
#include <functional>
#include <string>

namespace globular {

/// Produces @p target atomically. @p write must create the file at the path it is given
/// (a temporary beside @p target). Parent directories are created as needed.
/// @throw IoError naming @p target when writing, flushing or renaming fails; the
///        temporary is removed and an existing @p target is left untouched.
void writeAtomically(const std::filesystem::path& target,
                     const std::function<void(const std::filesystem::path& temporary)>& write);

/// writeAtomically for text or bytes already in memory.
void writeFileAtomically(const std::filesystem::path& target, const std::string& contents);

/// Removes temporaries that writeAtomically left in @p dir and its direct subfolders when
/// its process was killed: only names of exactly our pattern
/// (".<name>.globular-tmp-<host>-<pid>-<n>") made on this host by a process that is no
/// longer running, so a concurrent job keeps its files and a user's file that merely
/// looks like a temporary is never touched. @return the count.
std::size_t removeStaleTemporaries(const std::filesystem::path& dir);

/// Creates @p dir (and parents) and checks that it is a writable directory.
/// @throw IoError naming the directory otherwise.
void ensureWritableDirectory(const std::filesystem::path& dir);

}  // namespace globular
