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

/// @p parse run by the warm reader: one process, forked by the helper on first use, that
/// parses file after file. Reading a frame's cache in a child forked for it cost 8x the
/// parse itself on this project's virtual machines, where every page a new process
/// touches first is a slow fault (docs/performance.md, "Nineteenth pass"); the warm
/// reader's memory is already mapped. It keeps the isolation that matters: a crash or a
/// hang ends the reader, not this program. Whatever it fails on (an error, a crash, its
/// time limit), or where it cannot start, the file is read again by
/// parseInHelperChild, whose answer or IoError is returned: so every error comes from a
/// reader that had read nothing before, and a reader that met a damaged file is never
/// used again. Calls from several threads take turns. @p seconds: the warm reader's time
/// limit (0: readerSeconds(path)).
std::string parseInWarmReader(const std::filesystem::path& path, PathParser parse,
                              double seconds = 0);

/// parseInChild(path, [&] { return parse(path); }) with the child forked by the helper.
/// Calls from several threads take turns. Where the helper cannot be started or stops
/// answering (killed, or it hangs), this process forks the reader itself, as before.
/// @throw IoError as parseInChild does.
std::string parseInHelperChild(const std::filesystem::path& path, PathParser parse);

}  // namespace globular
