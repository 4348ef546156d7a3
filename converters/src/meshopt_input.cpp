// EXT_meshopt_compression input (what gltfpack and glTF-Transform's `meshopt` write).
//
// tinygltf does not know the extension and refuses such files (their fallback buffer has no data),
// so they are rewritten before tinygltf sees them: every buffer view is copied into one new buffer,
// compressed views decoded there with meshoptimizer's decoders (vertex codec, index codecs, and the
// octahedral, quaternion and exponential filters), the extension removed, and the result handed to
// tinygltf as a GLB in memory. Everything read is checked against what is there before a decoder
// sees it (meshoptimizer asserts on bad sizes), and the decoded size is bounded.
#include "gltf_read.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace ellicast::gltf_read {

namespace {

constexpr const char* kMeshopt = "EXT_meshopt_compression";
constexpr uint64_t kMaxDecodedBytes = uint64_t(1) << 30;  // all buffer views together

[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw InputError(path + ": " + what);
}

std::vector<uint8_t> base64_decode(const std::string& text, size_t from) {
    auto value = [](char c) -> int {
        if (c >= 'A' && c <= 'Z') return c - 'A';
        if (c >= 'a' && c <= 'z') return c - 'a' + 26;
        if (c >= '0' && c <= '9') return c - '0' + 52;
        if (c == '+' || c == '-') return 62;
        if (c == '/' || c == '_') return 63;
        return -1;
    };
    std::vector<uint8_t> out;
    out.reserve((text.size() - from) / 4 * 3);
    uint32_t acc = 0;
    int bits = 0;
    for (size_t i = from; i < text.size() && text[i] != '='; ++i) {
        const int v = value(text[i]);
        if (v < 0) return {};
        acc = (acc << 6) | uint32_t(v);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(uint8_t(acc >> bits));
        }
    }
    return out;
}

size_t natural(const nlohmann::json& o, const char* key, const std::string& path, const std::string& where,
               bool required, size_t fallback = 0) {
    if (!o.contains(key)) {
        if (required) fail(path, where + " has no " + key);
        return fallback;
    }
    const auto& v = o[key];
    if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<int64_t>() >= 0))
        fail(path, where + "." + key + " is not a non-negative integer");
    const uint64_t n = v.get<uint64_t>();
    if (n > (uint64_t(1) << 40)) fail(path, where + "." + key + " is absurdly large (" + std::to_string(n) + ")");
    return size_t(n);
}

// The data of every buffer that has some (a GLB's BIN chunk, a data: URI, a file), or empty.
std::vector<std::vector<uint8_t>> buffer_data(const std::string& path, const nlohmann::json& doc,
                                              const std::vector<uint8_t>& bin, bool has_bin, const InputOptions& options) {
    std::vector<std::vector<uint8_t>> data;
    const auto& buffers = doc["buffers"];
    for (size_t b = 0; b < buffers.size(); ++b) {
        const auto& buffer = buffers[b];
        const std::string where = "buffers[" + std::to_string(b) + "]";
        if (!buffer.is_object()) fail(path, where + " is not an object");
        const size_t length = natural(buffer, "byteLength", path, where, true);
        std::vector<uint8_t> bytes;
        if (buffer.contains("uri") && buffer["uri"].is_string()) {
            const std::string uri = buffer["uri"].get<std::string>();
            if (uri.rfind("data:", 0) == 0) {
                const size_t comma = uri.find(";base64,");
                if (comma == std::string::npos) fail(path, where + " has a data: URI that is not base64");
                bytes = base64_decode(uri, comma + 8);
            } else {
                const std::filesystem::path file = resource_file(path, uri, where, options);
                try {
                    bytes = read_file_bytes(file.string());
                } catch (const InputError&) {
                    fail(path, where + " refers to " + quoted_input(file.filename().string()) + ", which cannot be read");
                }
            }
            if (bytes.size() < length)
                fail(path, where + " holds " + std::to_string(bytes.size()) + " bytes, less than its byteLength " +
                               std::to_string(length));
        } else if (b == 0 && has_bin) {
            if (bin.size() < length)
                fail(path, "the BIN chunk holds " + std::to_string(bin.size()) + " bytes, less than buffers[0].byteLength " +
                               std::to_string(length));
            bytes = bin;
        }
        bytes.resize(std::min(bytes.size(), length));
        data.push_back(std::move(bytes));
    }
    return data;
}

// Decodes one compressed buffer view into `out` (count * byteStride bytes).
void decode_view(const std::string& path, size_t v, const nlohmann::json& ext,
                 const std::vector<std::vector<uint8_t>>& buffers, std::vector<uint8_t>& out) {
    const std::string where = "bufferViews[" + std::to_string(v) + "]." + kMeshopt;
    if (!ext.is_object()) fail(path, where + " is not an object");
    const size_t source = natural(ext, "buffer", path, where, true);
    const size_t offset = natural(ext, "byteOffset", path, where, false);
    const size_t length = natural(ext, "byteLength", path, where, true);
    const size_t stride = natural(ext, "byteStride", path, where, true);
    const size_t count = natural(ext, "count", path, where, true);
    const std::string mode = ext.contains("mode") && ext["mode"].is_string() ? ext["mode"].get<std::string>() : "";
    const std::string filter =
        ext.contains("filter") && ext["filter"].is_string() ? ext["filter"].get<std::string>() : "NONE";
    if (source >= buffers.size()) fail(path, where + " refers to buffer " + std::to_string(source) + ", which does not exist");
    const auto& src = buffers[source];
    if (offset > src.size() || length > src.size() - offset)
        fail(path, where + ": bytes " + std::to_string(offset) + ".." + std::to_string(offset + length) +
                       " run past the " + std::to_string(src.size()) + " bytes of buffer " + std::to_string(source));
    const uint8_t* in = src.data() + offset;
    int status = 0;
    if (mode == "ATTRIBUTES") {
        if (stride == 0 || stride > 256 || stride % 4 != 0)
            fail(path, where + ": byteStride " + std::to_string(stride) + " (ATTRIBUTES needs a multiple of 4 up to 256)");
        out.resize(count * stride);
        status = meshopt_decodeVertexBuffer(out.data(), count, stride, in, length);
        if (status == 0) {
            if (filter == "OCTAHEDRAL") {
                if (stride != 4 && stride != 8) fail(path, where + ": the OCTAHEDRAL filter needs byteStride 4 or 8");
                meshopt_decodeFilterOct(out.data(), count, stride);
            } else if (filter == "QUATERNION") {
                if (stride != 8) fail(path, where + ": the QUATERNION filter needs byteStride 8");
                meshopt_decodeFilterQuat(out.data(), count, stride);
            } else if (filter == "EXPONENTIAL") {
                meshopt_decodeFilterExp(out.data(), count, stride);
            } else if (filter != "NONE") {
                fail(path, where + ": unknown filter '" + filter.substr(0, 40) + "'");
            }
        }
    } else if (mode == "TRIANGLES" || mode == "INDICES") {
        if (stride != 2 && stride != 4) fail(path, where + ": byteStride " + std::to_string(stride) + " (indices need 2 or 4)");
        if (filter != "NONE") fail(path, where + ": a filter on " + mode + " data");
        if (mode == "TRIANGLES" && count % 3 != 0) fail(path, where + ": TRIANGLES count " + std::to_string(count) + " is not a multiple of 3");
        out.resize(count * stride);
        status = mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(out.data(), count, stride, in, length)
                                     : meshopt_decodeIndexSequence(out.data(), count, stride, in, length);
    } else {
        fail(path, where + ": unknown mode '" + mode.substr(0, 40) + "' (ATTRIBUTES, TRIANGLES or INDICES)");
    }
    if (status != 0) fail(path, where + ": the compressed data does not decode (meshoptimizer error " + std::to_string(status) + ")");
}

void put32(std::vector<uint8_t>& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
}

}  // namespace

std::vector<std::vector<uint8_t>> gltf_buffers(const std::string& path, const std::vector<uint8_t>& bytes, bool binary,
                                               const nlohmann::json& doc, const InputOptions& options) {
    std::vector<uint8_t> bin;
    bool has_bin = false;
    if (binary) {
        const uint64_t next = 20 + uint64_t(json_text(bytes, binary).size());
        if (next + 8 <= bytes.size()) {
            uint32_t length, type;
            std::memcpy(&length, bytes.data() + next, 4);
            std::memcpy(&type, bytes.data() + next + 4, 4);
            if (type == 0x004E4942u) {
                has_bin = true;
                bin.assign(bytes.begin() + long(next + 8), bytes.begin() + long(std::min<uint64_t>(next + 8 + length, bytes.size())));
            }
        }
    }
    if (!doc.contains("buffers") || !doc["buffers"].is_array()) return {};
    return buffer_data(path, doc, bin, has_bin, options);
}

std::vector<uint8_t> decode_meshopt(const std::string& path, const std::vector<uint8_t>& bytes, bool binary,
                                    const InputOptions& options) {
    const std::string text = json_text(bytes, binary);
    if (text.find(kMeshopt) == std::string::npos) return {};
    nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
    if (doc.is_discarded() || !doc.is_object()) return {};  // tinygltf names the JSON error
    auto uses = [&](const char* list) {
        if (!doc.contains(list) || !doc[list].is_array()) return false;
        return std::any_of(doc[list].begin(), doc[list].end(), [](const auto& e) { return e == kMeshopt; });
    };
    if (!uses("extensionsUsed") && !uses("extensionsRequired")) return {};
    if (!doc.contains("buffers") || !doc["buffers"].is_array() || !doc.contains("bufferViews") ||
        !doc["bufferViews"].is_array())
        fail(path, std::string("uses ") + kMeshopt + " but has no buffers or buffer views");

    const auto buffers = gltf_buffers(path, bytes, binary, doc, options);

    // Every view copied (or decoded) into one buffer, 4-byte aligned.
    std::vector<uint8_t> merged;
    auto& views = doc["bufferViews"];
    uint64_t decoded_total = 0;
    for (size_t v = 0; v < views.size(); ++v) {
        auto& view = views[v];
        const std::string where = "bufferViews[" + std::to_string(v) + "]";
        if (!view.is_object()) fail(path, where + " is not an object");
        const size_t length = natural(view, "byteLength", path, where, true);
        std::vector<uint8_t> data;
        if (view.contains("extensions") && view["extensions"].is_object() && view["extensions"].contains(kMeshopt)) {
            const auto& ext = view["extensions"][kMeshopt];
            if (ext.is_object()) {
                const uint64_t want = uint64_t(natural(ext, "count", path, where + "." + kMeshopt, true)) *
                                      natural(ext, "byteStride", path, where + "." + kMeshopt, true);
                if (want > length)
                    fail(path, where + ": decodes to " + std::to_string(want) + " bytes, more than its byteLength " +
                                   std::to_string(length));
                decoded_total += want;
                if (decoded_total > kMaxDecodedBytes)
                    fail(path, std::string("the ") + kMeshopt + " data decodes to more than " +
                                   std::to_string(kMaxDecodedBytes >> 20) + " MiB; not read");
            }
            decode_view(path, v, ext, buffers, data);
            data.resize(length, 0);
            view["extensions"].erase(kMeshopt);
            if (view["extensions"].empty()) view.erase("extensions");
        } else {
            const size_t b = natural(view, "buffer", path, where, true);
            const size_t offset = natural(view, "byteOffset", path, where, false);
            if (b >= buffers.size()) fail(path, where + " refers to buffer " + std::to_string(b) + ", which does not exist");
            if (offset > buffers[b].size() || length > buffers[b].size() - offset)
                fail(path, where + ": bytes " + std::to_string(offset) + ".." + std::to_string(offset + length) +
                               " are not in buffer " + std::to_string(b) + " (" + std::to_string(buffers[b].size()) +
                               " bytes with data)");
            decoded_total += length;
            if (decoded_total > kMaxDecodedBytes)
                fail(path, std::string("the buffer views add up to more than ") + std::to_string(kMaxDecodedBytes >> 20) + " MiB");
            data.assign(buffers[b].begin() + long(offset), buffers[b].begin() + long(offset + length));
        }
        while (merged.size() % 4) merged.push_back(0);
        view["buffer"] = 0;
        view["byteOffset"] = merged.size();
        merged.insert(merged.end(), data.begin(), data.end());
    }
    while (merged.size() % 4) merged.push_back(0);
    doc["buffers"] = nlohmann::json::array({{{"byteLength", merged.size()}}});
    for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
        if (!doc.contains(list) || !doc[list].is_array()) continue;
        auto& l = doc[list];
        l.erase(std::remove(l.begin(), l.end(), nlohmann::json(kMeshopt)), l.end());
        if (l.empty()) doc.erase(list);
    }

    std::string json = doc.dump();
    while (json.size() % 4) json.push_back(' ');
    std::vector<uint8_t> glb;
    glb.reserve(28 + json.size() + merged.size());
    put32(glb, 0x46546C67u);  // "glTF"
    put32(glb, 2);
    put32(glb, uint32_t(12 + 8 + json.size() + 8 + merged.size()));
    put32(glb, uint32_t(json.size()));
    put32(glb, 0x4E4F534Au);  // "JSON"
    glb.insert(glb.end(), json.begin(), json.end());
    put32(glb, uint32_t(merged.size()));
    put32(glb, 0x004E4942u);  // "BIN\0"
    glb.insert(glb.end(), merged.begin(), merged.end());
    return glb;
}

}  // namespace ellicast::gltf_read
