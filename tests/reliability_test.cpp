// End to end, the classes of failure of issue 11: damaged inputs, a full disk, crafted
// meshes, requests beyond the machine, derived limits, the checkpoint, a crowded output
// folder, the resolved scene, errors that name the right thing, nonsense input and
// temporaries. Each runs the built executable as a user or a farm would.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "cli_runner.h"
#include "errors.h"
#include "globule_cache.h"
#include "mesh.h"
#include "surface_grids.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

// 40 globules, 4 frames, a small image: every stage in well under a second.
const char* kSmallScene = R"([simulation]
frames = 4

[[emitter]]
type = "helix"
count = 40

[render]
width = 96
height = 64
)";

// A cap on the address space, so that taking the memory ends in bad_alloc instead of a
// refusal with numbers. AddressSanitizer reserves terabytes of shadow: no cap under it.
#ifdef GLOBULAR_SANITIZED
const char* kAddressSpaceCap = "";
#else
const char* kAddressSpaceCap = "ulimit -v 4000000;";
#endif

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

class Reliability : public CliTest {
protected:
    /// Simulates the small scene into mDir/out; @return the scene's path.
    fs::path simulateSmall(const std::string& stages = "sim") {
        const fs::path scene = writeScene("small.toml", kSmallScene);
        const RunResult r = run("run small.toml --out out -q --stages " + stages);
        EXPECT_EQ(r.status, 0) << r.err;
        return scene;
    }
    fs::path out() const { return mDir / "out"; }

    /// Every file under a final name in @p folder reads back whole.
    void expectIntactFiles(const fs::path& folder) {
        std::error_code ec;
        for (const auto& entry : fs::directory_iterator(folder, ec)) {
            const fs::path p = entry.path();
            const std::string name = p.filename().string();
            if (name.starts_with(".")) continue;  // a temporary: never a final name
            if (p.extension() == ".vdb" && name.starts_with("surface")) {
                EXPECT_NO_THROW(readSurfaceVdb(p)) << p;
            } else if (p.extension() == ".vdb") {
                EXPECT_NO_THROW(readGlobuleVdb(p)) << p;
            } else if (p.extension() == ".ply" && name.starts_with("surface")) {
                EXPECT_NO_THROW(readMeshPly(p)) << p;
            } else if (p.extension() == ".ply") {
                EXPECT_NO_THROW(readGlobulePly(p)) << p;
            }
        }
    }
};

// 1. A damaged cache is an error naming it, in the surface and the render stage.
TEST_F(Reliability, DamagedCacheIsAnErrorInEveryStage) {
    simulateSmall();
    const fs::path cache = out() / "cache/globules.0002.vdb";
    fs::copy_file(fs::path(GLOBULAR_SOURCE_DIR) / "tests/data/damaged/cache_page_size_zero.vdb",
                  cache, fs::copy_options::overwrite_existing);
    for (const char* stage : {"surface", "render"}) {
        const RunResult r = run(std::string("run small.toml --out out -q --stages ") + stage);
        EXPECT_EQ(r.status, 1) << stage << ": " << r.err;
        EXPECT_TRUE(contains(r.err, "cannot read out/cache/globules.0002.vdb")) << r.err;
        EXPECT_TRUE(contains(r.err, "crashed")) << r.err;
    }
}

// 2. A write that the disk refuses: an error naming the file, never a partial file under
// a final name. RLIMIT_FSIZE fails write() like a full disk (EFBIG) without root.
TEST_F(Reliability, FileSizeLimitDuringSurfacingLeavesNoPartialFile) {
    simulateSmall();
    const RunResult r = run("run small.toml --out out -q --stages surface",
                            "trap '' XFSZ; ulimit -f 150;");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_TRUE(contains(r.err, "cannot write out/")) << r.err;
    EXPECT_TRUE(contains(r.err, "File too large")) << r.err;
    expectIntactFiles(out() / "surface");
    expectIntactFiles(out() / "mesh");
}

TEST_F(Reliability, FileSizeLimitDuringSimulationNamesTheFile) {
    writeScene("small.toml", kSmallScene);
    const RunResult r = run("run small.toml --out out -q --stages sim --set emitter.0.count=3000",
                            "trap '' XFSZ; ulimit -f 100;");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_TRUE(contains(r.err, "cannot write out/")) << r.err;
    EXPECT_TRUE(contains(r.err, "File too large")) << r.err;
    EXPECT_FALSE(contains(r.err, "corrupt")) << r.err;
    expectIntactFiles(out() / "cache");
}

// The same on a real full disk: a small tmpfs (needs root and mount; skipped otherwise).
TEST_F(Reliability, FullDiskDuringSurfacingLeavesNoPartialFile) {
    simulateSmall();
    const fs::path disk = mDir / "disk";
    fs::create_directories(disk);
    if (::mount("tmpfs", disk.c_str(), "tmpfs", 0, "size=400k") != 0) {
        GTEST_SKIP() << "cannot mount a tmpfs here: " << std::strerror(errno);
    }
    fs::create_directories(disk / "out");
    fs::copy(out() / "cache", disk / "out/cache");
    const RunResult r = run("run small.toml --out disk/out -q --stages surface");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_TRUE(contains(r.err, "No space left on device")) << r.err;
    expectIntactFiles(disk / "out/surface");
    expectIntactFiles(disk / "out/mesh");
    ::umount(disk.c_str());
}

// 3. A crafted mesh makes the render stage fail at once instead of hanging.
TEST_F(Reliability, CraftedMeshDoesNotHangTheRenderStage) {
    simulateSmall("sim,surface");
    std::ofstream(out() / "mesh/surface.0002.ply", std::ios::binary)
        << "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
           "property float y\nproperty float z\nelement junk 18446744073709551615\n"
           "end_header\n" << std::string(12, '\0');
    const auto start = std::chrono::steady_clock::now();
    const RunResult r = run("run small.toml --out out -q --stages render --set render.mode=surface");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_TRUE(contains(r.err, "surface.0002.ply")) << r.err;
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
}

// 4. Requests beyond the machine are refused before the memory is taken.
TEST_F(Reliability, MemoryIsRefusedUpFront) {
    simulateSmall();
    std::string fiveBoxes = "[simulation]\nframes = 2\n";
    for (int k = 0; k < 5; ++k) {
        fiveBoxes += "[[emitter]]\ntype = \"box\"\ncount = 90000000\nmin = [-500, 0, -500]\n"
                     "max = [500, 500, 500]\nspacing = 1\n";
    }
    writeScene("boxes.toml", fiveBoxes);
    const struct {
        std::string args, expected;
    } cases[] = {
        {"run boxes.toml --out boxes -q", "the scene's emitters make 450000000 globules"},
        {"run small.toml --out out -q --stages surface --set surface.voxel_size=1e-4",
         "cannot surface frame 1"},
        {"run small.toml --out out -q --stages render --set render.width=16384 "
         "--set render.height=16384 --set render.samples=16",
         "cannot render the image"},
    };
    for (const auto& c : cases) {
        const auto start = std::chrono::steady_clock::now();
        const RunResult r = run(c.args, kAddressSpaceCap);
        EXPECT_EQ(r.status, 1) << c.args << ": " << r.err;
        EXPECT_TRUE(contains(r.err, c.expected)) << r.err;
        EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
    }
}

TEST_F(Reliability, GlobulesOfVeryDifferentRadiiAreRefusedUpFront) {
    writeScene("radii.toml", "[simulation]\nframes = 2\n[[emitter]]\ntype = \"helix\"\n"
                             "count = 20\n[[emitter]]\ntype = \"helix\"\ncount = 1\n"
                             "radius = 200\ncenter = [0, 500, 0]\n");
    ASSERT_EQ(run("run radii.toml --out out -q --stages sim").status, 0);
    const RunResult r = run("run radii.toml --out out -q --stages surface", kAddressSpaceCap);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_TRUE(contains(r.err, "cannot surface frame 1")) << r.err;
}

// 6. A damaged checkpoint is refused, and no frame is rewritten.
TEST_F(Reliability, DamagedCheckpointIsRefusedAndFramesStay) {
    simulateSmall();
    const std::string frame3 = readFile(out() / "cache/globules.0003.vdb");
    std::string state = readFile(out() / "state.bin");
    state[state.size() / 2] = char(state[state.size() / 2] ^ 4);
    std::ofstream(out() / "state.bin", std::ios::binary) << state;
    const RunResult r = run("run small.toml --out out -q --stages sim --resume "
                            "--set simulation.frames=6");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_TRUE(contains(r.err, "checksum")) << r.err;
    EXPECT_EQ(readFile(out() / "cache/globules.0003.vdb"), frame3);
    EXPECT_FALSE(fs::exists(out() / "cache/globules.0005.vdb"));
}

TEST_F(Reliability, ResumeNeverRewritesFramesBeforeTheCheckpoint) {
    simulateSmall();
    std::string before[5];
    for (int f = 1; f <= 4; ++f) before[f] = readFile(out() / ("cache/globules.000" + std::to_string(f) + ".vdb"));
    // frames = 4 is part of the scene's fingerprint: resume the same scene, nothing to do.
    const RunResult r = run("run small.toml --out out -q --stages sim --resume");
    EXPECT_EQ(r.status, 0) << r.err;
    for (int f = 1; f <= 4; ++f) {
        // Each cache carries a fresh UUID: unchanged bytes mean it was not rewritten.
        EXPECT_EQ(readFile(out() / ("cache/globules.000" + std::to_string(f) + ".vdb")), before[f]);
    }
}

// 7. Two runs into one folder: the second fails at once, naming the first.
TEST_F(Reliability, SecondRunIntoABusyFolderFailsNamingTheFirst) {
    writeScene("small.toml", kSmallScene);
    writeScene("long.toml", "[simulation]\nframes = 400\n[[emitter]]\ntype = \"helix\"\n"
                            "count = 3000\n");
    const pid_t first = fork();
    if (first == 0) {
        ::chdir(mDir.c_str());
        ::execl(kBinary, kBinary, "run", "long.toml", "--out", "out", "--stages", "sim", "-q",
                static_cast<char*>(nullptr));
        ::_exit(127);
    }
    // The first run holds the folder once it writes its second frame.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!fs::exists(out() / "cache/globules.0002.vdb") &&
           std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    const RunResult sim = run("run small.toml --out out -q");
    const RunResult render = run("run small.toml --out out -q --stages render");
    ::kill(first, SIGKILL);
    ::waitpid(first, nullptr, 0);
    for (const RunResult& r : {sim, render}) {
        EXPECT_EQ(r.status, 1) << r.err;
        EXPECT_TRUE(contains(r.err, "output folder out is in use by process " +
                                        std::to_string(first)))
            << r.err;
        EXPECT_TRUE(contains(r.err, "long.toml")) << r.err;
    }
    // Once the first run is gone (killed, even), the folder is free again.
    EXPECT_EQ(run("run small.toml --out out -q --stages sim").status, 0);
}

// 8. The resolved scene re-runs from any working directory.
TEST_F(Reliability, ResolvedSceneRerunsFromAnywhere) {
    fs::create_directories(mDir / "shots/points");
    std::ofstream(mDir / "shots/points/cloud.ply")
        << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
           "property float z\nend_header\n0 1 0\n0 2.2 0\n0 3.4 0\n";
    writeScene("shots/pour\nnight.toml", "[simulation]\nframes = 3\n[[emitter]]\n"
                                         "type = \"points\"\nfile = \"points/cloud.ply\"\n");
    ASSERT_EQ(run("run " + quote("shots/pour\nnight.toml") + " --out a -q --stages sim").status, 0);
    fs::create_directories(mDir / "elsewhere");
    const RunResult again = run("run ../a/scene.toml --out ../b -q --stages sim", "cd elsewhere &&");
    ASSERT_EQ(again.status, 0) << again.err;
    EXPECT_EQ(readFile(mDir / "a/stats.csv"), readFile(mDir / "b/stats.csv"));
}

// 9. Errors name the key, file or option that is wrong.
TEST_F(Reliability, ErrorsNameWhatIsWrong) {
    writeScene("small.toml", kSmallScene);
    std::ofstream(mDir / "nan.ply") << "ply\nformat ascii 1.0\nelement vertex 1\n"
                                       "property float x\nproperty float y\nproperty float z\n"
                                       "property float vx\nend_header\n0 1 0 nan\n";
    writeScene("nan.toml", "[[emitter]]\ntype = \"points\"\nfile = \"nan.ply\"\n");
    const struct {
        std::string args;
        int status;
        std::string expected;
    } cases[] = {
        {"--set material.r0=1e30", 2, "key 'r0'"},
        {"--set material.r0=1e-30", 2, "key 'r0'"},
        {"--set material.cd=1e-9 --set material.cr=1e-9 --set material.preset=custom", 2,
         "key 'radius'"},
        {"--set emitter.0.radius=1e-9", 2, "key 'radius'"},
        {"--set emitter.0.center=[1e308,0,0]", 2, "center"},
        {"--set emitter.0.jitter=1e308", 2, "jitter"},
        {"--frames 99999999999999999999", 2, "--frames 99999999999999999999: must lie within"},
        {"--set material.b1=1 --set material.b1=x", 2, "--set material.b1=x"},
    };
    for (const auto& c : cases) {
        const RunResult r = run("run small.toml --out out -q --stages sim " + c.args);
        EXPECT_EQ(r.status, c.status) << c.args << ": " << r.err;
        EXPECT_TRUE(contains(r.err, c.expected)) << c.args << ": " << r.err;
        EXPECT_FALSE(contains(r.err, "neighbour grid")) << r.err;
    }
    const RunResult nan = run("run nan.toml --out out2 -q --stages sim");
    EXPECT_EQ(nan.status, 1) << nan.err;
    EXPECT_TRUE(contains(nan.err, "nan.ply: vertex 0 (line 9) has a non-finite velocity")) << nan.err;
}

// 10. Nonsense is refused with a non-zero exit, and a bad value is quoted briefly.
TEST_F(Reliability, NonsenseIsRefused) {
    writeScene("small.toml", kSmallScene);
    std::ofstream(mDir / "neg.ply") << "ply\nformat ascii 1.0\nelement vertex 1\n"
                                       "property float x\nproperty float y\nproperty float z\n"
                                       "property float radius\nend_header\n0 1 0 -1\n";
    writeScene("neg.toml", "[[emitter]]\ntype = \"points\"\nfile = \"neg.ply\"\n");
    const struct {
        std::string args;
        int status;
        std::string expected;
    } cases[] = {
        {"run . --out out -q", 2, "is a directory"},
        {"run /dev/zero --out out -q", 2, "larger than 4 MiB"},
        {"run missing.toml --out out -q", 2, "no scene file missing.toml"},
        {"run small.toml --out out -q --set " + quote("render.mode=surface\n[render]\nwidth=9"), 2,
         "one line"},
        {"run neg.toml --out out -q", 1, "radius -1"},
        {"run small.toml --out out -q --set " + quote("emitter.0.file=\"a\\u0000b.ply\""), 2,
         "control character"},
    };
    for (const auto& c : cases) {
        const RunResult r = run(c.args);
        EXPECT_EQ(r.status, c.status) << c.args << ": " << r.err;
        EXPECT_TRUE(contains(r.err, c.expected)) << c.args << ": " << r.err;
    }
    const RunResult longValue =
        run("run small.toml --out out -q --set render.mode=" + std::string(100000, 'x'));
    EXPECT_EQ(longValue.status, 2);
    EXPECT_LT(longValue.err.size(), 1000u) << longValue.err.substr(0, 2000);
}

// 11. Every stage sweeps the temporaries its killed predecessor left, and only those.
TEST_F(Reliability, StagesSweepOnlyOurOwnTemporaries) {
    simulateSmall();
    char host[256] = {};
    ::gethostname(host, sizeof host - 1);
    // A process id that is surely not running: a child that has exited.
    const pid_t dead = fork();
    if (dead == 0) ::_exit(0);
    ::waitpid(dead, nullptr, 0);
    const std::string ours = ".globules.0002.vdb.globular-tmp-" + std::string(host) + "-" +
                             std::to_string(dead) + "-7";
    const std::string otherHost = ".globules.0002.vdb.globular-tmp-node17-" + std::to_string(dead) + "-7";
    const std::string lookalike = ".notes.tmp" + std::to_string(dead) + "_1";
    for (const char* stage : {"surface", "render"}) {
        for (const std::string& name : {ours, otherHost, lookalike}) {
            std::ofstream(out() / "cache" / name) << "x";
        }
        const RunResult r = run(std::string("run small.toml --out out --stages ") + stage);
        EXPECT_EQ(r.status, 0) << r.err;
        EXPECT_TRUE(contains(r.err, "removed 1 temporary files")) << r.err;
        EXPECT_FALSE(fs::exists(out() / "cache" / ours)) << stage;
        EXPECT_TRUE(fs::exists(out() / "cache" / otherHost)) << stage;
        EXPECT_TRUE(fs::exists(out() / "cache" / lookalike)) << stage;
    }
}

}  // namespace
}  // namespace globular
