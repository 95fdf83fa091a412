// Houdini's conventions, checked on what `globular run` writes (issue 16) with plain
// OpenVDB and the PLY headers, not globular's readers: a DCC tool sees exactly this.
//   points: P v pscale id mass temperature material (Houdini's point attribute names)
//   volumes: surface (level set), density (fog), vel (Vec3f, contravariant relative:
//            a velocity), temperature (float); file names frame-numbered .NNNN.
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/PointDataGrid.h>

#include <map>
#include <regex>
#include <set>

#include "cli_runner.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

class HoudiniConventions : public CliTest {};

/// The PLY header's vertex properties, in order.
std::vector<std::string> vertexProperties(const fs::path& path) {
    const std::string text = readFile(path);
    std::istringstream header(text.substr(0, text.find("end_header")));
    std::vector<std::string> names;
    std::string line;
    bool inVertex = false;
    while (std::getline(header, line)) {
        if (line.rfind("element ", 0) == 0) inVertex = line.rfind("element vertex", 0) == 0;
        if (inVertex && line.rfind("property ", 0) == 0 && line.find(" list ") == std::string::npos) {
            names.push_back(line.substr(line.rfind(' ') + 1));
        }
    }
    return names;
}

openvdb::GridPtrVecPtr gridsOf(const fs::path& path) {
    openvdb::io::File file(path.string());
    file.open(/*delayLoad=*/false);  // the grids are read after the file is closed
    auto grids = file.getGrids();
    file.close();
    return grids;
}

TEST_F(HoudiniConventions, CachesSurfacesAndMeshesUseHoudinisNames) {
    const std::string scene = std::string(GLOBULAR_SOURCE_DIR) + "/tests/data/blender/tiny.toml";
    const RunResult r = run("run " + quote(scene) + " --out out --stages sim,surface --quiet");
    ASSERT_EQ(r.status, 0) << r.err;
    openvdb::initialize();

    // Frame-numbered names: name.NNNN.ext, four digits from 0001, every frame.
    const std::regex numbered(R"((globules|colliders|surface)\.(\d{4})\.(vdb|ply|toml))");
    std::map<std::string, std::set<int>> frames;
    for (const char* folder : {"cache", "surface", "mesh"}) {
        for (const auto& entry : fs::directory_iterator(mDir / "out" / folder)) {
            std::smatch m;
            const std::string name = entry.path().filename().string();
            ASSERT_TRUE(std::regex_match(name, m, numbered)) << folder << "/" << name;
            frames[std::string(folder) + "/" + m[1].str() + "." + m[3].str()].insert(
                std::stoi(m[2].str()));
        }
    }
    for (const char* kind : {"cache/globules.vdb", "cache/globules.ply", "surface/surface.vdb",
                             "mesh/surface.ply", "cache/colliders.toml", "mesh/colliders.ply"}) {
        EXPECT_EQ(frames[kind], (std::set<int>{1, 2, 3, 4})) << kind;
    }

    // Points: Houdini's attribute names and types.
    const auto points = gridsOf(mDir / "out/cache/globules.0002.vdb");
    ASSERT_EQ(points->size(), 1u);
    auto grid = openvdb::gridPtrCast<openvdb::points::PointDataGrid>((*points)[0]);
    ASSERT_TRUE(grid);
    EXPECT_EQ(grid->getName(), "globules");
    const auto& descriptor = grid->tree().cbeginLeaf()->attributeSet().descriptor();
    const std::map<std::string, std::string> expected = {
        {"P", "vec3s"},     {"v", "vec3s"},           {"pscale", "float"},  {"id", "int32"},
        {"mass", "float"}, {"temperature", "float"}, {"material", "int32"}};
    for (const auto& [name, type] : expected) {
        const std::size_t index = descriptor.find(name);
        ASSERT_NE(index, openvdb::points::AttributeSet::INVALID_POS) << name;
        EXPECT_EQ(descriptor.valueType(index), type) << name;
    }

    // Volumes: names, types, classes and the velocity's vector type.
    std::map<std::string, openvdb::GridBase::Ptr> volumes;
    const auto surfaceGrids = gridsOf(mDir / "out/surface/surface.0002.vdb");
    for (const auto& g : *surfaceGrids) volumes[g->getName()] = g;
    ASSERT_EQ(volumes.size(), 4u);
    for (const char* name : {"surface", "density", "vel", "temperature"}) {
        ASSERT_TRUE(volumes.count(name)) << name;
    }
    EXPECT_TRUE(volumes["surface"]->isType<openvdb::FloatGrid>());
    EXPECT_EQ(volumes["surface"]->getGridClass(), openvdb::GRID_LEVEL_SET);
    EXPECT_TRUE(volumes["density"]->isType<openvdb::FloatGrid>());
    EXPECT_EQ(volumes["density"]->getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_TRUE(volumes["vel"]->isType<openvdb::Vec3SGrid>());
    EXPECT_EQ(volumes["vel"]->getVectorType(), openvdb::VEC_CONTRAVARIANT_RELATIVE);
    EXPECT_EQ(volumes["vel"]->getGridClass(), openvdb::GRID_UNKNOWN);
    EXPECT_GT(volumes["vel"]->activeVoxelCount(), 0u);
    EXPECT_TRUE(volumes["temperature"]->isType<openvdb::FloatGrid>());
    EXPECT_EQ(volumes["temperature"]->getGridClass(), openvdb::GRID_UNKNOWN);

    // PLY: the point cache and the mesh carry the same quantities as vertex properties.
    EXPECT_EQ(vertexProperties(mDir / "out/cache/globules.0002.ply"),
              (std::vector<std::string>{"x", "y", "z", "vx", "vy", "vz", "radius", "id", "mass",
                                        "material", "temperature"}));
    EXPECT_EQ(vertexProperties(mDir / "out/mesh/surface.0002.ply"),
              (std::vector<std::string>{"x", "y", "z", "nx", "ny", "nz", "vx", "vy", "vz",
                                        "temperature", "material"}));
}

}  // namespace
}  // namespace globular
