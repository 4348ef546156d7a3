// Morph target displacements between an asset's vertices and a stream's points (format 1.6, spec 22).
#include "morph_targets.h"

#include "point_transfer.h"

namespace ellicast::morph_targets {

std::vector<float> point_values(const Mesh& mesh, const VertexMorph& morph, const std::vector<QuantizedPoint>& points,
                                const StreamInfo& info, const ObjectInfo& object) {
    const size_t per = morph_record_values(morph.targets, morph.attributes);
    if (morph.empty() || per == 0 || morph.values.size() != per * mesh.positions.size()) return {};
    std::vector<float> out(per * points.size(), 0.0f);
    const std::vector<point_transfer::Source> where = point_transfer::sources(mesh, points, info, object);
    for (size_t i = 0; i < points.size(); ++i) {
        const point_transfer::Source& s = where[i];
        if (!s.found) continue;
        float* to = out.data() + i * per;
        if (s.snapped) {
            std::copy_n(morph.values.data() + size_t(s.nearest) * per, per, to);
            continue;
        }
        for (size_t v = 0; v < per; ++v) {
            double x = 0;
            for (size_t k = 0; k < 3; ++k) x += s.bary[k] * morph.values[size_t(s.corners[k]) * per + v];
            to[v] = float(x);
        }
    }
    return out;
}

VertexMorph vertex_morph(const Mesh& decoded, const ReceivedStream& stream, size_t index) {
    VertexMorph out;
    if (index >= stream.objects().size() || !stream.info()) return out;
    const ReceivedObject& object = stream.objects()[index];
    if (!object.info || object.morph.empty() || decoded.positions.empty()) return out;
    const std::vector<const float*> per_vertex = point_transfer::nearest_records(decoded, stream, index, object.morph);
    if (per_vertex.empty()) return out;
    out.targets = object.morph_targets;
    out.attributes = object.morph_attributes;
    const size_t per = morph_record_values(out.targets, out.attributes);
    out.values.reserve(per * decoded.positions.size());
    for (size_t v = 0; v < decoded.positions.size(); ++v) out.values.insert(out.values.end(), per_vertex[v], per_vertex[v] + per);
    return out;
}

}  // namespace ellicast::morph_targets
