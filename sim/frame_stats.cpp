#include "frame_stats.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <charconv>
#include <cmath>
#include <fstream>
#include <numeric>

#include "errors.h"
#include "neighbor_grid.h"

namespace globular {

namespace {

/// @brief Lock-free union-find (Anderson & Woll): a root only ever links below a smaller
/// index, so there are no cycles and the components are the same whatever order the
/// threads unite pairs in.
class ConcurrentUnionFind {
  public:
    explicit ConcurrentUnionFind(std::size_t n) : mParent(n) {
        for (std::size_t i = 0; i < n; ++i) mParent[i].store(uint32_t(i));
    }

    uint32_t find(uint32_t x) {
        while (true) {
            uint32_t p = mParent[x].load();
            if (p == x) return x;
            const uint32_t grandparent = mParent[p].load();
            if (grandparent != p) mParent[x].compare_exchange_weak(p, grandparent);  // halve
            x = grandparent;
        }
    }

    void unite(uint32_t a, uint32_t b) {
        while (true) {
            a = find(a);
            b = find(b);
            if (a == b) return;
            if (a < b) std::swap(a, b);
            uint32_t expected = a;  // a is a root; link it below the smaller root b
            if (mParent[a].compare_exchange_strong(expected, b)) return;
        }
    }

  private:
    std::vector<std::atomic<uint32_t>> mParent;
};

/// @brief Whether a globule can be binned: a grid cell coordinate of a non-finite or
/// astronomically distant position would overflow. Such globules stay clusters of one.
bool binnable(const Globules& g, std::size_t i, double cellSize) {
    const double limit = 1e15 * cellSize;
    for (float c : {g.px[i], g.py[i], g.pz[i]}) {
        if (!(std::fabs(c) < limit)) return false;
    }
    return true;
}

/// Sizes of the clusters of overlapping globules, one entry per cluster.
std::vector<std::size_t> clusterSizes(const Globules& g) {
    const std::size_t n = g.size();
    float maxRadius = 0;
    for (float r : g.radius) {
        if (std::isfinite(r)) maxRadius = std::max(maxRadius, r);
    }
    if (!(maxRadius > 0)) return std::vector<std::size_t>(n, 1);
    const float cellSize = 2 * maxRadius;  // covers the largest overlap distance
    std::vector<uint32_t> member;          // grid point k is globule member[k]
    member.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        if (binnable(g, i, cellSize)) member.push_back(uint32_t(i));
    }
    const std::size_t m = member.size();
    std::vector<float> x(m), y(m), z(m), r(m);
    for (std::size_t k = 0; k < m; ++k) {
        x[k] = g.px[member[k]];
        y[k] = g.py[member[k]];
        z[k] = g.pz[member[k]];
    }
    NeighborGrid grid;
    grid.build(x.data(), y.data(), z.data(), m, cellSize);
    // Copies in the grid's order: a query's runs are then contiguous ranges of these
    // arrays, read straight through, and a pair is tested once, from its earlier end.
    // The clusters are found over these positions too, so that the union-find's reads
    // stay as local as the neighbours (sizes do not depend on the labels).
    const std::vector<uint32_t>& order = grid.sortedOrder();
    for (std::size_t s = 0; s < m; ++s) {  // in place: x, y, z now in grid order
        const uint32_t i = member[order[s]];
        x[s] = g.px[i];
        y[s] = g.py[i];
        z[s] = g.pz[i];
        r[s] = g.radius[i];
    }
    ConcurrentUnionFind sets(m);
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, m, 1024),
        [&](const tbb::blocked_range<std::size_t>& range) {
            NeighborGrid::RunCursor cursor;
            std::array<NeighborGrid::Run, NeighborGrid::kMaxRuns> runs;
            constexpr std::size_t kChunk = 64;
            std::array<uint8_t, kChunk> overlaps;
            for (std::size_t s = range.begin(); s < range.end(); ++s) {
                // Most overlapping pairs are already in one cluster: a find on the
                // partner's side alone tells, and only the rest are united.
                uint32_t root = sets.find(uint32_t(s));
                const int count = grid.neighborRuns(x[s], y[s], z[s], cursor, runs);
                for (int q = 0; q < count; ++q) {
                    const std::size_t end = runs[q].second;
                    for (std::size_t l = std::max<std::size_t>(runs[q].first, s + 1); l < end;
                         l += kChunk) {
                        const std::size_t chunk = std::min(kChunk, end - l);
                        for (std::size_t k = 0; k < chunk; ++k) {  // vectorised test
                            const float dx = x[l + k] - x[s], dy = y[l + k] - y[s],
                                        dz = z[l + k] - z[s];
                            const float reach = r[s] + r[l + k];
                            overlaps[k] = dx * dx + dy * dy + dz * dz < reach * reach;
                        }
                        for (std::size_t k = 0; k < chunk; ++k) {
                            if (!overlaps[k]) continue;
                            const uint32_t other = sets.find(uint32_t(l + k));
                            if (other == root) continue;
                            sets.unite(root, other);
                            root = sets.find(uint32_t(s));
                        }
                    }
                }
            }
        });
    std::vector<std::size_t> sizeOfRoot(m, 0);
    for (std::size_t s = 0; s < m; ++s) ++sizeOfRoot[sets.find(uint32_t(s))];
    std::vector<std::size_t> sizes(n - m, 1);  // the unbinnable stay clusters of one
    for (std::size_t size : sizeOfRoot) {
        if (size > 0) sizes.push_back(size);
    }
    return sizes;
}

std::string formatReal(double v) {
    std::array<char, 64> buffer;
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v,
                                      std::chars_format::general, 9);
    return std::string(buffer.data(), result.ptr);
}

constexpr std::array<const char*, 12> kColumns = {"frame",         "time",
                                                  "count",         "kinetic_energy",
                                                  "max_speed",     "centroid_x",
                                                  "centroid_y",    "centroid_z",
                                                  "max_height",    "horizontal_spread",
                                                  "cluster_count", "largest_cluster_fraction"};

std::vector<std::string> splitFields(const std::string& line) {
    std::vector<std::string> fields;
    std::size_t begin = 0;
    while (true) {
        const std::size_t end = line.find(',', begin);
        fields.push_back(line.substr(begin, end - begin));
        if (end == std::string::npos) return fields;
        begin = end + 1;
    }
}

template <typename T>
bool parseField(const std::string& text, T& value) {
    const char* first = text.data();
    const char* last = first + text.size();
    while (first < last && *first == ' ') ++first;
    while (last > first && last[-1] == ' ') --last;
    return first < last && std::from_chars(first, last, value).ptr == last;
}

}  // namespace

FrameStats computeFrameStats(const Globules& g, int frame, double time) {
    FrameStats s;
    s.frame = frame;
    s.time = time;
    s.count = g.size();
    if (g.empty()) return s;

    const double n = double(g.size());
    Vec3 sum;
    s.maxHeight = -INFINITY;
    for (std::size_t i = 0; i < g.size(); ++i) {
        const double speed2 =
            double(g.vx[i]) * g.vx[i] + double(g.vy[i]) * g.vy[i] + double(g.vz[i]) * g.vz[i];
        s.kineticEnergy += 0.5 * g.mass[i] * speed2;
        s.maxSpeed = std::max(s.maxSpeed, std::sqrt(speed2));
        sum = sum + g.position(i);
        s.maxHeight = std::max(s.maxHeight, double(g.py[i]));
    }
    s.centroid = sum * (1.0 / n);

    double spread2 = 0;
    for (std::size_t i = 0; i < g.size(); ++i) {
        const double dx = g.px[i] - s.centroid.x, dz = g.pz[i] - s.centroid.z;
        spread2 += dx * dx + dz * dz;
    }
    s.horizontalSpread = std::sqrt(spread2 / n);

    const std::vector<std::size_t> sizes = clusterSizes(g);
    s.clusterCount = sizes.size();
    s.largestClusterFraction = double(*std::max_element(sizes.begin(), sizes.end())) / n;
    return s;
}

std::string statsCsvHeader() {
    std::string header;
    for (const char* column : kColumns) {
        if (!header.empty()) header += ',';
        header += column;
    }
    return header;
}

std::string statsCsvRow(const FrameStats& s) {
    const std::string fields[] = {
        std::to_string(s.frame),        formatReal(s.time),
        std::to_string(s.count),        formatReal(s.kineticEnergy),
        formatReal(s.maxSpeed),         formatReal(s.centroid.x),
        formatReal(s.centroid.y),       formatReal(s.centroid.z),
        formatReal(s.maxHeight),        formatReal(s.horizontalSpread),
        std::to_string(s.clusterCount), formatReal(s.largestClusterFraction)};
    std::string row;
    for (const std::string& f : fields) {
        if (!row.empty()) row += ',';
        row += f;
    }
    return row;
}

std::vector<FrameStats> readStatsCsv(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw IoError("cannot read " + path.string() + ": no such file or unreadable");
    int lineNo = 0;
    const auto fail = [&](const std::string& what) {
        return IoError("cannot read " + path.string() + ": line " + std::to_string(lineNo) + ": " +
                       what);
    };
    std::string line;
    std::vector<std::size_t> columnOf(kColumns.size());  // field index of each column
    std::size_t fieldCount = 0;
    std::vector<FrameStats> rows;
    while (std::getline(in, line)) {
        ++lineNo;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.find_first_not_of(" \t") == std::string::npos) continue;
        const std::vector<std::string> fields = splitFields(line);
        if (fieldCount == 0) {  // the header
            for (std::size_t c = 0; c < kColumns.size(); ++c) {
                const auto it = std::find(fields.begin(), fields.end(), kColumns[c]);
                if (it == fields.end()) throw fail(std::string("missing column ") + kColumns[c]);
                columnOf[c] = std::size_t(it - fields.begin());
            }
            fieldCount = fields.size();
            continue;
        }
        if (fields.size() != fieldCount) {
            throw fail("expected " + std::to_string(fieldCount) + " fields, found " +
                       std::to_string(fields.size()));
        }
        FrameStats s;
        std::size_t c = 0;
        const auto field = [&](auto& value) {
            const std::string& text = fields[columnOf[c]];
            if (!parseField(text, value)) {
                throw fail(std::string("bad value '") + text + "' in column " + kColumns[c]);
            }
            ++c;
        };
        field(s.frame), field(s.time), field(s.count), field(s.kineticEnergy);
        field(s.maxSpeed), field(s.centroid.x), field(s.centroid.y), field(s.centroid.z);
        field(s.maxHeight), field(s.horizontalSpread), field(s.clusterCount);
        field(s.largestClusterFraction);
        rows.push_back(s);
    }
    if (in.bad()) throw fail("read error");
    if (fieldCount == 0) throw IoError("cannot read " + path.string() + ": no header line");
    return rows;
}

}  // namespace globular
