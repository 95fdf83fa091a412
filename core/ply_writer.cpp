#include "ply_writer.h"

namespace globular {

std::string plyHeader(const std::string& comment, const std::vector<PlyElement>& elements) {
    std::string header = "ply\nformat binary_little_endian 1.0\ncomment " + comment + "\n";
    for (const PlyElement& element : elements) {
        header += "element " + element.name + " " + std::to_string(element.count) + "\n";
        for (const PlyProperty& p : element.properties) {
            header += "property ";
            if (p.isList()) header += "list " + std::string(plyTypeName(p.countType)) + " ";
            header += std::string(plyTypeName(p.type)) + " " + p.name + "\n";
        }
    }
    return header + "end_header\n";
}

}  // namespace globular
