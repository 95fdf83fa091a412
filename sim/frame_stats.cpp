#include "frame_stats.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>

#include "errors.h"
#include "overlap_clusters.h"

namespace globular {

namespace {

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

    const std::vector<std::size_t> sizes = overlapClusterSizes(g);
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
