#include "file_bytes.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace globular {

namespace fs = std::filesystem;

std::string readFileBytes(const fs::path& path, uint64_t maxBytes) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw std::runtime_error("no such file");
    if (!fs::is_regular_file(path, ec)) throw std::runtime_error("not a regular file");
    const uint64_t size = fs::file_size(path, ec);
    if (ec) throw std::runtime_error(ec.message());
    if (size > maxBytes) {
        throw std::runtime_error("the file is " + std::to_string(size) +
                                 " bytes, more than the limit of " + std::to_string(maxBytes));
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(std::strerror(errno));
    std::string data(size, '\0');
    in.read(data.data(), std::streamsize(data.size()));
    if (std::size_t(in.gcount()) != data.size()) {
        throw std::runtime_error("read failed (the file changed size while being read)");
    }
    return data;
}

}  // namespace globular
