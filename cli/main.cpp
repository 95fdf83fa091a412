// The `globular` command: parse options, run, and turn errors into messages and exit
// codes (0 success, 1 a run failed, 2 bad usage or a bad scene).

#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>

#include "console_reporter.h"
#include "errors.h"
#include "farm_command.h"
#include "figures_command.h"
#include "globular_version.h"
#include "memory_allocator.h"
#include "reader_helper.h"
#include "run_command.h"
#include "scene.h"

namespace {

constexpr int kRunFailed = 1;
constexpr int kBadInput = 2;

/// One line on stderr, whatever bytes a damaged input put into the message.
void printError(const std::string& message) {
    std::fprintf(stderr, "error: %s\n", globular::quoteForMessage(message, 4000).c_str());
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"globular: viscous fluid, powder and soft solids with globular dynamics "
                 "(Miller & Pearce 1989), from scene file to caches, VDB surfaces and frames"};
    app.set_version_flag("--version", std::string("globular ") + GLOBULAR_VERSION +
                                          "\nmemory: " + globular::memoryAllocator());
    app.require_subcommand(1);

    globular::RunOptions run;
    bool quiet = false;
    std::string stages = "sim,surface,render";
    CLI::App* runCmd = app.add_subcommand("run", "simulate, surface and render a scene");
    runCmd->add_option("scene", run.scene, "scene file (TOML); omitted: the default scene");
    runCmd->add_option("--out,-o", run.outDir, "output directory (default out/<scene name>)");
    runCmd->add_option("--stages", stages,
                       "comma-separated stages: sim,surface,render; also plan (the render "
                       "plan alone) and finish (contact sheet and movie alone)")
        ->capture_default_str();
    runCmd->add_option("--frames", run.frames, "frame range A-B for surface and render");
    runCmd->add_option("--threads", run.threads, "worker threads (0 = all cores)")
        ->capture_default_str();
    runCmd->add_option("--set", run.overrides, "override a scene key: --set material.b1=3");
    runCmd->add_flag("--resume", run.resume, "continue an interrupted run in --out");
    runCmd->add_flag("--quiet,-q", quiet, "only warnings and errors");

    globular::FiguresOptions figures;
    CLI::App* figuresCmd = app.add_subcommand(
        "figures", "regenerate the paper's figures and tables into DIR/REPRODUCTION.md");
    figuresCmd->add_option("--out,-o", figures.outDir, "output directory")->capture_default_str();
    figuresCmd->add_option("--scale", figures.scale,
                           "(0, 1]: shrink globule counts, frames and pixels (tests)")
        ->capture_default_str();
    figuresCmd->add_option("--threads", figures.threads, "worker threads (0 = all cores)")
        ->capture_default_str();
    figuresCmd->add_option("--scenes", figures.scenesDir,
                           "the paper's scenes (default scenes/paper, here or in the source)");
    figuresCmd->add_flag("--quiet,-q", quiet, "only warnings and errors");

    globular::FarmOptions farm;
    std::string farmStatus, farmResubmit;
    CLI::App* farmCmd = app.add_subcommand(
        "farm", "send a shot to a Slurm cluster: batch scripts for the simulation, surface and "
                "render arrays over frame chunks, the render plan and the contact sheet and movie "
                "(README, Rendering on a farm)");
    farmCmd->add_option("scene", farm.scene, "scene file (TOML)");
    farmCmd->add_option("--out,-o", farm.outDir, "output directory, on storage every node sees");
    farmCmd->add_option("--set", farm.overrides, "override a scene key, as for run");
    farmCmd->add_option("--chunk", farm.chunk, "frames per array task")->capture_default_str();
    farmCmd->add_option("--max-running", farm.maxRunning,
                        "array tasks running at once (Slurm's %N throttle; 0 = no limit)")
        ->capture_default_str();
    farmCmd->add_option("--partition", farm.partition, "Slurm partition (sbatch --partition)");
    farmCmd->add_option("--account", farm.account, "Slurm account (sbatch --account)");
    farmCmd->add_option("--time", farm.timeLimit, "time limit of each job (sbatch --time)");
    farmCmd->add_flag("--dry-run", farm.dryRun, "print the batch scripts; submit nothing");
    farmCmd->add_option("--status", farmStatus,
                        "report DIR's progress from its files, squeue and sacct");
    farmCmd->add_option("--resubmit", farmResubmit,
                        "resubmit the chunks of DIR that failed or are missing");
    farmCmd->add_flag("--quiet,-q", quiet, "only warnings and errors");

    CLI::App* keysCmd = app.add_subcommand(
        "keys", "print every scene key with its default and meaning (Markdown)");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : kBadInput;
    }

    // Before any thread of ours starts: the readers of cache and surface files are then
    // forked from a copy that holds no other thread's lock (reader_helper.h).
    if (!keysCmd->parsed()) globular::startReaderHelper();

    globular::ConsoleReporter reporter(stderr, quiet);
    try {
        if (keysCmd->parsed()) std::fputs(globular::sceneKeysMarkdown().c_str(), stdout);
        if (figuresCmd->parsed()) globular::runFigures(figures, reporter);
        if (farmCmd->parsed()) {
            farm.status = !farmStatus.empty();
            farm.resubmit = !farmResubmit.empty();
            if (farm.status || farm.resubmit) {
                if (!farm.outDir.empty()) {
                    throw globular::SceneError("farm: --status and --resubmit take DIR, not --out");
                }
                farm.outDir = farm.status ? farmStatus : farmResubmit;
            }
            globular::runFarm(farm, reporter);
        }
        if (runCmd->parsed()) {
            run.stages.clear();
            std::stringstream list(stages);
            for (std::string s; std::getline(list, s, ',');) {
                if (!s.empty()) run.stages.push_back(s);
            }
            globular::runScene(run, reporter);
        }
    } catch (const globular::SceneError& e) {
        printError(e.what());
        return kBadInput;
    } catch (const std::exception& e) {
        printError(e.what());
        return kRunFailed;
    }
    return 0;
}
