#pragma once
// The Slurm batch scripts of `globular farm`: pure text from the shot's settings, so they
// are tested without Slurm. One shot is five steps, each a `globular run` of the same
// scene and overrides into the same folder:
//   sim      one job                         --stages sim --resume
//   surface  an array, a task per chunk      --stages surface --frames A-B   afterok:sim
//   plan     one job                         --stages plan   afterok:sim (spheres) or
//                                                            afterok:surface (surface mode)
//   render   an array, a task per chunk      --stages render --frames A-B
//                                            aftercorr:surface,afterok:plan
//   finish   one job: contact sheet, movie   --stages finish  afterok:render
// Every step writes atomically and skips nothing it has not checked, so a requeued or
// repeated task is safe.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace globular {

struct FarmSettings {
    std::filesystem::path program;   ///< the globular executable the jobs run (absolute)
    std::filesystem::path scene;     ///< the scene file (absolute)
    std::filesystem::path outDir;    ///< DIR (absolute)
    std::vector<std::string> overrides;  ///< --set KEY=VALUE, as given to `run`
    int frames = 1;                  ///< [simulation] frames
    int chunk = 10;                  ///< frames per array task
    int maxRunning = 0;              ///< array throttle %N; 0: none
    std::string partition;           ///< --partition; empty: the cluster's default
    std::string account;             ///< --account; empty: the user's default
    std::string timeLimit;           ///< --time; empty: the partition's default
    bool planAfterSurface = false;   ///< [render] mode = surface: the plan measures meshes

    /// @throw SceneError naming the option (chunk or max-running below 1, ...).
    void validate() const;
};

inline const std::vector<std::string> kFarmSteps = {"sim", "surface", "plan", "render",
                                                    "finish"};

/// Array task k renders frames [first, last] of the chunk: k * chunk + 1 onwards.
std::vector<std::pair<int, int>> farmChunks(int frames, int chunk);

/// "0-4" for 5 chunks, or "1,3" for a resubmission of tasks 1 and 3; with the throttle.
std::string farmArraySpec(const FarmSettings& settings, const std::vector<int>& tasks);

/// The batch script of @p step (kFarmSteps). @p dependency is Slurm's --dependency value
/// ("" for none); @p tasks the array's task indices (surface and render; empty: all).
std::string farmScript(const FarmSettings& settings, const std::string& step,
                       const std::string& dependency, const std::vector<int>& tasks = {});

/// The dependency of @p step on the job ids of the steps before it (each "" when that
/// step is not submitted this time), in the order of kFarmSteps.
std::string farmDependency(const FarmSettings& settings, const std::string& step,
                           const std::vector<std::string>& ids);

/// DIR/farm, where the scripts, logs and the record of submitted jobs live.
std::filesystem::path farmDir(const std::filesystem::path& outDir);

/// @p text quoted for a POSIX shell.
std::string shellQuote(const std::string& text);

}  // namespace globular
