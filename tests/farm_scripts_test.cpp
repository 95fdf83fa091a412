// `globular farm`'s batch scripts, without Slurm: the arrays, dependencies and frame
// ranges each carries.
#include "farm_scripts.h"

#include <gtest/gtest.h>

#include "errors.h"

namespace globular {
namespace {

FarmSettings shot() {
    FarmSettings s;
    s.program = "/opt/globular/globular";
    s.scene = "/shots/pour it.toml";
    s.outDir = "/farm/out";
    s.overrides = {"render.color_by=speed", "material.b1=3"};
    s.frames = 25;
    s.chunk = 10;
    return s;
}

bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

const std::vector<std::string> kIds = {"101", "102", "103", "104", "105"};

TEST(FarmScripts, ChunksCoverEveryFrameOnce) {
    EXPECT_EQ(farmChunks(25, 10), (std::vector<std::pair<int, int>>{{1, 10}, {11, 20}, {21, 25}}));
    EXPECT_EQ(farmChunks(20, 10), (std::vector<std::pair<int, int>>{{1, 10}, {11, 20}}));
    EXPECT_EQ(farmChunks(3, 10), (std::vector<std::pair<int, int>>{{1, 3}}));
}

TEST(FarmScripts, SimIsOneResumableJob) {
    const std::string sim = farmScript(shot(), "sim", farmDependency(shot(), "sim", kIds));
    EXPECT_TRUE(has(sim, "#!/bin/bash\n"));
    EXPECT_FALSE(has(sim, "--array"));
    EXPECT_FALSE(has(sim, "--dependency"));
    EXPECT_TRUE(has(sim, "#SBATCH --output=/farm/out/farm/logs/sim-%j.out\n"));
    EXPECT_TRUE(has(sim, "exec /opt/globular/globular run '/shots/pour it.toml' --out /farm/out "
                         "--set render.color_by=speed --set material.b1=3 --stages sim --resume"));
}

TEST(FarmScripts, SurfaceAndRenderAreArraysOverTheChunks) {
    FarmSettings s = shot();
    s.maxRunning = 4;
    const std::string surface = farmScript(s, "surface", farmDependency(s, "surface", kIds));
    EXPECT_TRUE(has(surface, "#SBATCH --array=0-2%4\n"));
    EXPECT_TRUE(has(surface, "#SBATCH --dependency=afterok:101\n"));
    EXPECT_TRUE(has(surface, "    0) frames=1-10 ;;\n    1) frames=11-20 ;;\n    2) frames=21-25 ;;\n"));
    EXPECT_TRUE(has(surface, "--stages surface --frames \"$frames\""));
    const std::string render = farmScript(s, "render", farmDependency(s, "render", kIds));
    EXPECT_TRUE(has(render, "#SBATCH --array=0-2%4\n"));
    EXPECT_TRUE(has(render, "#SBATCH --dependency=aftercorr:102,afterok:103\n"));
    EXPECT_TRUE(has(render, "    2) frames=21-25 ;;\n"));
    EXPECT_TRUE(has(render, "--stages render --frames \"$frames\""));
    EXPECT_TRUE(has(render, "#SBATCH --output=/farm/out/farm/logs/render-%A_%a.out\n"));
}

TEST(FarmScripts, PlanWaitsForWhatItMeasures) {
    FarmSettings s = shot();
    EXPECT_EQ(farmDependency(s, "plan", kIds), "afterok:101");  // spheres: the caches
    s.planAfterSurface = true;
    EXPECT_EQ(farmDependency(s, "plan", kIds), "afterok:101,afterok:102");  // the meshes
    const std::string plan = farmScript(s, "plan", farmDependency(s, "plan", kIds));
    EXPECT_TRUE(has(plan, "--stages plan"));
    EXPECT_FALSE(has(plan, "--array"));
    const std::string finish = farmScript(s, "finish", farmDependency(s, "finish", kIds));
    EXPECT_TRUE(has(finish, "#SBATCH --dependency=afterok:104\n"));
    EXPECT_TRUE(has(finish, "--stages finish"));
}

TEST(FarmScripts, AResubmissionCarriesOnlyItsTasksAndDependencies) {
    FarmSettings s = shot();
    s.maxRunning = 2;
    const std::vector<std::string> ids = {"", "", "203", "204", ""};
    const std::string render =
        farmScript(s, "render", farmDependency(s, "render", ids), {1, 2});
    EXPECT_TRUE(has(render, "#SBATCH --array=1,2%2\n"));
    EXPECT_TRUE(has(render, "#SBATCH --dependency=afterok:203\n"));
    EXPECT_EQ(farmDependency(s, "finish", ids), "afterok:204");
    EXPECT_EQ(farmDependency(s, "surface", ids), "");
}

TEST(FarmScripts, SlurmOptionsArePassedThrough) {
    FarmSettings s = shot();
    s.partition = "gpu";
    s.account = "film";
    s.timeLimit = "02:00:00";
    const std::string sim = farmScript(s, "sim", "");
    EXPECT_TRUE(has(sim, "#SBATCH --partition=gpu\n#SBATCH --account=film\n#SBATCH --time=02:00:00\n"));
    s.partition = "a b";
    EXPECT_THROW(s.validate(), SceneError);
    s = shot();
    s.chunk = 0;
    EXPECT_THROW(s.validate(), SceneError);
}

TEST(FarmScripts, ShellQuoting) {
    EXPECT_EQ(shellQuote("plain/path-1.toml"), "plain/path-1.toml");
    EXPECT_EQ(shellQuote("it's"), "'it'\\''s'");
    EXPECT_EQ(shellQuote(""), "''");
    EXPECT_EQ(shellQuote("$HOME"), "'$HOME'");
}

}  // namespace
}  // namespace globular
