// Ed25519 keys and their files.
#include "ellicast/auth.h"

#include <sodium.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace ellicast::auth {

namespace {

constexpr std::string_view kPublicTag = "ellicast-ed25519-public-key";
constexpr std::string_view kSecretTag = "ellicast-ed25519-secret-key";

bool parse_hex32(std::string_view text, std::array<uint8_t, 32>& out) {
    if (text.size() != 64) return false;
    for (size_t i = 0; i < 32; ++i) {
        int v = 0;
        for (int k = 0; k < 2; ++k) {
            const char c = text[2 * i + k];
            int d;
            if (c >= '0' && c <= '9') d = c - '0';
            else if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
            else if (c >= 'A' && c <= 'F') d = c - 'A' + 10;
            else return false;
            v = v * 16 + d;
        }
        out[i] = static_cast<uint8_t>(v);
    }
    return true;
}

// The first line of a small key file, or why it cannot be read. Key files are one short line:
// anything over 4 KiB is not one.
bool read_key_line(const std::string& path, std::string& line, std::string& error) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = "cannot open key file '" + path + "': " + std::strerror(errno);
        return false;
    }
    std::string text(4097, '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<size_t>(in.gcount()));
    if (text.size() > 4096) {
        error = "'" + path + "' is not a key file (over 4 KiB)";
        return false;
    }
    const size_t end = text.find_first_of("\r\n");
    line = text.substr(0, end);
    return true;
}

// "TAG HEX" -> HEX, when the line starts with `tag`.
bool split_key_line(std::string_view line, std::string_view tag, std::string_view& hex) {
    if (line.size() < tag.size() + 1 || line.substr(0, tag.size()) != tag || line[tag.size()] != ' ') return false;
    hex = line.substr(tag.size() + 1);
    while (!hex.empty() && hex.back() == ' ') hex.remove_suffix(1);
    return true;
}

bool write_new_file(const std::string& path, const std::string& text, mode_t mode, std::string& error) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode);
    if (fd < 0) {
        error = errno == EEXIST ? "'" + path + "' exists; key files are never replaced (remove it first)"
                                : "cannot create '" + path + "': " + std::strerror(errno);
        return false;
    }
    size_t done = 0;
    while (done < text.size()) {
        const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
        if (n < 0) {
            if (errno == EINTR) continue;
            error = "cannot write '" + path + "': " + std::strerror(errno);
            ::close(fd);
            ::unlink(path.c_str());
            return false;
        }
        done += static_cast<size_t>(n);
    }
    if (::fsync(fd) != 0 || ::close(fd) != 0) {
        error = "cannot write '" + path + "': " + std::strerror(errno);
        ::unlink(path.c_str());
        return false;
    }
    return true;
}

}  // namespace

bool available() { return sodium_init() >= 0; }

KeyPair key_pair_from_seed(const Seed& seed) {
    KeyPair k;
    k.seed = seed;
    if (!available()) return k;
    unsigned char sk[crypto_sign_SECRETKEYBYTES];
    crypto_sign_seed_keypair(k.public_key.data(), sk, seed.data());
    sodium_memzero(sk, sizeof sk);
    return k;
}

KeyPair generate_key_pair() {
    Seed seed{};
    if (available()) randombytes_buf(seed.data(), seed.size());
    KeyPair k = key_pair_from_seed(seed);
    sodium_memzero(seed.data(), seed.size());
    return k;
}

std::string to_hex(std::span<const uint8_t> bytes) {
    static const char digits[] = "0123456789abcdef";
    std::string s;
    s.reserve(bytes.size() * 2);
    for (uint8_t b : bytes) {
        s.push_back(digits[b >> 4]);
        s.push_back(digits[b & 15]);
    }
    return s;
}

std::string public_key_text(const PublicKey& key) { return std::string(kPublicTag) + " " + to_hex(key) + "\n"; }
std::string secret_key_text(const KeyPair& key) { return std::string(kSecretTag) + " " + to_hex(key.seed) + "\n"; }

bool read_public_key(const std::string& file_or_hex, PublicKey& out, std::string& error) {
    if (file_or_hex.size() == 64 && parse_hex32(file_or_hex, out)) return true;
    std::string line;
    if (!read_key_line(file_or_hex, line, error)) {
        if (file_or_hex.size() == 64) error += " (nor is it 64 hex digits)";
        return false;
    }
    std::string_view hex;
    if (split_key_line(line, kSecretTag, hex)) {
        error = "'" + file_or_hex + "' is a secret key; a receiver needs the public key (the .pub file)";
        return false;
    }
    if (!split_key_line(line, kPublicTag, hex) || !parse_hex32(hex, out)) {
        error = "'" + file_or_hex + "' is not an ellicast public key: its first line must be '" +
                std::string(kPublicTag) + "' and 64 hex digits";
        return false;
    }
    return true;
}

bool read_secret_key(const std::string& path, KeyPair& out, std::string& error) {
    std::string line;
    if (!read_key_line(path, line, error)) return false;
    std::string_view hex;
    Seed seed{};
    if (split_key_line(line, kPublicTag, hex)) {
        error = "'" + path + "' is a public key; signing needs the secret key (the .key file)";
        return false;
    }
    if (!split_key_line(line, kSecretTag, hex) || !parse_hex32(hex, seed)) {
        error = "'" + path + "' is not an ellicast secret key: its first line must be '" + std::string(kSecretTag) +
                "' and 64 hex digits";
        return false;
    }
    if (!available()) {
        error = "libsodium cannot be initialized";
        return false;
    }
    out = key_pair_from_seed(seed);
    sodium_memzero(seed.data(), seed.size());
    return true;
}

bool write_key_pair(const std::string& secret_path, const std::string& public_path, const KeyPair& key,
                    std::string& error) {
    if (secret_path == public_path) {
        error = "the secret and the public key files must differ";
        return false;
    }
    struct stat st;
    for (const std::string& p : {secret_path, public_path})
        if (::lstat(p.c_str(), &st) == 0) {
            error = "'" + p + "' exists; key files are never replaced (remove it first)";
            return false;
        }
    std::string secret = secret_key_text(key);
    const bool ok = write_new_file(secret_path, secret, 0600, error);
    sodium_memzero(secret.data(), secret.size());
    if (!ok) return false;
    if (!write_new_file(public_path, public_key_text(key.public_key), 0644, error)) {
        ::unlink(secret_path.c_str());
        return false;
    }
    return true;
}

}  // namespace ellicast::auth
