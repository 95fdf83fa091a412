#include "ply_types.h"

#include <utility>

namespace globular {

PlyType plyTypeNamed(std::string_view name) {
    static const std::pair<std::string_view, PlyType> kNames[] = {
        {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
        {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
        {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
        {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
        {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
        {"float64", PlyType::Float64}};
    for (const auto& [n, t] : kNames) {
        if (n == name) return t;
    }
    return PlyType::None;
}

std::string_view plyTypeName(PlyType type) {
    switch (type) {
        case PlyType::Int8: return "char";
        case PlyType::UInt8: return "uchar";
        case PlyType::Int16: return "short";
        case PlyType::UInt16: return "ushort";
        case PlyType::Int32: return "int";
        case PlyType::UInt32: return "uint";
        case PlyType::Float32: return "float";
        case PlyType::Float64: return "double";
        case PlyType::None: break;
    }
    return "";
}

std::size_t plyTypeSize(PlyType type) {
    switch (type) {
        case PlyType::Int8:
        case PlyType::UInt8: return 1;
        case PlyType::Int16:
        case PlyType::UInt16: return 2;
        case PlyType::Int32:
        case PlyType::UInt32:
        case PlyType::Float32: return 4;
        case PlyType::Float64: return 8;
        case PlyType::None: return 0;
    }
    return 0;
}

}  // namespace globular
