// Warnings on stderr, one line each kind: a model with a hundred parts that each drop a degenerate
// triangle gets one line naming the first and counting the others (all of them with --verbose).
#include "commands.h"

#include <cctype>
#include <cstdio>
#include <map>

namespace ellicast::cli {

namespace {

// What a warning says, without what it is about: a warning reads "[FILE: ]SUBJECT: what", the subject
// a mesh, primitive or node; the kind is the "what" with its numbers folded, so that "body_3 primitive
// 0: 2 degenerate ..." and "body_7 primitive 1: 5 degenerate ..." are one kind.
bool looks_like_path(const std::string& s) {
    if (s.find('/') != std::string::npos) return true;
    const size_t dot = s.rfind('.');
    if (dot == std::string::npos) return false;
    std::string ext = s.substr(dot + 1);
    for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext == "gltf" || ext == "glb" || ext == "obj" || ext == "ply" || ext == "off" || ext == "stl";
}

std::pair<std::string, std::string> kind_and_subject(const std::string& warning) {
    size_t start = 0, cut = warning.find(": ");
    if (cut != std::string::npos && looks_like_path(warning.substr(0, cut))) {
        start = cut + 2;
        cut = warning.find(": ", start);
    }
    const std::string subject = cut == std::string::npos ? "" : warning.substr(start, cut - start);
    const size_t what = cut == std::string::npos ? start : cut + 2;
    std::string kind;
    for (size_t i = what; i < warning.size(); ++i) {
        const bool digit = std::isdigit(static_cast<unsigned char>(warning[i])) != 0;
        if (digit && !kind.empty() && kind.back() == '#') continue;
        kind += digit ? '#' : warning[i];
    }
    return {kind, subject};
}

}  // namespace

void print_warnings(const std::vector<std::string>& warnings, bool verbose) {
    constexpr size_t kGroupFrom = 3, kNamed = 4;
    std::map<std::string, std::vector<size_t>> by_kind;
    std::vector<std::string> order;
    for (size_t i = 0; i < warnings.size(); ++i) {
        const std::string kind = kind_and_subject(warnings[i]).first;
        auto [it, fresh] = by_kind.try_emplace(kind);
        if (fresh) order.push_back(kind);
        it->second.push_back(i);
    }
    for (const std::string& kind : order) {
        const std::vector<size_t>& same = by_kind[kind];
        if (verbose || same.size() < kGroupFrom) {
            for (size_t i : same) std::fprintf(stderr, "ellicast: warning: %s\n", warnings[i].c_str());
            continue;
        }
        std::string others;
        for (size_t k = 1; k < same.size() && k <= kNamed; ++k)
            others += (k > 1 ? ", " : "") + kind_and_subject(warnings[same[k]]).second;
        if (same.size() > kNamed + 1) others += ", ...";
        std::fprintf(stderr, "ellicast: warning: %s (and %zu more like it: %s; --verbose lists each)\n",
                     warnings[same[0]].c_str(), same.size() - 1, others.c_str());
    }
}

}  // namespace ellicast::cli
