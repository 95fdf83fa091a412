#pragma once
// `globular run`: load a scene, resolve it, and run the requested stages into DIR.

#include <filesystem>
#include <string>
#include <vector>

namespace globular {

class Reporter;

struct RunOptions {
    std::string scene;                ///< scene file; empty runs the built-in default
    std::filesystem::path outDir;     ///< empty: out/<scene name>
    std::vector<std::string> stages{"sim", "surface", "render"};
    std::string frames;               ///< "A-B" or "N"; empty = all
    int threads = 0;                  ///< 0 = all cores
    std::vector<std::string> overrides;  ///< --set KEY=VALUE
    bool resume = false;
};

/// The text of scenes/default.toml, built into the executable.
const char* defaultSceneText();

/// Runs the stages. @throw globular::Error subclasses with a message for the user.
void runScene(const RunOptions& options, Reporter& reporter);

}  // namespace globular
