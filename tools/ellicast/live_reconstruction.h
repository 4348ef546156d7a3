// What a live receiver shows: the base mesh built as soon as the base is complete, then every
// point inserted as it arrives (in arrival order), in bounded slices of work so that reading the
// socket never waits long. Built on the decoder's own steps (rasterize, marching cubes,
// insert_point, flips, collapses).
#pragma once

#include "ellicast/codec/decoder.h"
#include "ellicast/codec/mesh.h"
#include "ellicast/format.h"

#include <chrono>
#include <string>
#include <vector>

namespace ellicast::cli {

class LiveReconstruction {
public:
    explicit LiveReconstruction(int grid_resolution = 0) : grid_resolution_(grid_resolution) {}

    // Builds the base mesh of every surface object (call once the base is complete). False with
    // `error` when a base cannot be built (e.g. the grid would be too large).
    bool start(const ReceivedStream& stream, std::string& error);
    bool started() const { return started_; }

    // Inserts points that arrived since the last call, for at most `budget`. Returns how many.
    size_t work(const ReceivedStream& stream, std::chrono::microseconds budget);
    // True when every received point has been inserted.
    bool caught_up(const ReceivedStream& stream) const;

    size_t inserted() const { return inserted_total_; }
    // The current mesh of every object of the stream, as it would be shown (index = object id;
    // empty for an object that has nothing yet).
    std::vector<Mesh> objects() const;

private:
    struct Object {
        bool present = false;       // its stream info arrived when the base was built
        bool surface = false;       // it has a base surface (else shown as points)
        ObjectInfo info;
        Reconstruction reconstruction;
        std::vector<SurfacePoint> points;  // inserted, in insertion order
        std::vector<bool> inserted;        // by point index
    };
    int grid_resolution_;
    bool started_ = false;
    std::vector<Object> objects_;
    StreamInfo stream_info_;
    size_t inserted_total_ = 0;
};

}  // namespace ellicast::cli
