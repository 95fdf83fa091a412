// Reliability of the sim stage under SIGKILL: a killed run resumed with --resume writes
// frames bit-identical to an uninterrupted run, and frames written before a failure stay.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "frame_paths.h"
#include "globule_cache.h"
#include "state_file.h"

namespace fs = std::filesystem;
using namespace globular;

namespace {

const char* kScene = R"(
[simulation]
frames = 60
[material]
preset = "liquid"
[[emitter]]
type = "helix"
count = 600
[[emitter]]
type = "spout"
count = 1500
center = [10.0, 12.0, 0.0]
nozzle_radius = 2.5
speed = 8.0
)";

fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::path(testing::TempDir()) / ("resume_test_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

fs::path writeScene(const fs::path& dir) {
    const fs::path scene = dir / "scene_in.toml";
    std::ofstream(scene) << kScene;
    return scene;
}

pid_t spawn(const std::vector<std::string>& args) {
    const pid_t pid = ::fork();
    if (pid == 0) {
        std::vector<char*> argv;
        for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    return pid;
}

int waitExit(pid_t pid) {
    int status = 0;
    ::waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

int run(const std::vector<std::string>& args) { return waitExit(spawn(args)); }

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void expectSameFrame(const fs::path& a, const fs::path& b, int frame) {
    const Globules ga = readGlobuleVdb(cacheVdbPath(a, frame));
    const Globules gb = readGlobuleVdb(cacheVdbPath(b, frame));
    ASSERT_EQ(ga.size(), gb.size()) << "frame " << frame;
    EXPECT_EQ(ga.px, gb.px) << "frame " << frame;
    EXPECT_EQ(ga.py, gb.py) << "frame " << frame;
    EXPECT_EQ(ga.vx, gb.vx) << "frame " << frame;
    EXPECT_EQ(ga.id, gb.id) << "frame " << frame;
}

}  // namespace

TEST(Resume, KilledRunResumesBitForBit) {
    const fs::path dir = freshDir("kill");
    const fs::path scene = writeScene(dir);
    const fs::path whole = dir / "whole", killed = dir / "killed";
    ASSERT_EQ(run({GLOBULAR_EXECUTABLE, "run", scene.string(), "--stages", "sim", "--out",
                   whole.string(), "--quiet"}),
              0);

    const pid_t pid = spawn({GLOBULAR_EXECUTABLE, "run", scene.string(), "--stages", "sim",
                             "--out", killed.string(), "--quiet"});
    // Kill it once a few frames are complete, in the middle of a later frame.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!fs::exists(cacheVdbPath(killed, 8)) && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ::kill(pid, SIGKILL);
    EXPECT_EQ(waitExit(pid), 128 + SIGKILL);
    const int lastComplete = readCheckpoint(killed / "state.bin").frame;
    ASSERT_LT(lastComplete, 60) << "the run finished before it could be killed";

    ASSERT_EQ(run({GLOBULAR_EXECUTABLE, "run", scene.string(), "--stages", "sim", "--out",
                   killed.string(), "--resume", "--quiet"}),
              0);
    for (int frame = 1; frame <= 60; ++frame) expectSameFrame(whole, killed, frame);
    EXPECT_EQ(readText(whole / "stats.csv"), readText(killed / "stats.csv"));
    // No temporary left behind under any name.
    for (const auto& entry : fs::recursive_directory_iterator(killed)) {
        EXPECT_EQ(entry.path().filename().string().find("globular-tmp"), std::string::npos)
            << entry.path();
    }
}

TEST(Resume, RefusesADifferentScene) {
    const fs::path dir = freshDir("other");
    const fs::path scene = writeScene(dir);
    ASSERT_EQ(run({GLOBULAR_EXECUTABLE, "run", scene.string(), "--stages", "sim", "--out",
                   (dir / "out").string(), "--set", "simulation.frames=3", "--quiet"}),
              0);
    EXPECT_NE(run({GLOBULAR_EXECUTABLE, "run", scene.string(), "--stages", "sim", "--out",
                   (dir / "out").string(), "--set", "simulation.frames=3", "--set",
                   "material.b1=3", "--resume", "--quiet"}),
              0);
}

TEST(Resume, ExplosionKeepsEarlierFramesAndExitsNonZero) {
    const fs::path dir = freshDir("explode");
    const fs::path scene = dir / "explode.toml";
    std::ofstream(scene) << "[simulation]\ndt = 0.01\nframes = 60\n[material]\npreset = "
                            "\"powder\"\n[[emitter]]\ncount = 200\n";
    EXPECT_EQ(run({GLOBULAR_EXECUTABLE, "run", scene.string(), "--stages", "sim", "--out",
                   (dir / "out").string(), "--quiet"}),
              1);
    const int last = readCheckpoint(dir / "out" / "state.bin").frame;
    EXPECT_GT(last, 1);
    EXPECT_LT(last, 60);
    for (int frame = 1; frame <= last; ++frame) {
        EXPECT_NO_THROW(readGlobuleVdb(cacheVdbPath(dir / "out", frame))) << frame;
    }
    EXPECT_FALSE(fs::exists(cacheVdbPath(dir / "out", last + 1)));
}

TEST(Resume, UnwritableOutputDirectoryIsAClearError) {
    const fs::path dir = freshDir("unwritable");
    const fs::path scene = writeScene(dir);
    // A regular file where the output directory should be: unwritable even for root.
    const fs::path blocker = dir / "blocker";
    std::ofstream(blocker) << "x";
    const std::string out = (blocker / "out").string();
    const std::string command = std::string(GLOBULAR_EXECUTABLE) + " run " + scene.string() +
                                " --stages sim --out " + out + " 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    std::string output;
    char buffer[256];
    while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
    const int status = ::pclose(pipe);
    EXPECT_EQ(WEXITSTATUS(status), 1);
    EXPECT_NE(output.find(out), std::string::npos) << output;
}

TEST(Resume, ReadOnlyOutputDirectoryIsAClearError) {
    if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
    const fs::path dir = freshDir("readonly");
    const fs::path scene = writeScene(dir);
    const fs::path out = dir / "out";
    fs::create_directories(out);
    fs::permissions(out, fs::perms::owner_read | fs::perms::owner_exec);
    EXPECT_EQ(run({GLOBULAR_EXECUTABLE, "run", scene.string(), "--stages", "sim", "--out",
                   out.string(), "--quiet"}),
              1);
    fs::permissions(out, fs::perms::owner_all);
    EXPECT_TRUE(fs::is_empty(out));
}
