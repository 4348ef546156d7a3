// What a receiver does with streams that would otherwise hold memory forever or overflow.
#include "support.h"

#include "ellicast/format.h"

#include <cmath>

using namespace ellicast;

namespace {

StreamInfo one_object_stream() {
    StreamInfo info;
    ObjectInfo o;
    o.frame = {{0, 0, 0}, 1};
    o.point_count = 10;
    info.objects.push_back(o);
    return info;
}

}  // namespace

TEST_CASE("packets held for an object the stream turns out not to have are rejected when its info arrives") {
    StreamInfo info = one_object_stream();
    std::vector<ObjectContent> contents(1);
    contents[0].points.resize(10);
    StreamPackets packets;
    REQUIRE(packetize_stream(info, contents, 3, packets) == Error::Ok);
    // A POINTS packet of object 0 re-addressed to object 5: valid on its own, held without stream info.
    PacketView view;
    REQUIRE(parse_packet(packets.points[0], view) == Error::Ok);
    PacketHeader h = view.header;
    h.object_id = 5;
    auto stray = write_packet(h, view.payload);
    ReceivedStream rs;
    REQUIRE(rs.add_packet(stray, 0) == Error::Ok);
    CHECK(rs.counters().pending == 1);
    REQUIRE(rs.add_packet(packets.stream_info[0], 1) == Error::Ok);
    CHECK(rs.counters().pending == 0);
    REQUIRE(rs.rejections().size() == 1);
    CHECK(rs.rejections()[0].error == Error::UnknownObject);
    CHECK(rs.rejections()[0].where == 0);
}

TEST_CASE("a frame whose far corner overflows single precision is refused") {
    StreamInfo info = one_object_stream();
    info.objects[0].frame = {{3e38f, 0, 0}, 3e38f};
    CHECK(check_stream_info(info) == Error::MalformedPayload);
    info.objects[0].frame = {{-3e38f, 0, 0}, 3e38f};  // ends at 0: fine
    CHECK(check_stream_info(info) == Error::Ok);
    info.objects[0].attributes = kAttrTexcoord;
    info.objects[0].texcoord_origin = {3e38f, 0};
    info.objects[0].texcoord_scale = {3e38f, 1};
    CHECK(check_stream_info(info) == Error::MalformedPayload);
}
