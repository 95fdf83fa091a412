#pragma once
// Runs the built `globular` executable for end-to-end tests: each test gets its own
// temporary folder (kept when the test fails), and run() captures the exit status,
// stdout and stderr.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace globular {

inline const char* kBinary = GLOBULAR_EXECUTABLE;  // build/globular (tests/CMakeLists.txt)

struct RunResult {
    int status = -1;  ///< exit status; -1 when killed by a signal
    std::string out, err;
};

inline std::string readFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

/// @p text quoted for sh.
inline std::string quote(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

class CliTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        mDir = std::filesystem::temp_directory_path() /
               ("globular_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
                std::to_string(getpid()));
        std::filesystem::remove_all(mDir);
        std::filesystem::create_directories(mDir);
        ASSERT_TRUE(std::filesystem::exists(kBinary)) << kBinary << " is not built";
    }
    void TearDown() override {
        if (!HasFailure()) std::filesystem::remove_all(mDir);
    }

    /// Runs `globular ARGS` in mDir with stdin from /dev/null, capturing stdout and stderr.
    /// @p prefix goes before the command (shell settings such as a ulimit).
    RunResult run(const std::string& args, const std::string& prefix = "") {
        const std::filesystem::path out = mDir / "stdout.txt", err = mDir / "stderr.txt";
        const std::string command = "cd " + quote(mDir.string()) + " && " + prefix + " " +
                                    quote(kBinary) + " " + args + " </dev/null >" +
                                    quote(out.string()) + " 2>" + quote(err.string());
        const int raw = std::system(("/bin/bash -c " + quote(command)).c_str());
        RunResult result;
        if (raw != -1 && WIFEXITED(raw)) result.status = WEXITSTATUS(raw);
        result.out = readFile(out);
        result.err = readFile(err);
        return result;
    }

    std::filesystem::path writeScene(const std::string& name, const std::string& text) {
        const std::filesystem::path path = mDir / name;
        std::ofstream(path) << text;
        return path;
    }

    std::filesystem::path mDir;
};

}  // namespace globular
