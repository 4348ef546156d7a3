// Writes hostile recordings that conform as far as a receiver can tell packet by packet, each built to
// make a receiver hold or compute much more than it was sent (issue 29). bench/run.sh amplification
// runs every command on them and measures seconds and peak memory against the input's bytes.
//   bench_hostile OUTDIR
#include "ellicast/format.h"

#include <cstdio>
#include <string>
#include <vector>

using namespace ellicast;

namespace {

bool write(const std::string& path, const std::vector<std::vector<uint8_t>>& packets) {
    const std::vector<uint8_t> bytes = write_container(packets);
    std::string message;
    if (write_file(path, bytes, message) != Error::Ok) {
        std::fprintf(stderr, "bench_hostile: %s\n", message.c_str());
        return false;
    }
    std::fprintf(stderr, "%s: %zu packets, %zu bytes\n", path.c_str(), packets.size(), bytes.size());
    return true;
}

ObjectInfo object(uint32_t points) {
    ObjectInfo o;
    o.frame = {{0, 0, 0}, 1};
    o.point_count = points;
    return o;
}

// A stream of one surface object of `ellipsoids` and `points` (to be filled in `content`).
StreamInfo surface_stream(uint32_t ellipsoids, uint32_t points, ObjectContent& content) {
    StreamInfo info;
    ObjectInfo o = object(points);
    o.kind = ObjectKind::Surface;
    o.ellipsoid_count = ellipsoids;
    info.objects.push_back(o);
    content.points.resize(points);
    content.ellipsoids.resize(ellipsoids);
    return info;
}

std::vector<std::vector<uint8_t>> cat(std::initializer_list<const std::vector<std::vector<uint8_t>>*> groups) {
    std::vector<std::vector<uint8_t>> all;
    for (const auto* g : groups) all.insert(all.end(), g->begin(), g->end());
    return all;
}

// Writes a surface stream: its stream info, ellipsoids and points.
bool write_surface(const std::string& path, const StreamInfo& info, const ObjectContent& content) {
    StreamPackets p;
    return packetize_stream(info, {content}, 3, p) == Error::Ok &&
           write(path, cat({&p.stream_info, &p.ellipsoids, &p.points}));
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: bench_hostile OUTDIR\n");
        return 2;
    }
    const std::string dir = argv[1];
    const uint32_t n = 2'000'000;
    bool ok = true;
    // An object of n points with surface normals, every entry left to the surface; mapped at level 7
    // when `mapped`, its points then spread over 128 x 128 cells.
    auto surface_normals_stream = [&](bool mapped, StreamPackets& p, uint16_t packet_size = kDefaultPacketSize) {
        StreamInfo info;
        info.packet_size = packet_size;
        ObjectInfo o = object(n);
        o.map_level = mapped ? 7 : 0;
        o.map_batch = mapped ? 4096 : 0;
        o.exact_layer = true;
        o.surface_normals = true;
        info.objects.push_back(o);
        std::vector<ObjectContent> c(1);
        c[0].points.resize(n);
        c[0].normals.resize(n);
        if (mapped)
            for (uint32_t i = 0; i < n; ++i) c[0].points[i].position = {i % 128, (i / 128) % 128, 5};
        return packetize_stream(info, c, 3, p) == Error::Ok;
    };
    {   // Mapped records whose map never arrives, each with a NORMALS entry.
        StreamPackets p;
        ok = ok && surface_normals_stream(true, p) &&
             write(dir + "/unplaced-records.ellc", cat({&p.stream_info, &p.points, &p.normals}));
    }
    {   // The same, with three STREAM_INFOs first that contradict the real one (another packet size)
        // but declare the same object: a network receiver keeps four candidates of one stream id,
        // and every packet reaches all four (spec 11.4). Sent as datagrams to `receive`.
        StreamPackets p;
        std::vector<std::vector<uint8_t>> all;
        for (const uint16_t size : {uint16_t(kDefaultPacketSize + 100), uint16_t(kDefaultPacketSize + 200),
                                    uint16_t(kDefaultPacketSize + 300)}) {
            StreamPackets q;
            ok = ok && surface_normals_stream(true, q, size);
            all.insert(all.end(), q.stream_info.begin(), q.stream_info.end());
        }
        ok = ok && surface_normals_stream(true, p);
        for (const auto* g : {&p.stream_info, &p.points, &p.normals}) all.insert(all.end(), g->begin(), g->end());
        ok = ok && write(dir + "/candidates.ellc", all);
    }
    {   // NORMALS entries only: a bit a point.
        StreamPackets p;
        ok = ok && surface_normals_stream(false, p) && write(dir + "/normal-entries.ellc", cat({&p.stream_info, &p.normals}));
    }
    {   // One point every 512 indices, a packet each: one page per point held.
        StreamInfo info;
        info.objects.push_back(object(7'900'000));
        std::vector<ObjectContent> c(1);
        c[0].points.resize(info.objects[0].point_count);
        StreamPackets p;
        ok = ok && packetize_stream(info, c, 3, p) == Error::Ok;
        std::vector<std::vector<uint8_t>> sparse = p.stream_info;
        const ObjectInfo& oi = info.objects[0];
        for (uint32_t first = 0; first < oi.point_count; first += 512) {
            PointBatch b;
            b.first_index = first;
            b.points.resize(1);
            PacketHeader h;
            h.type = uint8_t(PacketType::Points);
            h.stream_id = 3;
            h.sequence = first / 512 + 1;
            h.object_id = 0;
            sparse.push_back(write_packet(h, encode_points_payload(b, info, oi)));
        }
        ok = ok && write(dir + "/sparse-points.ellc", sparse);
    }
    {   // A million ellipsoids over one object.
        ObjectContent c;
        const StreamInfo info = surface_stream(1'000'000, 1, c);
        for (uint32_t i = 0; i < c.ellipsoids.size(); ++i) {
            QuantizedEllipsoid& e = c.ellipsoids[i];
            e.center = {uint16_t(i % 32768), uint16_t((i * 7) % 32768), uint16_t((i * 13) % 32768)};
            e.radii = {100, 200, 300};
        }
        ok = ok && write_surface(dir + "/ellipsoids.ellc", info, c);
    }
    {   // Ellipsoids that each cover the whole object: a rasterizer pays each one's volume in grid
        // nodes. 100,000 of them, with a point each spread over the frame.
        ObjectContent c;
        const StreamInfo info = surface_stream(100'000, 100'000, c);
        for (uint32_t i = 0; i < c.points.size(); ++i)
            c.points[i].position = {(i * 37) % 16384, (i * 101) % 16384, (i * 7) % 16384};
        for (uint32_t i = 0; i < c.ellipsoids.size(); ++i) {
            Ellipsoid e;
            e.center = {0.5f + 0.001f * float(i % 7), 0.5f, 0.5f};
            e.radii = {0.49f, 0.45f, 0.4f};
            c.ellipsoids[i] = quantize_ellipsoid(e, info.objects[0].frame);
        }
        ok = ok && write_surface(dir + "/covering-ellipsoids.ellc", info, c);
    }
    {   // A pile of flat discs (a sheet's ellipsoids) and points just off their plane, within their
        // reach: a decoder that tries every disc for every point does 10^10 tests.
        ObjectContent c;
        const StreamInfo info = surface_stream(200'000, 50'000, c);
        Ellipsoid disc;
        disc.center = {0.5f, 0.5f, 0.5f};
        disc.radii = {0.3f, 0.3f, 0.004f};
        for (auto& e : c.ellipsoids) e = quantize_ellipsoid(disc, info.objects[0].frame);
        for (uint32_t i = 0; i < c.points.size(); ++i) {
            SurfacePoint sp;
            sp.position = {0.3f + 0.4f * float(i % 223) / 223, 0.3f + 0.4f * float(i / 223) / 225, 0.503f};
            c.points[i] = quantize_point(sp, info, info.objects[0]);
        }
        ok = ok && write_surface(dir + "/disc-pile.ellc", info, c);
    }
    return ok ? 0 : 1;
}
