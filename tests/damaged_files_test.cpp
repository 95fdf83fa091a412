// Every file a stage reads may be damaged or hostile (issue 11): a reader either returns
// something consistent or throws an IoError naming the file; it never crashes, hangs or
// takes the machine's memory. Real files of each kind are written, then damaged at
// random (with the checksum forged back where the file has one, so the bytes reach
// OpenVDB), truncated at every length and crafted by hand.

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <latch>
#include <memory>
#include <mutex>
#include <random>
#include <sstream>
#include <string>
#include <thread>

#include "errors.h"
#include "file_bytes.h"
#include "globule_cache.h"
#include "isolated_parse.h"
#include "mesh.h"
#include "state_file.h"
#include "surface_frame.h"
#include "surface_grids.h"
#include "vdb_archive.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

class DamagedFiles : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        mDir = fs::temp_directory_path() /
               ("globular_damaged_" + std::string(info->name()) + "_" + std::to_string(getpid()));
        fs::remove_all(mDir);
        fs::create_directories(mDir);
    }
    void TearDown() override {
        if (!HasFailure()) fs::remove_all(mDir);
    }
    fs::path path(const std::string& name) const { return mDir / name; }

    fs::path mDir;
};

/// A small blob of liquid: 120 globules on a jittered lattice, moving.
Globules blob() {
    Globules g;
    std::mt19937 random(5);
    std::uniform_real_distribution<float> jitter(-0.1f, 0.1f);
    for (int i = 0; i < 120; ++i) {
        g.add({float(i % 5) + jitter(random), float(i / 25) + 1, float(i / 5 % 5) + jitter(random)},
              {0.5f, -float(i % 7), 0.25f}, 0.6f, 1.0f, i);
    }
    return g;
}

void writeBytes(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

/// @p original with 1 to 8 bytes changed at random after @p from; sometimes cut short.
std::string damaged(const std::string& original, std::size_t from, std::mt19937& random) {
    std::string bytes = original;
    const int changes = 1 << (random() % 4);
    for (int k = 0; k < changes; ++k) {
        bytes[from + random() % (bytes.size() - from)] = char(random() % 256);
    }
    if (random() % 10 == 0) bytes.resize(from + random() % (bytes.size() - from));
    return bytes;
}

/// Runs @p read on @p file and checks that it returned or threw an IoError naming it.
template <typename Read>
void expectSurvives(const fs::path& file, Read&& read, int& refused) {
    try {
        read();
    } catch (const IoError& e) {
        ++refused;
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
}

TEST_F(DamagedFiles, CacheWithForgedChecksumNeverCrashes) {
    const fs::path file = path("globules.0001.vdb");
    writeGlobuleVdb(file, blob(), CacheInfo{1, 0.0});
    const std::string original = readFileBytes(file, 1 << 30);
    std::mt19937 random(11);
    int refused = 0, forged = 0;
    for (int trial = 0; trial < 300; ++trial) {
        std::string bytes = damaged(original, 200, random);
        try {
            sealVdbChecksum(bytes);
            ++forged;
        } catch (const std::exception&) {  // layout broken: the byte checks refuse it
        }
        writeBytes(file, bytes);
        expectSurvives(file, [&] {
            const Globules g = readGlobuleVdb(file);
            EXPECT_TRUE(g.consistent());
        }, refused);
    }
    EXPECT_GT(forged, 200);   // most damaged files reached OpenVDB in the child
    EXPECT_GT(refused, 200);  // and most were refused
}

// Two damaged caches (checksum forged) that abort OpenVDB 10 inside its own asserts when
// read in-process: "PageHandle::read(): Assertion `mSize > 0'" and
// "AttributeSet::Descriptor::type: Assertion `pos < mTypes.size()'".
TEST_F(DamagedFiles, CachesThatAbortOpenVdbAreErrors) {
    for (const char* name : {"cache_page_size_zero.vdb", "cache_attribute_index.vdb"}) {
        const fs::path file = fs::path(GLOBULAR_SOURCE_DIR) / "tests/data/damaged" / name;
        try {
            readGlobuleVdb(file);
            ADD_FAILURE() << name << " was read";
        } catch (const IoError& e) {
            EXPECT_NE(std::string(e.what()).find("crashed (SIGABRT)"), std::string::npos)
                << e.what();
        }
    }
}

TEST_F(DamagedFiles, CacheFlipsAndCutsAreRefusedByTheChecksum) {
    const fs::path file = path("globules.0001.vdb");
    writeGlobuleVdb(file, blob(), CacheInfo{1, 0.0});
    const std::string original = readFileBytes(file, 1 << 30);
    for (std::size_t i = 0; i < original.size(); i += 97) {
        std::string bytes = original;
        bytes[i] = char(bytes[i] ^ 0x10);
        writeBytes(file, bytes);
        EXPECT_THROW(readGlobuleVdb(file), IoError) << "flip at byte " << i;
        writeBytes(file, original.substr(0, i));
        EXPECT_THROW(readGlobuleVdb(file), IoError) << "cut at byte " << i;
    }
    writeBytes(file, original);
    EXPECT_EQ(readGlobuleVdb(file).size(), 120u);
}

// `globular` starts the reader helper before anything initializes OpenVDB (main,
// before threads): its readers register OpenVDB's grid types themselves.
TEST_F(DamagedFiles, ReadersOfAHelperStartedBeforeOpenVdbReadEveryFile) {
    startReaderHelper();
    const fs::path cache = path("globules.0001.vdb"), surface = path("surface.0001.vdb");
    writeGlobuleVdb(cache, blob(), CacheInfo{1, 0.0});
    writeSurfaceVdb(surface, surfaceGlobules(blob(), SurfaceSettings{}));
    EXPECT_EQ(readGlobuleVdb(cache).size(), 120u);
    EXPECT_TRUE(readSurfaceVdb(surface).surface);
}

TEST_F(DamagedFiles, SurfaceVdbWithForgedChecksumNeverCrashes) {
    SurfaceSettings settings;
    const SurfaceFrame frame = surfaceGlobules(blob(), settings);
    const fs::path file = path("surface.0001.vdb");
    writeSurfaceVdb(file, frame);
    const SurfaceGrids intact = readSurfaceVdb(file);
    ASSERT_TRUE(intact.surface && intact.density);
    EXPECT_EQ(intact.surface->activeVoxelCount(), frame.grids->surface->activeVoxelCount());

    const std::string original = readFileBytes(file, 1 << 30);
    std::mt19937 random(12);
    int refused = 0;
    for (int trial = 0; trial < 150; ++trial) {
        std::string bytes = damaged(original, 200, random);
        try {
            sealVdbChecksum(bytes);
        } catch (const std::exception&) {
        }
        writeBytes(file, bytes);
        expectSurvives(file, [&] {
            const SurfaceGrids grids = readSurfaceVdb(file);
            EXPECT_TRUE(grids.surface && grids.density);
        }, refused);
    }
    EXPECT_GT(refused, 50);
}

TEST_F(DamagedFiles, MeshNeverCrashesAndStaysInRange) {
    const SurfaceFrame frame = surfaceGlobules(blob(), SurfaceSettings{});
    const fs::path file = path("surface.0001.ply");
    writeMeshPly(file, frame.mesh);
    const std::string original = readFileBytes(file, 1 << 30);
    const std::size_t header = original.find("end_header\n") + 11;
    std::mt19937 random(13);
    int refused = 0;
    for (int trial = 0; trial < 400; ++trial) {
        // Half the trials damage the header's text, half the binary data.
        writeBytes(file, damaged(original, trial % 2 ? header : 0, random));
        expectSurvives(file, [&] {
            const TriangleMesh mesh = readMeshPly(file);
            for (uint32_t index : mesh.triangles) ASSERT_LT(index, mesh.vertexCount());
        }, refused);
    }
    EXPECT_GT(refused, 100);
}

TEST_F(DamagedFiles, PlyElementWithHugeCountAndNoPropertiesIsRefusedAtOnce) {
    const fs::path file = path("crafted.ply");
    for (const char* extra : {"element junk 18446744073709551615\n",
                              "element junk 4000000000\nproperty list uchar int x\n"}) {
        // Before the vertices, so that both readers must walk past it; and after them.
        const std::string vertices = "element vertex 1\nproperty float x\nproperty float y\n"
                                     "property float z\n";
        writeBytes(file, "ply\nformat binary_little_endian 1.0\n" + std::string(extra) +
                             vertices + "end_header\n" + std::string(12, '\0'));
        EXPECT_THROW(readGlobulePly(file), IoError) << extra;
        writeBytes(file, "ply\nformat binary_little_endian 1.0\n" + vertices + extra +
                             "end_header\n" + std::string(12, '\0'));
        const auto start = std::chrono::steady_clock::now();
        EXPECT_THROW(readMeshPly(file), IoError) << extra;
        EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
    }
}

TEST_F(DamagedFiles, PointsFileRefusesValuesNoSimulationCanStartFrom) {
    const fs::path file = path("points.ply");
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n"
                               "property float y\nproperty float z\nproperty float vx\n"
                               "property float radius\nend_header\n0 0 0 0 1\n";
    for (const char* row : {"0 nan 0 0 1\n", "0 0 0 inf 1\n", "0 0 0 0 -1\n", "0 0 0 0 0\n"}) {
        writeBytes(file, header + row);
        EXPECT_THROW(readGlobulePly(file), IoError) << row;
    }
    writeBytes(file, header + "1 2 3 4 0.5\n");
    EXPECT_EQ(readGlobulePly(file).size(), 2u);
}

TEST_F(DamagedFiles, DevicesAndFoldersAreNotFiles) {
    EXPECT_THROW(readGlobulePly("/dev/zero"), IoError);
    EXPECT_THROW(readMeshPly("/dev/zero"), IoError);
    EXPECT_THROW(readGlobuleVdb(mDir), IoError);
    EXPECT_THROW(readCheckpoint("/dev/zero"), IoError);
}

Checkpoint smallCheckpoint() {
    Checkpoint c;
    c.frame = 3;
    c.sceneFingerprint = 42;
    c.state.globules = blob();
    c.state.time = 0.08;
    c.state.steps = 80;
    c.state.nextId = 120;
    c.state.emitted = {120};
    return c;
}

TEST_F(DamagedFiles, CheckpointAnyFlippedBitIsRefused) {
    const fs::path file = path("state.bin");
    writeCheckpoint(file, smallCheckpoint());
    const std::string original = readFileBytes(file, 1 << 30);
    EXPECT_EQ(readCheckpoint(file).frame, 3);
    for (std::size_t i = 0; i < original.size(); i += 7) {
        std::string bytes = original;
        bytes[i] = char(bytes[i] ^ (1 << (i % 8)));
        writeBytes(file, bytes);
        EXPECT_THROW(readCheckpoint(file), IoError) << "bit flipped in byte " << i;
    }
}

TEST_F(DamagedFiles, CheckpointFieldsAreValidatedBehindAGoodChecksum) {
    const fs::path file = path("state.bin");
    const auto refused = [&](Checkpoint c, const std::string& why) {
        writeCheckpoint(file, c);  // a correct checksum over bad values
        try {
            readCheckpoint(file);
            ADD_FAILURE() << "accepted a checkpoint with " << why;
        } catch (const IoError& e) {
            EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos);
        }
    };
    Checkpoint c = smallCheckpoint();
    c.frame = -2;
    refused(c, "a negative frame");
    c = smallCheckpoint();
    c.state.time = std::nan("");
    refused(c, "a non-finite time");
    c = smallCheckpoint();
    c.state.globules.vx[7] = INFINITY;
    refused(c, "a non-finite velocity");
    c = smallCheckpoint();
    c.state.globules.radius[3] = -1;
    refused(c, "a negative radius");
    c = smallCheckpoint();
    c.state.nextId = 5;
    refused(c, "ids beyond the next id");
    c = smallCheckpoint();
    c.state.emitted = {3};
    refused(c, "emitter counts that do not add up");
    c = smallCheckpoint();
    c.state.emitted = {std::size_t(-1), 121};  // wraps around to 120
    refused(c, "emitter counts that wrap around");
    c = smallCheckpoint();
    c.state.globules.id[9] = c.state.globules.id[8];
    refused(c, "a duplicate id");
}

TEST(ParseInChild, ACrashIsAnErrorNamingTheFile) {
    try {
        parseInChild("/data/frame.vdb", []() -> std::string {
            std::raise(SIGSEGV);
            return "";
        });
        ADD_FAILURE() << "no error";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("/data/frame.vdb"), std::string::npos) << e.what();
        // "crashed (SIGSEGV)"; under AddressSanitizer, which reports the fault and exits,
        // "failed (exit status 1)".
        EXPECT_NE(std::string(e.what()).find("the file is damaged: its reader"),
                  std::string::npos)
            << e.what();
    }
}

TEST(ParseInChild, AHangIsStoppedAtItsTimeLimit) {
    const auto start = std::chrono::steady_clock::now();
    ChildLimits limits;
    limits.seconds = 1;
    try {
        parseInChild("/data/frame.vdb", []() -> std::string {
            for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
        }, limits);
        ADD_FAILURE() << "no error";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("longer than 1 s"), std::string::npos) << e.what();
    }
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

TEST(ParseInChild, ExceptionsAndAnswersCrossTheBoundary) {
    EXPECT_EQ(parseInChild("x", [] { return std::string("a\0b", 3); }), std::string("a\0b", 3));
    try {
        parseInChild("x", []() -> std::string { throw std::runtime_error("bad header"); });
        ADD_FAILURE() << "no error";
    } catch (const IoError& e) {
        EXPECT_STREQ(e.what(), "cannot read x: bad header");
    }
    // A large answer is read while the child writes it (a pipe holds 64 KiB).
    EXPECT_EQ(parseInChild("x", [] { return std::string(5 << 20, 'g'); }).size(), 5u << 20);
}

/// The parent of the process that runs the parse.
std::string readersParent(const fs::path&) { return std::to_string(::getppid()); }

/// The parent of process @p pid, from /proc.
pid_t parentOf(pid_t pid) {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    for (std::string line; std::getline(status, line);) {
        if (line.rfind("PPid:", 0) == 0) return pid_t(std::stol(line.substr(5)));
    }
    return -1;
}

// The readers of damaged files are forked by one helper (a child of this process), not by
// this process, whose memory would then fault page by page (reader_helper.h).
TEST(ReaderHelper, OneHelperForksEveryReader) {
    const pid_t helper = pid_t(std::stol(parseInHelperChild("x", readersParent)));
    EXPECT_NE(helper, ::getpid());
    EXPECT_EQ(parentOf(helper), ::getpid());
    EXPECT_EQ(parseInHelperChild("y", readersParent), std::to_string(helper));
}

/// A way of reading a file in another process: parseInHelperChild or parseInWarmReader.
using Reader = std::string (*)(const fs::path&, PathParser);

/// A parse that throws is parseInChild's error.
void expectTheParsersError(Reader read) {
    try {
        read("x", [](const fs::path&) -> std::string { throw std::runtime_error("bad header"); });
        ADD_FAILURE() << "no error";
    } catch (const IoError& e) {
        EXPECT_STREQ(e.what(), "cannot read x: bad header");
    }
}

/// A parse that crashes is an error naming the file.
void expectACrashNamingTheFile(Reader read) {
    try {
        read("/data/frame.vdb", [](const fs::path&) -> std::string {
            std::raise(SIGSEGV);
            return "";
        });
        ADD_FAILURE() << "no error";
    } catch (const IoError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("cannot read /data/frame.vdb: the file is damaged: its reader", 0), 0u)
            << e.what();
    }
}

TEST(ReaderHelper, AnswersAndErrorsAreParseInChilds) {
    EXPECT_EQ(parseInHelperChild("x", [](const fs::path&) { return std::string("a\0b", 3); }),
              std::string("a\0b", 3));
    EXPECT_EQ(parseInHelperChild("x", [](const fs::path&) { return std::string(5 << 20, 'g'); })
                  .size(),
              5u << 20);
    expectTheParsersError(parseInHelperChild);
    expectACrashNamingTheFile(parseInHelperChild);
    // The helper survived its reader's crash.
    EXPECT_EQ(parseInHelperChild("x", [](const fs::path& p) { return p.string(); }), "x");
}

// A helper that is gone (killed, say) costs nothing but a fork: the next read forks its
// reader here, the one after starts a new helper.
TEST(ReaderHelper, AKilledHelperIsBypassedThenReplaced) {
    const pid_t helper = pid_t(std::stol(parseInHelperChild("x", readersParent)));
    ASSERT_EQ(::kill(helper, SIGKILL), 0);
    EXPECT_EQ(parseInHelperChild("x", readersParent), std::to_string(::getpid()));
    const pid_t next = pid_t(std::stol(parseInHelperChild("x", readersParent)));
    EXPECT_NE(next, helper);
    EXPECT_NE(next, ::getpid());
    EXPECT_EQ(parentOf(next), ::getpid());
}

/// This process's id and how many files it has parsed, this one included.
std::string parsesInThisProcess(const fs::path&) {
    static int count = 0;
    return std::to_string(::getpid()) + " " + std::to_string(++count);
}

struct Parses {
    pid_t pid = 0;
    int count = 0;
};

Parses warmParses() {
    std::istringstream answer(parseInWarmReader("x", parsesInThisProcess));
    Parses p;
    answer >> p.pid >> p.count;
    return p;
}

// The warm reader is one process, a child of the helper, that reads file after file
// (reader_helper.h): its memory is already mapped, where a process forked for each file
// faults on every page it touches.
TEST(WarmReader, OneProcessReadsFileAfterFile) {
    const pid_t helper = pid_t(std::stol(parseInHelperChild("x", readersParent)));
    const Parses first = warmParses(), second = warmParses();
    EXPECT_NE(first.pid, ::getpid());
    EXPECT_EQ(second.pid, first.pid);
    EXPECT_EQ(second.count, first.count + 1);
    EXPECT_EQ(parentOf(first.pid), helper);
}

// Whatever the warm reader fails on is read again by a reader forked for it, whose answer
// or error counts, and the warm reader is not used again: the next one has read nothing.
TEST(WarmReader, AFailedReadIsAnsweredByAFreshReaderAndEndsTheWarmOne) {
    const Reader warm = [](const fs::path& path, PathParser parse) {
        return parseInWarmReader(path, parse);
    };
    const Parses before = warmParses();
    expectTheParsersError(warm);
    const Parses after = warmParses();
    EXPECT_NE(after.pid, before.pid);
    EXPECT_EQ(after.count, 1);
    expectACrashNamingTheFile(warm);
    const Parses last = warmParses();
    EXPECT_NE(last.pid, after.pid);
    EXPECT_EQ(last.count, 1);
}

/// Hangs where @p marker does not exist yet, after creating it; answers where it does.
std::string hangOnce(const fs::path& marker) {
    if (!fs::exists(marker)) {
        std::ofstream(marker) << "hung";
        for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
    }
    return "answered";
}

TEST(WarmReader, AHungReadIsStoppedAtItsLimitAndReadAgain) {
    const fs::path marker = fs::temp_directory_path() /
                            ("globular_warm_hang_" + std::to_string(::getpid()));
    fs::remove(marker);
    const Parses before = warmParses();
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(parseInWarmReader(marker, hangOnce, 1.0), "answered");
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
    EXPECT_TRUE(fs::exists(marker));  // the warm reader did hang on it
    fs::remove(marker);
    EXPECT_NE(warmParses().pid, before.pid);
}

/// Where an allocation escapes to, so that the compiler keeps it.
void* volatile gReservation = nullptr;

/// Asks for @p bytes of address space without touching them.
std::string reserve(std::size_t bytes) {
    const std::unique_ptr<char[]> reserved(new char[bytes]);
    gReservation = reserved.get();
    return "reserved";
}

std::string reserveAGibibyte(const fs::path&) { return reserve(std::size_t(1) << 30); }
std::string reserve200Mebibytes(const fs::path&) { return reserve(std::size_t(200) << 20); }

// Each read may take what a forked reader may (256 MiB for a file this small) and no
// more, however many reads came before it.
TEST(WarmReader, EachReadHasTheForkedReadersMemoryLimit) {
    if (!addressSpaceCanBeLimited()) GTEST_SKIP() << "no memory limit under AddressSanitizer";
    for (int k = 0; k < 3; ++k) EXPECT_EQ(parseInWarmReader("x", reserve200Mebibytes), "reserved");
    try {
        parseInWarmReader("x", reserveAGibibyte);
        ADD_FAILURE() << "no error";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("more than 256 MiB"), std::string::npos)
            << e.what();
    }
}

/// A library's lock, which the parse below takes.
std::mutex gLibraryLock;

std::string parseTakingTheLibraryLock(const fs::path&) {
    std::lock_guard lock(gLibraryLock);
    return "read";
}

// A lock that another thread holds when a reader is asked (ASan's allocator, which has no
// fork handler, in the surface stage's worker threads) does not reach the reader: the
// helper started before that thread took it has its own copy, free. Started only now, the
// helper would copy it held, and the reader would hang until its time limit (twice).
TEST(ReaderHelper, StartedFirstItHoldsNoLockTakenLater) {
    startReaderHelper();
    std::latch locked(1), release(1);
    std::thread holder([&] {
        std::lock_guard lock(gLibraryLock);
        locked.count_down();
        release.wait();
    });
    locked.wait();
    const auto start = std::chrono::steady_clock::now();
    std::string answer;
    EXPECT_NO_THROW(answer = parseInHelperChild("x", parseTakingTheLibraryLock));
    release.count_down();
    holder.join();
    EXPECT_EQ(answer, "read");
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

}  // namespace
}  // namespace globular
