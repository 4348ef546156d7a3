// OBJ, PLY, OFF and STL through OpenMesh's readers, into the same Mesh a glTF primitive gives:
// per-corner texture coordinates (OBJ "vt") split vertices at seams, colours become linear RGBA;
// faces of more than three corners are triangulated here (polygon.h), not fanned by OpenMesh.
#include "ellicast/converters/mesh_input.h"
#include "ellicast/converters/polygon.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

namespace ellicast {

namespace {

struct InputTraits : public OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3f Point;
    typedef OpenMesh::Vec3f Normal;
    typedef OpenMesh::Vec4f Color;
    typedef OpenMesh::Vec2f TexCoord2D;
    VertexAttributes(OpenMesh::Attributes::Normal | OpenMesh::Attributes::Color | OpenMesh::Attributes::TexCoord2D);
    HalfedgeAttributes(OpenMesh::Attributes::TexCoord2D | OpenMesh::Attributes::PrevHalfedge);
    FaceAttributes(OpenMesh::Attributes::None);
};
// A polygon mesh: each face keeps its corners in the file's order, with their texture coordinates
// (a triangle mesh would fan every polygon from its first corner, wrong for a concave one).
using InputMesh = OpenMesh::PolyMesh_ArrayKernelT<InputTraits>;

// A non-simple polygon of more corners than this is refused: its fan would cover area outside it
// and make the encoder's inside test slow (every point near every long triangle of the fan).
constexpr size_t kMaxFannedCorners = 4096;

// OpenMesh's importer, but with the check for a corner given twice in a face sorted instead of
// pairwise (O(n^2): 200,000 corners took seconds); faces of up to 64 corners go through
// OpenMesh's own code unchanged.
class PolygonImporter : public OpenMesh::IO::ImporterT<InputMesh> {
public:
    explicit PolygonImporter(InputMesh& mesh) : ImporterT(mesh), mesh_(mesh) {}

    OpenMesh::FaceHandle add_face(const VHandles& indices) override {
        if (indices.size() <= 64) {
            // A face OpenMesh cannot add (a duplicate, non-manifold or wrongly wound one) gets vertices of
            // its own, one per corner in order, with only their position: their colours, normals and
            // texture coordinates were read uninitialised (the same PLY gave different streams).
            const size_t before = mesh_.n_vertices();
            const OpenMesh::FaceHandle fh = ImporterT::add_face(indices);
            if (mesh_.n_vertices() == before + indices.size())
                for (size_t j = 0; j < indices.size(); ++j)
                    copy_properties(indices[j], OpenMesh::VertexHandle(int(before + j)));
            return fh;
        }
        VHandles sorted = indices;
        std::sort(sorted.begin(), sorted.end());
        for (auto vh : sorted)
            if (!mesh_.is_valid_handle(vh)) {
                omerr() << "ImporterT: Face contains invalid vertex index\n";
                return OpenMesh::FaceHandle();
            }
        if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
            omerr() << "ImporterT: Face has equal vertices\n";
            return OpenMesh::FaceHandle();
        }
        OpenMesh::FaceHandle fh = mesh_.add_face(indices);
        if (!fh.is_valid()) {
            // Non-manifold: the face gets vertices of its own, as OpenMesh's importer does.
            VHandles own(indices.size());
            for (size_t j = 0; j < indices.size(); ++j) {
                const auto p = mesh_.point(indices[j]);
                own[j] = mesh_.add_vertex(p);
                copy_properties(indices[j], own[j]);
            }
            fh = mesh_.add_face(own);
        }
        return fh;
    }

private:
    // The per-vertex attributes of `from` given to its copy `to`.
    void copy_properties(OpenMesh::VertexHandle from, OpenMesh::VertexHandle to) {
        if (!mesh_.is_valid_handle(from) || !mesh_.is_valid_handle(to)) return;
        if (mesh_.has_vertex_colors()) mesh_.set_color(to, mesh_.color(from));
        if (mesh_.has_vertex_normals()) mesh_.set_normal(to, mesh_.normal(from));
        if (mesh_.has_vertex_texcoords2D()) mesh_.set_texcoord2D(to, mesh_.texcoord2D(from));
    }
    InputMesh& mesh_;
};

float srgb_to_linear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// OpenMesh reports trouble (complex edges, unreadable lines) on omerr. One sink is connected to it
// once for the whole process (OpenMesh's disconnect never frees what connect allocated: connecting
// a capture per load leaked 32 bytes each time); while a load runs it keeps what OpenMesh says (at
// most 1 MB), otherwise it passes it on to std::cerr as before.
class ErrorSink : public std::streambuf {
public:
    bool capturing = false;
    std::string text;

protected:
    int overflow(int c) override {
        if (c == traits_type::eof()) return traits_type::not_eof(c);
        const char ch = char(c);
        xsputn(&ch, 1);
        return c;
    }
    std::streamsize xsputn(const char* s, std::streamsize n) override {
        if (!capturing) {
            std::cerr.write(s, n);
        } else if (text.size() < (1u << 20)) {
            text.append(s, size_t(std::min<std::streamsize>(n, std::streamsize((1u << 20) - text.size()))));
        }
        return n;
    }
};

ErrorSink& error_sink() {
    static ErrorSink sink;
    static std::ostream stream(&sink);
    static const bool connected = [] {
        omerr().disconnect(std::cerr);
        return omerr().connect(stream);
    }();
    (void)connected;
    return sink;
}

class CapturedErrors {
public:
    CapturedErrors() : sink_(error_sink()) {
        omerr().flush();
        sink_.text.clear();
        sink_.capturing = true;
        omlog().disable();
    }
    ~CapturedErrors() {
        omerr().flush();
        sink_.capturing = false;
        sink_.text.clear();
        omlog().enable();
    }
    std::vector<std::string> lines() {
        omerr().flush();
        std::vector<std::string> out;
        std::istringstream in(sink_.text);
        for (std::string line; std::getline(in, line);)
            if (!line.empty()) out.push_back(line);
        return out;
    }

private:
    ErrorSink& sink_;
};

// OpenMesh's readers trust their input: an OBJ face index out of range corrupts the heap, a PLY
// header cut short makes the reader spin, an unparsable "v" line is skipped and shifts every later
// index. Every file is checked here first, and the first problem is named with its line or size.

[[noreturn]] void bad(const std::string& path, size_t line, const std::string& what) {
    throw InputError(path + ": line " + std::to_string(line) + ": " + what);
}

uint64_t file_size(const std::string& path) {
    std::error_code ec;
    auto size = std::filesystem::file_size(path, ec);
    return ec ? 0 : uint64_t(size);
}

// OBJ, checked the way OpenMesh's reader reads it (two passes: every "v" / "vt" / "vn" first, then
// the faces), so that what passes here cannot make it index outside its arrays: lines trimmed of
// " \t\r\n", keyword up to the first white space; "v" / "vt" / "vn" with numbers a float holds;
// face corners "v", "v/t", "v//n", "v/t/n" whose positive indices refer to an element anywhere in the
// file (OBJ allows a face before its vertices) and whose negative indices count back from the last
// element defined before the face.
void check_obj(const std::string& path) {
    std::ifstream in(path);
    const char* const kinds[3] = {"vertex", "texture coordinate", "normal"};
    const char* const plural[3] = {"vertices", "texture coordinates", "normals"};
    long long counts[3] = {0, 0, 0};  // v, vt, vn so far
    // The largest positive index of each kind, with where it was: checked against the totals at the end.
    struct Reference {
        long long index = 0;
        size_t line = 0;
        std::string corner;
    } largest[3];
    std::istringstream fields;
    std::string line, keyword;
    for (size_t number = 1; std::getline(in, line); ++number) {
        const size_t first = line.find_first_not_of(" \t\r\n");
        if (first == std::string::npos || line[first] == '#' || std::isspace(static_cast<unsigned char>(line[first])))
            continue;
        size_t end = first;
        while (end < line.size() && !std::isspace(static_cast<unsigned char>(line[end]))) ++end;
        keyword.assign(line, first, end - first);
        const int kind = keyword == "v" ? 0 : keyword == "vt" ? 1 : keyword == "vn" ? 2 : -1;
        if (kind >= 0) {
            ++counts[kind];
            fields.str(line.substr(end));
            fields.clear();
            const int needed = kind == 1 ? 2 : 3;
            for (int k = 0; k < needed; ++k) {
                float value = 0;
                fields >> value;
                if (fields.fail() || !std::isfinite(value))
                    bad(path, number, std::string(kinds[kind]) + " value " + std::to_string(k + 1) +
                                          " is not a finite number a float holds (" + quoted_input(line) + ")");
            }
            continue;
        }
        if (keyword != "f") continue;
        fields.str(line.substr(end));
        fields.clear();
        std::string corner;
        while (fields >> corner) {
            size_t start = 0;
            for (int part = 0; part < 3 && start <= corner.size(); ++part) {
                size_t slash = corner.find('/', start);
                std::string text = corner.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
                start = slash == std::string::npos ? corner.size() + 1 : slash + 1;
                if (text.empty() && part > 0) continue;  // "v//n", "v/t/"
                char* stop = nullptr;
                errno = 0;
                long long index = std::strtoll(text.c_str(), &stop, 10);
                if (text.empty() || *stop != '\0' || errno == ERANGE || index == 0 || index > INT32_MAX ||
                    index < -INT32_MAX)
                    bad(path, number, "face corner " + quoted_input(corner) + " is not a " + kinds[part] +
                                          " index (a nonzero whole number)");
                if (index < 0 && -index > counts[part])
                    bad(path, number, "face corner " + quoted_input(corner) + " counts back " + std::to_string(-index) + " " +
                                          (-index == 1 ? kinds[part] : plural[part]) + " from line " +
                                          std::to_string(number) + ", but only " + std::to_string(counts[part]) +
                                          " are defined before it");
                if (index > largest[part].index) largest[part] = {index, number, corner};
            }
        }
    }
    if (in.bad()) throw InputError(path + ": could not be read to the end");
    for (int part = 0; part < 3; ++part)
        if (largest[part].index > counts[part])
            bad(path, largest[part].line, "face corner " + quoted_input(largest[part].corner) + " refers to " + kinds[part] + " " +
                                              std::to_string(largest[part].index) + ", but the file defines " +
                                              std::to_string(counts[part]) + " " + plural[part]);
}

// PLY: a complete header of known types, then a body holding every declared element whole, with
// face indices that refer to declared vertices (ASCII and binary bodies are walked value by value).
void check_ply(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    struct Property {
        bool list = false;
        std::string count_type, type, name;
    };
    struct Element {
        std::string name;
        uint64_t count = 0;
        std::vector<Property> properties;
    };
    std::vector<Element> elements;
    auto type_size = [](const std::string& t) -> int {
        if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
        if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
        if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
        if (t == "double" || t == "float64") return 8;
        return 0;
    };
    std::string line, format;
    size_t number = 0;
    bool ended = false;
    uint64_t header_bytes = 0;
    while (std::getline(in, line)) {
        ++number;
        header_bytes += line.size() + 1;
        if (header_bytes > (1u << 20)) bad(path, number, "the PLY header does not end within 1 MB");
        if (!line.empty() && line.back() == '\r') line.pop_back();
        // OpenMesh reads the header word by word across lines: a control byte or a word more than a
        // line holds would be read as the next keyword (a NUL-separated "property" before any
        // element crashed its reader), so the header must be plain lines of exactly their words.
        for (unsigned char c : line)
            if ((c < 0x20 && c != '\t') || c == 0x7F) {
                char hex[8];
                std::snprintf(hex, sizeof hex, "0x%02X", c);
                bad(path, number, std::string("the PLY header holds the control byte ") + hex);
            }
        std::istringstream words(line);
        std::string word, extra;
        words >> word;
        if (number == 1) {
            if (word != "ply" || (words >> extra)) bad(path, 1, "not a PLY file (it must start with a line \"ply\")");
        } else if (word == "format") {
            std::string version;
            words >> format >> version;
            if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
                bad(path, number, "unknown PLY format \"" + format + "\"");
            if (version != "1.0") bad(path, number, "PLY version " + quoted_input(version) + " (1.0 is the only one)");
            if (words >> extra) bad(path, number, "a word more than the format line holds: " + quoted_input(line));
        } else if (word == "element") {
            Element e;
            long long count = -1;
            words >> e.name >> count;
            if (!words || count < 0 || count > (1ll << 31)) bad(path, number, "bad element line " + quoted_input(line));
            e.count = uint64_t(count);
            if (words >> extra) bad(path, number, "a word more than an element line holds: " + quoted_input(line));
            elements.push_back(e);
        } else if (word == "property") {
            if (elements.empty()) bad(path, number, "a property before any element");
            Property p;
            std::string type;
            words >> type;
            if (type == "list") {
                p.list = true;
                words >> p.count_type >> p.type >> p.name;
                if (!type_size(p.count_type) || !type_size(p.type))
                    bad(path, number, "unknown property type in " + quoted_input(line));
            } else {
                p.type = type;
                words >> p.name;
                if (!type_size(p.type)) bad(path, number, "unknown property type \"" + type + "\"");
            }
            if (p.name.empty()) bad(path, number, "a property without a name: " + quoted_input(line));
            if (words >> extra) bad(path, number, "a word more than a property line holds: " + quoted_input(line));
            elements.back().properties.push_back(p);
        } else if (word == "end_header") {
            if (words >> extra) bad(path, number, "words after end_header: " + quoted_input(line));
            ended = true;
            break;
        } else if (word != "comment" && word != "obj_info" && !word.empty()) {
            bad(path, number, "unexpected PLY header line " + quoted_input(line));
        }
    }
    if (!ended) bad(path, number, "the PLY header has no end_header line (the file is cut short?)");
    if (format.empty()) bad(path, number, "the PLY header has no format line");

    uint64_t vertices = 0;
    for (const auto& e : elements)
        if (e.name == "vertex") vertices = e.count;
    const bool ascii = format == "ascii";
    const bool swap = format == "binary_big_endian";
    std::string token;
    // A property's type, looked up once: its size in bytes and how its bytes read.
    enum class Kind { I8, U8, I16, U16, I32, U32, F32, F64 };
    auto kind_of = [](const std::string& t) {
        if (t == "char" || t == "int8") return Kind::I8;
        if (t == "uchar" || t == "uint8") return Kind::U8;
        if (t == "short" || t == "int16") return Kind::I16;
        if (t == "ushort" || t == "uint16") return Kind::U16;
        if (t == "int" || t == "int32") return Kind::I32;
        if (t == "uint" || t == "uint32") return Kind::U32;
        if (t == "float" || t == "float32") return Kind::F32;
        return Kind::F64;
    };
    // The next value of the body as a double; false at the end of the file or on a non-number.
    auto next = [&](Kind kind, int size, double& value) -> bool {
        if (ascii) {
            if (!(in >> token)) return false;
            char* end = nullptr;
            value = std::strtod(token.c_str(), &end);
            return *end == '\0' && std::isfinite(value);
        }
        unsigned char b[8];
        if (!in.read(reinterpret_cast<char*>(b), size)) return false;
        if (swap) std::reverse(b, b + size);
        switch (kind) {
        case Kind::I8: value = double(int8_t(b[0])); break;
        case Kind::U8: value = b[0]; break;
        case Kind::I16: { int16_t v; std::memcpy(&v, b, 2); value = v; break; }
        case Kind::U16: { uint16_t v; std::memcpy(&v, b, 2); value = v; break; }
        case Kind::I32: { int32_t v; std::memcpy(&v, b, 4); value = v; break; }
        case Kind::U32: { uint32_t v; std::memcpy(&v, b, 4); value = v; break; }
        case Kind::F32: { float v; std::memcpy(&v, b, 4); value = v; break; }
        case Kind::F64: { double v; std::memcpy(&v, b, 8); value = v; break; }
        }
        return true;
    };
    for (const auto& e : elements) {
        const bool faces = e.name == "face";
        struct Read {
            Kind count_kind, kind;
            int count_size, size;
            bool indices;
        };
        std::vector<Read> reads;
        for (const auto& p : e.properties)
            reads.push_back({kind_of(p.count_type), kind_of(p.type), type_size(p.count_type), type_size(p.type),
                             faces && (p.name == "vertex_indices" || p.name == "vertex_index")});
        for (uint64_t i = 0; i < e.count; ++i)
            for (size_t j = 0; j < reads.size(); ++j) {
                const Read& r = reads[j];
                // Where a value stands, for a message (made only when one is needed).
                auto where = [&] { return "PLY " + e.name + " " + std::to_string(i) + ", property " + e.properties[j].name; };
                double value = 0;
                if (!e.properties[j].list) {
                    if (!next(r.kind, r.size, value))
                        throw InputError(path + ": " + where() + ": missing or not a finite number (the file is cut "
                                                "short or damaged)");
                    continue;
                }
                if (!next(r.count_kind, r.count_size, value) || value < 0 || value > 1024 || value != std::floor(value))
                    throw InputError(path + ": " + where() + ": bad list length");
                const int items = int(value);
                for (int k = 0; k < items; ++k) {
                    if (!next(r.kind, r.size, value))
                        throw InputError(path + ": " + where() + ": missing or not a finite number (the file is cut "
                                                "short or damaged)");
                    if (r.indices && (value < 0 || value >= double(vertices) || value != std::floor(value)))
                        throw InputError(path + ": " + where() + ": index " + std::to_string(value) +
                                         " is not one of the " + std::to_string(vertices) + " vertices");
                }
            }
    }
}

// OFF, read the way OpenMesh's ASCII reader reads it, with the same stream extractions, so that what
// passes here is what OpenMesh reads: the first line is the header ([ST][C][N]OFF); the three counts
// are the next three words wherever they stand; a vertex is 3 floats (6 with N) and the rest of its
// line; a face is a corner count and that many indices (and, with C, the rest of its line). OpenMesh
// pushes as many corners as a face declares even past the end of the file, so a corner count is
// checked before anything is read for it (found by fuzz_readers: a face "-3 0 1 2" read as
// 4,294,967,293 corners took 2 GB, and a vertical tab on the counts line hid it from a line-by-line
// check).
void check_off(const std::string& path) {
    // An ASCII OFF file is text: a control byte (a NUL, say) stops OpenMesh's number reading
    // without stopping its loops (found by fuzz_readers: a 488-byte file with NULs on its counts line
    // kept OpenMesh reading for 13 s, and past 2 GB under AddressSanitizer).
    {
        std::ifstream raw(path, std::ios::binary);
        size_t line_number = 1;
        char c;
        while (raw.get(c)) {
            const auto b = static_cast<unsigned char>(c);
            if (b == '\n') {
                ++line_number;
            } else if (b < 0x20 && b != '\t' && b != '\r' && b != '\v' && b != '\f') {
                char hex[8];
                std::snprintf(hex, sizeof hex, "0x%02X", b);
                bad(path, line_number, std::string("a control byte (") + hex +
                                           ") in an ASCII OFF file; binary OFF files are not supported");
            }
        }
    }
    // The line a stream position is on (for messages only).
    auto line_at = [&path](std::streamoff position) {
        std::ifstream raw(path, std::ios::binary);
        size_t line = 1;
        char c;
        for (std::streamoff i = 0; i < position && raw.get(c); ++i)
            if (c == '\n') ++line;
        return line;
    };
    std::ifstream in(path);
    const uint64_t size = file_size(path);
    // Skips to the next word and says where it starts (the file's end when there is none).
    auto next_word = [&in, size]() -> std::streamoff {
        in >> std::ws;
        return in.eof() ? std::streamoff(size) : std::streamoff(in.tellg());
    };
    std::string header;
    if (!std::getline(in, header)) throw InputError(path + ": an empty file, not an OFF file");
    size_t p = 0;
    bool normals = false, colours = false;
    if (header.compare(p, 2, "ST") == 0) p += 2;
    if (header.compare(p, 1, "C") == 0) colours = true, p += 1;
    if (header.compare(p, 1, "N") == 0) normals = true, p += 1;
    if (header.compare(p, 1, "4") == 0 || header.compare(p, 1, "n") == 0)
        bad(path, 1, "OFF files with other than 3 coordinates a vertex (4OFF, nOFF) are not supported");
    if (header.compare(p, 3, "OFF") != 0)
        bad(path, 1, "not an OFF file: the first line must start with OFF, COFF, NOFF, STOFF or a mix (" +
                         quoted_input(header) + ")");
    if (header.find("BINARY", p + 3) != std::string::npos)
        bad(path, 1, "binary OFF files are not supported (their counts cannot be checked before reading)");

    // A count: the next word, read as OpenMesh reads it (an unsigned int), refused when negative.
    auto count = [&](const char* what) -> unsigned {
        const std::streamoff at = next_word();
        if (in.peek() == '-') bad(path, line_at(at), std::string("a negative ") + what);
        const bool digit = std::isdigit(in.peek()) != 0;
        unsigned value = 0;
        if (!(in >> value) && digit)
            bad(path, line_at(at), std::string("the OFF header's ") + what +
                                       " is beyond 4,294,967,295, more than the file can hold");
        if (!in)
            bad(path, line_at(at), std::string("the OFF header must give vertex and face counts after its first line (no ") +
                                       what + ")");
        return value;
    };
    const unsigned vertices = count("vertex count");
    const std::streamoff counts_at = in.tellg();
    const unsigned faces = count("face count");
    unsigned edges = 0;
    in >> edges;  // OpenMesh reads and ignores it; a failure here leaves its stream failed, as ours
    if (uint64_t(vertices) > size / 2 || uint64_t(faces) > size / 2 || (uint64_t(vertices) + faces) * 2 > size)
        bad(path, line_at(counts_at), "the OFF header declares " + std::to_string(vertices) + " vertices and " +
                                          std::to_string(faces) + " faces, more than the file can hold");
    // Every vertex and face must read whole: once an extraction fails, OpenMesh's stream stays failed
    // and each later face keeps the corner count it last read (the vertex count, if no face was
    // read), pushing that many corners a face: faces x vertices (found by fuzz_readers: a corner count
    // past 2^32 - 1 is read as 4,294,967,295 with the stream failed).
    std::string rest;
    float value;
    const int numbers = normals ? 6 : 3;
    for (unsigned i = 0; i < vertices; ++i) {
        const std::streamoff at = next_word();
        for (int k = 0; k < numbers; ++k)
            if (!(in >> value))
                bad(path, line_at(at),
                    "vertex " + std::to_string(i) + " of " + std::to_string(vertices) + ": " +
                        (normals ? "6 numbers (position and normal)" : "3 numbers (its position)") +
                        " expected, the file " + (in.eof() ? "ends" : "holds something else") + " after " +
                        std::to_string(k));
        std::getline(in, rest);
    }
    for (unsigned f = 0; f < faces; ++f) {
        const std::streamoff at = next_word();
        const std::string face = "face " + std::to_string(f) + " of " + std::to_string(faces);
        if (in.peek() == '-') bad(path, line_at(at), face + " declares a negative corner count");
        unsigned corners = 0;
        if (!(in >> corners))
            bad(path, line_at(at), face + ": a corner count expected, the file " +
                                       (in.eof() ? "ends" : "holds something else or a number past 4,294,967,295"));
        if (corners < 3 || corners > vertices)
            bad(path, line_at(at), face + " declares " + std::to_string(corners) + " corners; a face needs 3 to " +
                                       std::to_string(vertices) + " (the vertex count)");
        unsigned given = 0, index;
        while (given < corners && in >> index) ++given;
        if (given < corners)
            bad(path, line_at(at), face + " declares " + std::to_string(corners) + " corners but the file " +
                                       (in.eof() ? "ends" : "holds something other than a vertex number") +
                                       " after " + std::to_string(given) + " of them");
        if (colours) std::getline(in, rest);
    }
}

// STL: binary (84 + 50 bytes per triangle, exactly) or ASCII ("solid ...").
void check_stl(const std::string& path) {
    uint64_t size = file_size(path);
    std::ifstream in(path, std::ios::binary);
    char head[84] = {};
    in.read(head, 84);
    if (size >= 84) {
        uint32_t count;
        std::memcpy(&count, head + 80, 4);
        if (84 + 50 * uint64_t(count) == size) return;
    }
    if (size >= 5 && std::string(head, 5) == "solid") return;
    throw InputError(path + ": neither a binary STL (84 + 50 bytes per triangle, here " + std::to_string(size) +
                     " bytes) nor an ASCII STL (starting with \"solid\")");
}

}  // namespace

LoadResult load_openmesh(const std::string& path) {
    InputMesh om;
    OpenMesh::IO::Options opt;
    opt += OpenMesh::IO::Options::VertexNormal;
    opt += OpenMesh::IO::Options::VertexColor;
    opt += OpenMesh::IO::Options::VertexTexCoord;
    opt += OpenMesh::IO::Options::FaceTexCoord;
    std::string ext = std::filesystem::path(path).extension().string();
    for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".obj") check_obj(path);
    else if (ext == ".ply") check_ply(path);
    else if (ext == ".off") check_off(path);
    else if (ext == ".stl") check_stl(path);
    std::vector<std::string> reader_messages;
    bool ok;
    {
        CapturedErrors capture;
        PolygonImporter importer(om);
        ok = OpenMesh::IO::IOManager().read(path, importer, opt);
        reader_messages = capture.lines();
    }
    if (!ok) {
        std::string why = reader_messages.empty() ? "the reader rejected it" : reader_messages.front();
        throw InputError(path + ": not a readable mesh file: " + why);
    }

    LoadResult result;
    size_t complex = 0;
    for (const auto& line : reader_messages)
        if (line.find("complex") != std::string::npos) ++complex;
    if (complex)
        result.warnings.push_back(path + ": " + std::to_string(complex) +
                                  " faces touched non-manifold edges or vertices; the reader duplicated their "
                                  "vertices to keep them");
    else if (!reader_messages.empty())
        result.warnings.push_back(path + ": reader: " + reader_messages.front());

    Mesh mesh;
    mesh.name = std::filesystem::path(path).stem().string();
    const bool normals = opt.check(OpenMesh::IO::Options::VertexNormal);
    const bool colors = opt.check(OpenMesh::IO::Options::VertexColor);
    const bool corner_uv = opt.check(OpenMesh::IO::Options::FaceTexCoord);
    const bool vertex_uv = !corner_uv && opt.check(OpenMesh::IO::Options::VertexTexCoord);
    mesh.colors_have_alpha = colors && opt.check(OpenMesh::IO::Options::ColorAlpha);

    // With per-corner texture coordinates a vertex is split once per distinct (vertex, uv).
    std::map<std::pair<int, std::array<float, 2>>, uint32_t> split;
    std::vector<uint32_t> plain(om.n_vertices(), UINT32_MAX);
    std::vector<bool> used(om.n_vertices(), false);
    auto emit = [&](InputMesh::VertexHandle vh, const std::array<float, 2>* uv) -> uint32_t {
        used[vh.idx()] = true;
        uint32_t* slot;
        if (uv) {
            auto [it, inserted] = split.try_emplace({vh.idx(), *uv}, uint32_t(mesh.positions.size()));
            if (!inserted) return it->second;
            slot = &it->second;
        } else {
            if (plain[vh.idx()] != UINT32_MAX) return plain[vh.idx()];
            plain[vh.idx()] = uint32_t(mesh.positions.size());
            slot = &plain[vh.idx()];
        }
        auto p = om.point(vh);
        mesh.positions.push_back({p[0], p[1], p[2]});
        if (normals) {
            auto n = om.normal(vh);
            mesh.normals.push_back({n[0], n[1], n[2]});
        }
        if (colors) {
            auto c = om.color(vh);
            mesh.colors.push_back({srgb_to_linear(c[0]), srgb_to_linear(c[1]), srgb_to_linear(c[2]),
                                   mesh.colors_have_alpha ? c[3] : 1.0f});
        }
        if (uv) mesh.texcoords.push_back(*uv);
        else if (vertex_uv) {
            auto t = om.texcoord2D(vh);
            mesh.texcoords.push_back({t[0], t[1]});
        }
        return *slot;
    };

    mesh.triangles.reserve(om.n_faces());
    std::vector<uint32_t> corners;
    std::vector<std::array<float, 3>> points;
    size_t not_simple = 0;
    for (auto fh : om.faces()) {
        corners.clear();
        points.clear();
        for (auto heh : om.fh_range(fh)) {
            auto vh = om.to_vertex_handle(heh);
            if (corner_uv) {
                auto t = om.texcoord2D(heh);
                std::array<float, 2> uv{t[0], t[1]};
                corners.push_back(emit(vh, &uv));
            } else {
                corners.push_back(emit(vh, nullptr));
            }
        }
        if (corners.size() == 3) {
            mesh.triangles.push_back({corners[0], corners[1], corners[2]});
            continue;
        }
        if (corners.size() < 3) continue;
        for (uint32_t c : corners) points.push_back(mesh.positions[c]);
        PolygonTriangulation split = triangulate_polygon(points);
        if (!split.simple) {
            ++not_simple;
            if (corners.size() > kMaxFannedCorners)
                throw InputError(path + ": face " + std::to_string(fh.idx() + 1) + " has " + std::to_string(corners.size()) +
                                 " corners and is not a simple polygon in its plane (it crosses or touches itself, or "
                                 "has no area); ellicast splits such a face as a fan from its first corner only up to " +
                                 std::to_string(kMaxFannedCorners) + " corners");
        }
        for (const auto& t : split.triangles) mesh.triangles.push_back({corners[t[0]], corners[t[1]], corners[t[2]]});
    }
    if (not_simple)
        result.warnings.push_back(path + ": " + std::to_string(not_simple) +
                                  (not_simple == 1 ? " polygon face is" : " polygon faces are") +
                                  " not simple in its plane (self-crossing, self-touching or without area): split as a "
                                  "fan from the first corner, which may cover area outside the face");
    // Vertices no face uses are original vertices too (the bunny has about a thousand): keep them.
    const std::array<float, 2> no_uv{0, 0};
    for (auto vh : om.vertices())
        if (!used[vh.idx()]) emit(vh, corner_uv ? &no_uv : nullptr);
    if (mesh.triangles.empty()) {
        if (om.n_vertices() == 0) throw InputError(path + ": the file holds no vertices");
        throw InputError(path + ": no faces could be read (" + std::to_string(om.n_vertices()) +
                         " vertices): the file has none, or the reader stopped at a value it could not parse "
                         "(such as nan); ellicast encodes triangle meshes from this format");
    }
    check_and_repair_mesh(mesh, path, result.warnings);
    if (mesh.triangles.empty()) throw InputError(path + ": every face is degenerate; nothing to encode");
    result.meshes.push_back(std::move(mesh));
    return result;
}

}  // namespace ellicast
