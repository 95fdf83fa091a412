#include "ply_reader.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string_view>

#include "errors.h"

namespace globular {


namespace {

std::vector<std::string_view> splitWords(std::string_view line) {
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        std::size_t j = i;
        while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
        if (j > i) words.push_back(line.substr(i, j - i));
        i = j;
    }
    return words;
}

/// A header line quoted in a message: at most 80 characters.
std::string quoted(std::string_view line) {
    return "'" + quoteForMessage(std::string(line), 80) + "'";
}

/// The value of type T at @p bytes, in the host's byte order.
template <typename T>
double decodeAs(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof value);
    return double(value);
}

}  // namespace

int PlyElement::find(std::initializer_list<const char*> names) const {
    for (std::size_t i = 0; i < properties.size(); ++i) {
        for (const char* n : names) {
            if (properties[i].name == n) return int(i);
        }
    }
    return -1;
}

PlyHeader parsePlyHeader(const std::string& data) {
    PlyHeader header;
    std::size_t pos = 0;
    int lineNo = 0;
    bool hasFormat = false;
    const auto fail = [&](const std::string& what) {
        return std::runtime_error("header line " + std::to_string(lineNo) + ": " + what);
    };
    while (pos < data.size()) {
        std::size_t end = data.find('\n', pos);
        if (end == std::string::npos) end = data.size();
        std::string_view line(data.data() + pos, end - pos);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        pos = std::min(end + 1, data.size());
        ++lineNo;
        const auto words = splitWords(line);
        if (lineNo == 1) {
            if (line != "ply") throw std::runtime_error("not a PLY file (no 'ply' magic line)");
            continue;
        }
        if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
        if (words[0] == "end_header") {
            if (!hasFormat) throw fail("end_header before any format line");
            header.dataOffset = pos;
            header.lineCount = lineNo;
            return header;
        }
        if (words[0] == "format") {
            if (words.size() < 2) throw fail("format line without a format");
            if (words[1] == "ascii") {
                header.format = PlyFormat::Ascii;
            } else if (words[1] == "binary_little_endian") {
                header.format = PlyFormat::BinaryLittleEndian;
            } else if (words[1] == "binary_big_endian") {
                header.format = PlyFormat::BinaryBigEndian;
            } else {
                throw fail("unsupported format " + quoted(words[1]));
            }
            hasFormat = true;
        } else if (words[0] == "element") {
            uint64_t count = 0;
            const auto last = words.size() == 3 ? words[2].data() + words[2].size() : nullptr;
            if (!last || std::from_chars(words[2].data(), last, count).ptr != last) {
                throw fail("expected 'element NAME COUNT', got " + quoted(line));
            }
            header.elements.push_back({std::string(words[1]), count, {}});
        } else if (words[0] == "property") {
            if (header.elements.empty()) throw fail("property before any element");
            const bool isList = words.size() == 5 && words[1] == "list";
            if (!isList && words.size() != 3) throw fail("malformed property line " + quoted(line));
            PlyProperty property{std::string(words.back()), plyTypeNamed(words[isList ? 3 : 1]),
                                 isList ? plyTypeNamed(words[2]) : PlyType::None};
            if (property.type == PlyType::None || (isList && !property.isList())) {
                throw fail("unknown property type in " + quoted(line));
            }
            header.elements.back().properties.push_back(property);
        } else {
            throw fail("unexpected " + quoted(line));
        }
    }
    throw std::runtime_error("header has no end_header line");
}

PlyCursor::PlyCursor(const std::string& data, const PlyHeader& header)
    : mData(data), mPos(header.dataOffset), mFormat(header.format), mLine(header.lineCount + 1) {}

double PlyCursor::read(PlyType type) {
    return mFormat == PlyFormat::Ascii ? readAscii() : readBinary(type);
}

double PlyCursor::readBinary(PlyType type) {
    const std::size_t size = plyTypeSize(type);
    if (size == 0) throw std::runtime_error("unknown property type");
    return decode(type, take(size));
}

const unsigned char* PlyCursor::take(std::size_t bytes) {
    if (remaining() < bytes) throw std::runtime_error("data is truncated");
    const auto* at = reinterpret_cast<const unsigned char*>(mData.data() + mPos);
    mPos += bytes;
    return at;
}

double PlyCursor::decode(PlyType type, const unsigned char* at) const {
    // The common case, our own files' floats, first and without the copy.
    if (type == PlyType::Float32 && mFormat == PlyFormat::BinaryLittleEndian) {
        return decodeAs<float>(at);
    }
    unsigned char bytes[8];
    const std::size_t size = plyTypeSize(type);
    std::memcpy(bytes, at, size);
    if (mFormat == PlyFormat::BinaryBigEndian) std::reverse(bytes, bytes + size);
    switch (type) {
        case PlyType::Int8: return decodeAs<int8_t>(bytes);
        case PlyType::UInt8: return decodeAs<uint8_t>(bytes);
        case PlyType::Int16: return decodeAs<int16_t>(bytes);
        case PlyType::UInt16: return decodeAs<uint16_t>(bytes);
        case PlyType::Int32: return decodeAs<int32_t>(bytes);
        case PlyType::UInt32: return decodeAs<uint32_t>(bytes);
        case PlyType::Float32: return decodeAs<float>(bytes);
        case PlyType::Float64: return decodeAs<double>(bytes);
        case PlyType::None: break;
    }
    throw std::runtime_error("unknown property type");
}

double PlyCursor::readAscii() {
    while (mPos < mData.size() && std::isspace(static_cast<unsigned char>(mData[mPos]))) {
        if (mData[mPos++] == '\n') ++mLine;
    }
    if (mPos == mData.size()) throw std::runtime_error("data ends early (truncated file)");
    const char* begin = mData.data() + mPos;
    std::size_t end = mPos;
    while (end < mData.size() && !std::isspace(static_cast<unsigned char>(mData[end]))) ++end;
    const char* last = mData.data() + end;
    double v = 0;
    if (*begin == '+') ++begin;  // from_chars rejects a leading '+'
    const auto [ptr, ec] = std::from_chars(begin, last, v);
    if (ptr != last || ec != std::errc()) {  // out of range (1e999) is an error too
        throw std::runtime_error("line " + std::to_string(mLine) + ": bad number '" +
                                 quoteForMessage(std::string(mData.data() + mPos, last), 40) + "'");
    }
    mPos = end;
    return v;
}

std::size_t PlyCursor::readListLength(PlyType countType) {
    const double count = read(countType);
    // Bounded before the conversion (1e300 would overflow it): no PLY count type goes
    // past 2^32 - 1.
    if (!(count >= 0) || count != std::floor(count) || count > 4294967295.0) {
        throw std::runtime_error("bad list length " + std::to_string(count));
    }
    return std::size_t(count);
}

void PlyCursor::checkFits(const PlyElement& element) const {
    std::size_t minRow = 0;
    for (const auto& p : element.properties) {
        minRow += mFormat == PlyFormat::Ascii ? 2 : plyTypeSize(p.isList() ? p.countType : p.type);
    }
    // A row without properties takes no bytes, but a file that declares more of them
    // than it has bytes is not one we wrote or will walk.
    minRow = std::max<std::size_t>(minRow, 1);
    if (element.count > (remaining() + 1) / minRow) {
        throw std::runtime_error("element '" + quoteForMessage(element.name, 80) + "' declares " +
                                 std::to_string(element.count) + " rows but only " +
                                 std::to_string(remaining()) +
                                 " bytes of data follow (the file is too short or truncated)");
    }
}

void PlyCursor::skip(const PlyProperty& property) {
    const std::size_t n = property.isList() ? readListLength(property.countType) : 1;
    for (std::size_t k = 0; k < n; ++k) read(property.type);
}

void PlyCursor::skip(const PlyElement& element) {
    checkFits(element);
    if (element.properties.empty()) return;
    for (uint64_t row = 0; row < element.count; ++row) {
        for (const auto& p : element.properties) skip(p);
    }
}

}  // namespace globular
