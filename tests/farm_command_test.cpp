// `globular farm` talking to Slurm's commands: a missing or failing command is named in
// the error with what it answered. Fake commands on PATH stand in for Slurm.
#include "farm_command.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "errors.h"
#include "recording_reporter.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

/// PATH holds only @p dir while alive.
class PathOnly {
  public:
    explicit PathOnly(const fs::path& dir) : mOld(std::getenv("PATH") ? std::getenv("PATH") : "") {
        ::setenv("PATH", dir.c_str(), 1);
    }
    ~PathOnly() { ::setenv("PATH", mOld.c_str(), 1); }

  private:
    std::string mOld;
};

fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / "globular_farm_command_test" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void writeScript(const fs::path& path, const std::string& body) {
    std::ofstream(path) << "#!/bin/sh\n" << body << "\n";
    fs::permissions(path, fs::perms::owner_all);
}

TEST(FarmCommand, RunProgramReturnsStatusAndBothStreams) {
    const fs::path bin = freshDir("bin");
    writeScript(bin / "talk", "echo out; echo err >&2; exit 3");
    const PathOnly path(bin);
    const ProgramResult r = runProgram("talk", {});
    EXPECT_EQ(r.status, 3);
    EXPECT_EQ(r.out, "out\n");
    EXPECT_EQ(r.err, "err\n");
}

TEST(FarmCommand, AMissingCommandIsNamed) {
    const PathOnly path(freshDir("empty"));
    try {
        runProgram("sbatch", {"x"});
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("`sbatch` is not on PATH"), std::string::npos)
            << e.what();
    }
}

TEST(FarmCommand, AFailingCommandIsNamedWithItsAnswer) {
    const fs::path dir = freshDir("shot"), bin = freshDir("failing");
    fs::create_directories(dir / "farm");
    std::ofstream(dir / "farm" / "farm.toml")
        << "program = \"/bin/globular\"\nscene = \"/s.toml\"\nout = \"" << dir.string()
        << "\"\noverrides = []\nframes = 20\nchunk = 10\nmax_running = 0\npartition = \"\"\n"
           "account = \"\"\ntime = \"\"\nmesh_format = \"ply\"\n"
           "[[job]]\nstep = \"sim\"\nid = \"7\"\ntasks = []\n";
    writeScript(bin / "squeue", "echo 'squeue: error: Unable to contact slurm controller' >&2; exit 1");
    const PathOnly path(bin);
    RecordingReporter reporter;
    FarmOptions options;
    options.outDir = dir;
    options.resubmit = true;
    try {
        runFarm(options, reporter);
        FAIL();
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("`squeue --me --noheader '--format=%i|%j|%T|%r'` failed with exit "
                               "status 1: squeue: error: Unable to contact slurm controller"),
                  std::string::npos)
            << message;
    }
}

}  // namespace
}  // namespace globular
