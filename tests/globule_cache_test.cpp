#include "globule_cache.h"

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/points/PointCount.h>
#include <openvdb/points/PointDataGrid.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <string>

#include "errors.h"

namespace globular {
namespace {

namespace fs = std::filesystem;

/// A fresh directory per test, removed afterwards.
class GlobuleCacheTest : public testing::Test {
  protected:
    void SetUp() override {
        const auto* info = testing::UnitTest::GetInstance()->current_test_info();
        mDir = fs::path(testing::TempDir()) /
               ("globule_cache_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(mDir);
        fs::create_directories(mDir);
    }
    void TearDown() override { fs::remove_all(mDir); }
    fs::path mDir;
};

Globules randomGlobules(std::size_t n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-20, 20), vel(-5, 5), rad(0.5f, 1.5f);
    Globules g;
    for (std::size_t i = 0; i < n; ++i) {
        // Masses other than 1, so that a reader that forgets them fails.
        g.add({pos(rng), pos(rng) + 10, pos(rng)}, {vel(rng), vel(rng), vel(rng)}, rad(rng),
              0.5f + 0.25f * float(i % 7), int32_t(1000 + 7 * i));
    }
    return g;
}

std::map<int32_t, std::size_t> indexById(const Globules& g) {
    std::map<int32_t, std::size_t> byId;
    for (std::size_t i = 0; i < g.size(); ++i) byId[g.id[i]] = i;
    return byId;
}

void expectSameGlobules(const Globules& expected, const Globules& actual, float posTolerance) {
    ASSERT_EQ(actual.size(), expected.size());
    const auto byId = indexById(actual);
    ASSERT_EQ(byId.size(), expected.size()) << "ids are not unique";
    for (std::size_t i = 0; i < expected.size(); ++i) {
        const auto it = byId.find(expected.id[i]);
        ASSERT_NE(it, byId.end()) << "id " << expected.id[i];
        const std::size_t k = it->second;
        EXPECT_NEAR(actual.px[k], expected.px[i], posTolerance);
        EXPECT_NEAR(actual.py[k], expected.py[i], posTolerance);
        EXPECT_NEAR(actual.pz[k], expected.pz[i], posTolerance);
        EXPECT_EQ(actual.vx[k], expected.vx[i]);
        EXPECT_EQ(actual.vy[k], expected.vy[i]);
        EXPECT_EQ(actual.vz[k], expected.vz[i]);
        EXPECT_EQ(actual.radius[k], expected.radius[i]);
        EXPECT_EQ(actual.mass[k], expected.mass[i]);
    }
}

void writeText(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

std::string readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Runs @p read and expects an IoError whose message names @p path.
template <typename Read>
void expectIoErrorNaming(const fs::path& path, Read&& read) {
    try {
        read();
        ADD_FAILURE() << "no IoError for " << path;
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
}

TEST_F(GlobuleCacheTest, VdbRoundTripKeepsEveryAttribute) {
    const Globules g = randomGlobules(1000, 42);
    const fs::path path = mDir / "globules.0003.vdb";
    writeGlobuleVdb(path, g, {3, 0.125});
    CacheInfo info;
    const Globules back = readGlobuleVdb(path, &info);
    EXPECT_EQ(info.frame, 3);
    EXPECT_EQ(info.time, 0.125);
    expectSameGlobules(g, back, 1e-5f);
    EXPECT_TRUE(std::is_sorted(back.id.begin(), back.id.end()));
    EXPECT_EQ(std::distance(fs::directory_iterator(mDir), {}), 1);  // no temporary left
}

TEST_F(GlobuleCacheTest, MaterialsTravelInTheVdbAndPlyCaches) {
    Globules g = randomGlobules(300, 5);
    for (std::size_t i = 0; i < g.size(); ++i) g.material.push_back(uint8_t(g.id[i] % 3));
    writeGlobuleVdb(mDir / "mixed.vdb", g, {1, 0.0});
    const Globules back = readGlobuleVdb(mDir / "mixed.vdb");
    ASSERT_EQ(back.material.size(), g.size());
    for (std::size_t i = 0; i < back.size(); ++i) EXPECT_EQ(back.material[i], back.id[i] % 3);
    writeGlobulePly(mDir / "mixed.ply", g);
    const std::string ply = readBytes(mDir / "mixed.ply");
    EXPECT_NE(ply.find("property int id\nproperty float mass\nproperty int material\n"),
              std::string::npos);
    // One material: every globule's is 0.
    writeGlobuleVdb(mDir / "single.vdb", randomGlobules(50, 6), {1, 0.0});
    const Globules single = readGlobuleVdb(mDir / "single.vdb");
    for (std::size_t i = 0; i < single.size(); ++i) EXPECT_EQ(single.materialOf(i), 0);
}

TEST_F(GlobuleCacheTest, TemperatureRoundTripsExactlyInTheVdbAndPlyCaches) {
    Globules g = randomGlobules(400, 8);
    for (std::size_t i = 0; i < g.size(); ++i) {
        g.temperature.push_back(-40.0f + 1234.5678f * float(i) / float(g.size()));
    }
    writeGlobuleVdb(mDir / "hot.vdb", g, {2, 0.04});
    const Globules vdb = readGlobuleVdb(mDir / "hot.vdb");
    ASSERT_EQ(vdb.temperature.size(), g.size());
    for (std::size_t i = 0; i < g.size(); ++i) EXPECT_EQ(vdb.temperature[i], g.temperature[i]);

    writeGlobulePly(mDir / "hot.ply", g);
    EXPECT_NE(readBytes(mDir / "hot.ply").find("property int material\nproperty float temperature\n"),
              std::string::npos);
    const Globules ply = readGlobulePly(mDir / "hot.ply");
    ASSERT_EQ(ply.temperature.size(), g.size());
    for (std::size_t i = 0; i < g.size(); ++i) EXPECT_EQ(ply.temperature[i], g.temperature[i]);

    // Without temperature, none is written and none comes back.
    const Globules cold = randomGlobules(50, 9);
    writeGlobuleVdb(mDir / "plain.vdb", cold, {1, 0.0});
    writeGlobulePly(mDir / "plain.ply", cold);
    EXPECT_TRUE(readGlobuleVdb(mDir / "plain.vdb").temperature.empty());
    EXPECT_TRUE(readGlobulePly(mDir / "plain.ply").temperature.empty());
    EXPECT_EQ(readBytes(mDir / "plain.ply").find("temperature"), std::string::npos);
}

TEST_F(GlobuleCacheTest, NonFiniteTemperatureIsRefusedNamingTheFile) {
    Globules g = randomGlobules(20, 10);
    g.temperature.assign(g.size(), 20.0f);
    g.temperature[7] = std::numeric_limits<float>::quiet_NaN();
    for (const char* name : {"bad.vdb", "bad.ply"}) {
        const fs::path path = mDir / name;
        try {
            if (path.extension() == ".vdb") {
                writeGlobuleVdb(path, g, {1, 0.0});
            } else {
                writeGlobulePly(path, g);
            }
            FAIL() << name << " written with a NaN temperature";
        } catch (const IoError& e) {
            EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("temperature"), std::string::npos) << e.what();
        }
        EXPECT_FALSE(fs::exists(path));
    }
    // A PLY cloud from elsewhere with an infinite temperature.
    const fs::path path = mDir / "inf.ply";
    std::ofstream(path) << "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n"
                           "property float y\nproperty float z\nproperty float temperature\n"
                           "end_header\n0 0 0 20\n1 0 0 1e39\n";  // inf as a float
    try {
        readGlobulePly(path);
        FAIL() << "an infinite temperature read";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("vertex 1"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("temperature"), std::string::npos) << e.what();
    }
}

TEST_F(GlobuleCacheTest, VdbIsReadableWithPlainOpenVdb) {
    const Globules g = randomGlobules(500, 7);
    const fs::path path = mDir / "plain.vdb";
    writeGlobuleVdb(path, g, {1, 0.0});
    openvdb::initialize();
    openvdb::io::File file(path.string());
    file.open();
    ASSERT_TRUE(file.hasGrid("globules"));
    auto grid = openvdb::gridPtrCast<openvdb::points::PointDataGrid>(file.readGrid("globules"));
    file.close();
    ASSERT_TRUE(grid);
    EXPECT_EQ(openvdb::points::pointCount(grid->tree()), 500u);
    auto leaf = grid->tree().cbeginLeaf();
    ASSERT_TRUE(leaf);
    const auto& descriptor = leaf->attributeSet().descriptor();
    EXPECT_EQ(descriptor.valueType(descriptor.find("P")), "vec3s");
    EXPECT_EQ(descriptor.valueType(descriptor.find("v")), "vec3s");
    EXPECT_EQ(descriptor.valueType(descriptor.find("pscale")), "float");
    EXPECT_EQ(descriptor.valueType(descriptor.find("id")), "int32");
    EXPECT_EQ(grid->metaValue<int32_t>("frame"), 1);
}

TEST_F(GlobuleCacheTest, VdbOfOneGlobuleAndOfNone) {
    Globules one;
    one.add({1e5, -3, 0.5}, {1, 2, 3}, 0.25f, 2.0f, 9);
    writeGlobuleVdb(mDir / "one.vdb", one, {});
    expectSameGlobules(one, readGlobuleVdb(mDir / "one.vdb"), 0.01f);

    writeGlobuleVdb(mDir / "none.vdb", Globules{}, {5, 2.5});
    CacheInfo info;
    EXPECT_TRUE(readGlobuleVdb(mDir / "none.vdb", &info).empty());
    EXPECT_EQ(info.frame, 5);
    EXPECT_EQ(info.time, 2.5);
}

TEST_F(GlobuleCacheTest, VdbRejectsNonFinitePositionsWithoutWriting) {
    Globules g = randomGlobules(3, 1);
    g.py[1] = NAN;
    EXPECT_THROW(writeGlobuleVdb(mDir / "nan.vdb", g, {}), IoError);
    EXPECT_FALSE(fs::exists(mDir / "nan.vdb"));
}

TEST_F(GlobuleCacheTest, VdbMissingTruncatedOrForeignFilesGiveIoError) {
    expectIoErrorNaming(mDir / "missing.vdb", [&] { readGlobuleVdb(mDir / "missing.vdb"); });

    const fs::path good = mDir / "good.vdb";
    writeGlobuleVdb(good, randomGlobules(1000, 3), {});
    const std::string bytes = readBytes(good);
    for (std::size_t keep : {std::size_t(0), std::size_t(8), bytes.size() / 4, bytes.size() / 2,
                             bytes.size() - 16, bytes.size() - 1}) {
        const fs::path cut = mDir / ("cut" + std::to_string(keep) + ".vdb");
        writeText(cut, bytes.substr(0, keep));
        expectIoErrorNaming(cut, [&] { readGlobuleVdb(cut); });
    }

    const fs::path garbage = mDir / "garbage.vdb";
    writeText(garbage, "this is not a vdb file at all");
    expectIoErrorNaming(garbage, [&] { readGlobuleVdb(garbage); });

    openvdb::initialize();
    const fs::path other = mDir / "other.vdb";
    auto density = openvdb::FloatGrid::create();
    density->setName("density");
    openvdb::io::File(other.string()).write(openvdb::GridCPtrVec{density});
    try {
        readGlobuleVdb(other);
        ADD_FAILURE() << "no IoError";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("globules"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(other.string()), std::string::npos) << e.what();
    }
}

TEST_F(GlobuleCacheTest, VdbWithAFlippedByteIsCorrupt) {
    const fs::path path = mDir / "flipped.vdb";
    writeGlobuleVdb(path, randomGlobules(200, 9), {});
    std::string bytes = readBytes(path);
    for (std::size_t at : {bytes.size() / 3, bytes.size() - 5}) {
        std::string flipped = bytes;
        flipped[at] ^= 0x10;
        writeText(path, flipped);
        try {
            readGlobuleVdb(path);
            ADD_FAILURE() << "no IoError";
        } catch (const IoError& e) {
            EXPECT_NE(std::string(e.what()).find("corrupt"), std::string::npos) << e.what();
        }
    }
}

TEST_F(GlobuleCacheTest, MassIsStoredAsHoudinisMassAttribute) {
    Globules g = randomGlobules(100, 12);
    g.mass[17] = 3.75f;
    writeGlobuleVdb(mDir / "heavy.vdb", g, {1, 0.0});
    openvdb::initialize();
    openvdb::io::File file((mDir / "heavy.vdb").string());
    file.open();
    auto grid = openvdb::gridPtrCast<openvdb::points::PointDataGrid>(file.readGrid("globules"));
    file.close();
    const auto& descriptor = grid->tree().cbeginLeaf()->attributeSet().descriptor();
    ASSERT_NE(descriptor.find("mass"), openvdb::points::AttributeSet::INVALID_POS);
    EXPECT_EQ(descriptor.valueType(descriptor.find("mass")), "float");
    const Globules back = readGlobuleVdb(mDir / "heavy.vdb");
    EXPECT_EQ(back.mass[indexById(back).at(g.id[17])], 3.75f);

    writeGlobulePly(mDir / "heavy.ply", g);
    EXPECT_EQ(readGlobulePly(mDir / "heavy.ply").mass, g.mass);
}

TEST_F(GlobuleCacheTest, MassThatIsNotPositiveIsRefusedNamingTheFile) {
    for (float bad : {0.0f, -1.0f, NAN, INFINITY}) {
        Globules g = randomGlobules(5, 13);
        g.mass[2] = bad;
        expectIoErrorNaming(mDir / "bad.vdb", [&] { writeGlobuleVdb(mDir / "bad.vdb", g, {}); });
        EXPECT_FALSE(fs::exists(mDir / "bad.vdb"));
        expectIoErrorNaming(mDir / "bad.ply", [&] { writeGlobulePly(mDir / "bad.ply", g); });
        EXPECT_FALSE(fs::exists(mDir / "bad.ply"));
    }
    // Read: a PLY cache with a mass of 0, and a VDB cache of another tool with a negative one.
    writeText(mDir / "zero.ply",
              "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
              "property float z\nproperty float mass\nend_header\n0 0 0 1\n1 1 1 0\n");
    expectIoErrorNaming(mDir / "zero.ply", [&] { readGlobulePly(mDir / "zero.ply"); });
    openvdb::initialize();
    const std::vector<openvdb::Vec3f> positions = {{1, 2, 3}};
    auto transform = openvdb::math::Transform::createLinearTransform(0.5);
    auto grid =
        openvdb::points::createPointDataGrid<openvdb::points::NullCodec,
                                             openvdb::points::PointDataGrid>(positions, *transform);
    openvdb::points::appendAttribute<float>(grid->tree(), "mass", -2.0f);
    grid->setName("globules");
    openvdb::io::File((mDir / "negative.vdb").string()).write(openvdb::GridCPtrVec{grid});
    expectIoErrorNaming(mDir / "negative.vdb", [&] { readGlobuleVdb(mDir / "negative.vdb"); });
}

TEST_F(GlobuleCacheTest, VdbFromOtherToolsGetsDefaults) {
    // Positions only, written by plain OpenVDB (as a DCC tool might): v 0, radius 1,
    // id = index, frame and time 0.
    openvdb::initialize();
    const std::vector<openvdb::Vec3f> positions = {{1, 2, 3}, {-4, 5, 6}};
    auto transform = openvdb::math::Transform::createLinearTransform(0.5);
    auto grid =
        openvdb::points::createPointDataGrid<openvdb::points::NullCodec,
                                             openvdb::points::PointDataGrid>(positions, *transform);
    grid->setName("globules");
    const fs::path path = mDir / "foreign.vdb";
    openvdb::io::File(path.string()).write(openvdb::GridCPtrVec{grid});

    CacheInfo info{7, 7.0};
    const Globules g = readGlobuleVdb(path, &info);
    ASSERT_EQ(g.size(), 2u);
    EXPECT_EQ(info.frame, 0);
    EXPECT_EQ(info.time, 0.0);
    EXPECT_EQ(g.radius, (std::vector<float>{1, 1}));
    EXPECT_EQ(g.vx, (std::vector<float>{0, 0}));
    EXPECT_EQ(g.mass, (std::vector<float>{1, 1}));
    std::vector<int32_t> ids = g.id;
    std::sort(ids.begin(), ids.end());
    EXPECT_EQ(ids, (std::vector<int32_t>{0, 1}));
    const std::size_t first = g.px[0] == 1 ? 0 : 1;
    EXPECT_NEAR(g.px[first], 1, 1e-6);
    EXPECT_NEAR(g.py[first], 2, 1e-6);
    EXPECT_NEAR(g.pz[1 - first], 6, 1e-6);
}

TEST_F(GlobuleCacheTest, PlyRoundTripIsExact) {
    const Globules g = randomGlobules(1000, 11);
    const fs::path path = mDir / "globules.0001.ply";
    writeGlobulePly(path, g);
    const Globules back = readGlobulePly(path);
    expectSameGlobules(g, back, 0.0f);
    EXPECT_EQ(back.id, g.id);  // file order is kept
    // x y z vx vy vz radius (float), id (int32), mass (float), material (int32): 40 bytes
    // a row.
    EXPECT_EQ(fs::file_size(path), readBytes(path).find("end_header\n") + 11 + 1000 * 40);

    writeGlobulePly(mDir / "empty.ply", Globules{});
    EXPECT_TRUE(readGlobulePly(mDir / "empty.ply").empty());
}

TEST_F(GlobuleCacheTest, PlyReadsAsciiWithOtherTypesAndElements) {
    const fs::path path = mDir / "cloud.ply";
    writeText(path,
              "ply\r\nformat ascii 1.0\ncomment made by hand\n"
              "element material 1\nproperty list uchar int colors\n"
              "element vertex 3\nproperty double x\nproperty float y\nproperty int z\n"
              "property uchar red\nproperty float radius\n"
              "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
              "3 1 2 3\n"
              "1.5 -2 3 255 0.5\n"
              "+4 5e-1 -6 0 0.25\n"
              "7 8 9 1 2\n"
              "3 0 1 2\n");
    const Globules g = readGlobulePly(path, 0.75f);
    ASSERT_EQ(g.size(), 3u);
    EXPECT_EQ(g.px, (std::vector<float>{1.5f, 4, 7}));
    EXPECT_EQ(g.py, (std::vector<float>{-2, 0.5f, 8}));
    EXPECT_EQ(g.pz, (std::vector<float>{3, -6, 9}));
    EXPECT_EQ(g.radius, (std::vector<float>{0.5f, 0.25f, 2}));
    EXPECT_EQ(g.vx, (std::vector<float>{0, 0, 0}));
    EXPECT_EQ(g.id, (std::vector<int32_t>{0, 1, 2}));
    EXPECT_EQ(g.mass, (std::vector<float>{1, 1, 1}));

    const fs::path bare = mDir / "bare.ply";
    writeText(bare,
              "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
              "property float y\nproperty float z\nend_header\n1 2 3\n");
    EXPECT_EQ(readGlobulePly(bare, 0.75f).radius, std::vector<float>{0.75f});
}

TEST_F(GlobuleCacheTest, PlyReadsBinaryWithOtherTypesAndElements) {
    std::string bytes =
        "ply\nformat binary_little_endian 1.0\n"
        "element face 2\nproperty list uchar int vertex_indices\n"
        "element vertex 2\nproperty double x\nproperty short y\nproperty uchar z\n"
        "property list uchar float extra\nproperty uint id\nproperty float vy\nend_header\n";
    const auto put = [&](auto value) {
        bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
    };
    put(uint8_t(3)), put(int32_t(0)), put(int32_t(1)), put(int32_t(2));  // face 0
    put(uint8_t(0));                                                     // face 1
    put(-1.25), put(int16_t(-7)), put(uint8_t(200)), put(uint8_t(1)), put(9.0f);
    put(uint32_t(41)), put(2.5f);
    put(3.0), put(int16_t(8)), put(uint8_t(0)), put(uint8_t(0)), put(uint32_t(42)), put(-1.0f);
    const fs::path path = mDir / "binary.ply";
    writeText(path, bytes);
    const Globules g = readGlobulePly(path);
    EXPECT_EQ(g.px, (std::vector<float>{-1.25f, 3}));
    EXPECT_EQ(g.py, (std::vector<float>{-7, 8}));
    EXPECT_EQ(g.pz, (std::vector<float>{200, 0}));
    EXPECT_EQ(g.vy, (std::vector<float>{2.5f, -1}));
    EXPECT_EQ(g.id, (std::vector<int32_t>{41, 42}));
    EXPECT_EQ(g.radius, (std::vector<float>{1, 1}));
}

TEST_F(GlobuleCacheTest, PlyRejectsMalformedInputNamingTheFile) {
    expectIoErrorNaming(mDir / "missing.ply", [&] { readGlobulePly(mDir / "missing.ply"); });

    const std::string header =
        "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
        "property float z\nend_header\n";
    const std::map<std::string, std::string> cases = {
        {"garbage", "\x89PNG\r\n\x1a\n not a ply"},
        {"no_end", "ply\nformat ascii 1.0\nelement vertex 1\n"},
        {"bad_type", "ply\nformat ascii 1.0\nelement vertex 1\nproperty flaot x\nend_header\n"},
        {"big_endian", "ply\nformat binary_big_endian 1.0\nend_header\n"},
        {"no_z",
         "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
         "property float y\nend_header\n1 2\n"},
        {"short_ascii", header + "1 2 3\n4 5\n"},
        {"bad_number", header + "1 2 3\n4 five 6\n"},
        {"out_of_range_number", header + "1 2 3\n4 1e999 6\n"},
        {"lying_count",
         "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n"
         "property float x\nproperty float y\nproperty float z\nend_header\n" +
             std::string(24, '\0')},
    };
    for (const auto& [name, text] : cases) {
        const fs::path path = mDir / (name + ".ply");
        writeText(path, text);
        expectIoErrorNaming(path, [&] { readGlobulePly(path); });
    }

    // Truncated binary data: every cut inside the vertex data is detected.
    const fs::path good = mDir / "good.ply";
    writeGlobulePly(good, randomGlobules(10, 5));
    const std::string bytes = readBytes(good);
    for (std::size_t cut = 1; cut <= 10 * 32; cut += 13) {
        const fs::path path = mDir / "cut.ply";
        writeText(path, bytes.substr(0, bytes.size() - cut));
        expectIoErrorNaming(path, [&] { readGlobulePly(path); });
    }

    // The header line of a malformed header is named.
    try {
        readGlobulePly(mDir / "bad_type.ply");
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("header line 4"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace globular
