#pragma once
// The one PLY reader under every PLY input: globule clouds (globule_cache.h) and
// surface meshes (surface/mesh.h). It parses the header (ascii, binary little and big
// endian) and walks the data value by value, bounded by the file's size: an element's
// declared count is checked against the bytes that follow before anything is
// allocated, and every read checks the end. Errors are std::runtime_error; the callers
// add the file's name.

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "ply_types.h"

namespace globular {

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::None;       ///< value type (of the items, for a list)
    PlyType countType = PlyType::None;  ///< the length's type; None unless a list

    bool isList() const { return countType != PlyType::None; }
};

struct PlyElement {
    std::string name;
    uint64_t count = 0;
    std::vector<PlyProperty> properties;

    /// Index of the first non-list property with one of @p names, or -1.
    int find(std::initializer_list<const char*> names) const;
};

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyHeader {
    PlyFormat format = PlyFormat::Ascii;
    std::vector<PlyElement> elements;
    std::size_t dataOffset = 0;  ///< bytes
    int lineCount = 0;           ///< header lines, for ascii data line numbers
};

/// @throw std::runtime_error naming the header line.
PlyHeader parsePlyHeader(const std::string& data);

/// Walks the data after the header, one value at a time.
class PlyCursor {
public:
    PlyCursor(const std::string& data, const PlyHeader& header);

    double read(PlyType type);
    /// Whether the data is binary: then take() and decode() read it a row at a time, with
    /// one check of the end for the row rather than one per value.
    bool isBinary() const { return mFormat != PlyFormat::Ascii; }
    /// The next @p bytes of binary data, checked to be there; the cursor moves past them.
    const unsigned char* take(std::size_t bytes);
    /// One binary value of @p type (not None) at @p bytes, in the file's byte order.
    double decode(PlyType type, const unsigned char* bytes) const;
    /// A list's length, read as @p countType and checked to be a whole number that fits.
    std::size_t readListLength(PlyType countType);
    /// Refuses @p element when its declared count cannot fit in the bytes left (each
    /// row takes at least one byte, or an ascii value and a separator per property).
    void checkFits(const PlyElement& element) const;
    /// Skips every row of @p element (after checkFits).
    void skip(const PlyElement& element);
    /// Skips one value of @p property (a whole list for a list property).
    void skip(const PlyProperty& property);
    std::size_t remaining() const { return mData.size() - mPos; }
    /// The current line of ascii data (1-based, counting the header).
    int line() const { return mLine; }

private:
    double readBinary(PlyType type);
    double readAscii();

    const std::string& mData;
    std::size_t mPos;
    PlyFormat mFormat;
    int mLine;
};

}  // namespace globular
