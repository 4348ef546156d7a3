// Container files (.ellc): a recorded stream, read back with resynchronization after damage.
#include "ellicast/format.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include <fcntl.h>
#include <unistd.h>

namespace ellicast {

std::vector<uint8_t> write_container(const std::vector<std::vector<uint8_t>>& packets) {
    size_t total = kContainerHeaderSize;
    for (const auto& p : packets) total += p.size();
    std::vector<uint8_t> out;
    out.reserve(total);
    for (uint8_t b : kContainerSignature) out.push_back(b);
    out.push_back(kContainerVersion);
    out.insert(out.end(), 3, 0);
    for (const auto& p : packets) out.insert(out.end(), p.begin(), p.end());
    return out;
}

ContainerContents read_container(std::span<const uint8_t> bytes) {
    ContainerContents contents;
    if (bytes.size() < kContainerHeaderSize) {
        contents.header_error = bytes.size() >= kContainerSignature.size() &&
                                        std::equal(kContainerSignature.begin(), kContainerSignature.end(), bytes.begin())
                                    ? Error::TooShort
                                    : Error::BadSignature;
        return contents;
    }
    if (!std::equal(kContainerSignature.begin(), kContainerSignature.end(), bytes.begin())) {
        contents.header_error = Error::BadSignature;
        return contents;
    }
    if (bytes[8] != kContainerVersion) {
        contents.header_error = Error::UnsupportedContainer;
        return contents;
    }
    size_t pos = kContainerHeaderSize;
    const size_t end = bytes.size();
    while (pos < end) {
        PacketView view;
        Error e = parse_packet_prefix(bytes.subspan(pos), view);
        if (e == Error::Ok) {
            contents.packets.push_back({pos, view});
            pos += view.size;
            continue;
        }
        // Damage: the next packet is the next offset where a whole valid packet starts.
        DamagedRegion region{pos, 0, e};
        size_t next = pos + 1;
        for (;;) {
            const void* hit = next < end ? std::memchr(bytes.data() + next, kPacketMagic[0], end - next) : nullptr;
            if (!hit) {
                next = end;
                break;
            }
            next = static_cast<const uint8_t*>(hit) - bytes.data();
            if (parse_packet_prefix(bytes.subspan(next), view) == Error::Ok) break;
            ++next;
        }
        region.length = next - pos;
        contents.damaged.push_back(region);
        pos = next;
    }
    return contents;
}

Error read_file(const std::string& path, std::vector<uint8_t>& out, std::string& message) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
        message = path + ": is a directory";
        return Error::IoError;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        message = path + ": cannot open (" + std::strerror(errno) + ")";
        return Error::IoError;
    }
    in.seekg(0, std::ios::end);
    std::streamoff size = in.tellg();
    if (size < 0) {
        message = path + ": cannot determine the size";
        return Error::IoError;
    }
    in.seekg(0, std::ios::beg);
    std::vector<uint8_t> data(static_cast<size_t>(size));
    if (size > 0 && !in.read(reinterpret_cast<char*>(data.data()), size)) {
        message = path + ": read failed after " + std::to_string(in.gcount()) + " bytes";
        return Error::IoError;
    }
    out = std::move(data);
    return Error::Ok;
}

Error write_file(const std::string& path, std::span<const uint8_t> bytes, std::string& message) {
    namespace fs = std::filesystem;
    const fs::path target(path);
    const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::random_device random;
    std::string temp;
    int fd = -1;
    for (int attempt = 0; attempt < 16 && fd < 0; ++attempt) {
        char suffix[16];
        std::snprintf(suffix, sizeof suffix, "%08x%04x", random(), random() & 0xFFFFu);
        std::string name = ".";
        name += target.filename().string();
        name += '.';
        name += suffix;
        name += ".partial";
        temp = (folder / name).string();
        fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
        if (fd < 0 && errno != EEXIST) break;
    }
    if (fd < 0) {
        message = path + ": cannot create a temporary file in " + folder.string() + " (" + std::strerror(errno) + ")";
        return Error::IoError;
    }
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            message = path + ": write failed (" + std::strerror(errno) + ")";
            ::close(fd);
            ::unlink(temp.c_str());
            return Error::IoError;
        }
        done += size_t(n);
    }
    if (::close(fd) != 0) {
        message = path + ": write failed (" + std::strerror(errno) + ")";
        ::unlink(temp.c_str());
        return Error::IoError;
    }
    std::error_code ec;
    std::filesystem::rename(temp, path, ec);
    if (ec) {
        message = path + ": cannot move the finished file into place (" + ec.message() + ")";
        std::filesystem::remove(temp, ec);
        return Error::IoError;
    }
    return Error::Ok;
}

}  // namespace ellicast
