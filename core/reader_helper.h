#pragma once
// The reader processes of isolated_parse.h, forked by a small helper process instead of
// by this one. fork() marks every page of the caller copy-on-write: a 500 MiB surfacing
// process that forked a reader for each frame's cache then took a page fault (and, with
// two threads, a TLB shoot-down) on the first write to each page it touched afterwards:
// a third of the surface stage on this project's virtual machines
// (docs/performance.md, "Reader processes"). The helper is forked once, on the first
// read or by startReaderHelper; it forks the readers (parseInChild, same limits, same
// messages) and relays their answers over a socket.

#include <filesystem>
#include <string>

namespace globular {

/// A parse that needs nothing but the path: a plain function is the same code in the
/// helper (a forked copy of this program), so it can be named across the socket. The
/// copy is of the program as it was when the helper started, perhaps before anything
/// was initialized: a parser initializes what it uses (OpenVDB's grid types, say).
using PathParser = std::string (*)(const std::filesystem::path&);

/// Starts the helper now, where it is not running. Call it before this program starts
/// threads of its own (`globular` does, first thing in main): a fork copies only the
/// calling thread, so a lock that another thread held at that moment (the allocator's, a
/// library's) stays locked in the helper and in every reader it forks, which then hang.
/// Without it the helper starts on the first read, which may be on a worker thread.
void startReaderHelper();

/// parseInChild(path, [&] { return parse(path); }) with the child forked by the helper.
/// Calls from several threads take turns. Where the helper cannot be started or stops
/// answering (killed, or it hangs), this process forks the reader itself, as before.
/// @throw IoError as parseInChild does.
std::string parseInHelperChild(const std::filesystem::path& path, PathParser parse);

}  // namespace globular
