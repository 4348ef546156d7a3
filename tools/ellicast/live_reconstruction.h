// What a live receiver shows: the base mesh built as soon as the base is complete, then every
// point inserted as it arrives (in arrival order), in bounded slices of work so that reading the
// socket never waits long. Built on the decoder's own steps (rasterize, marching cubes,
// insert_point, flips, collapses). An object whose exact layer is whole (every point and its
// connectivity, spec 19.4) is shown exact from then on, as `ellicast decode` would write it.
#pragma once

#include "ellicast/codec/decoder.h"
#include "ellicast/codec/mesh.h"
#include "ellicast/format.h"

#include <array>
#include <chrono>
#include <functional>
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

    // Refinement where the viewer looks: a point for which `insert_if` (object, position in the
    // object's frame) is false is held, not inserted, until a later region takes it. Empty: every
    // point. A new region rescans every held point.
    using InsertIf = std::function<bool(size_t object, const std::array<float, 3>& position)>;
    void set_region(InsertIf insert_if);
    // Received points held outside the region at the last complete scan.
    size_t held() const { return held_; }
    // Counts every change to what objects() gives (a base built, points inserted, an object turned exact).
    uint64_t changes() const { return changes_; }

    // What object `i` shows: nothing yet, its base alone, its base refined by points, its exact
    // mesh, or (an object without a base surface) its points.
    enum class State { Waiting, Base, Points, Exact, PointSet };
    State state(size_t i) const;
    size_t object_count() const { return objects_.size(); }
    size_t inserted(size_t i) const { return i < objects_.size() ? objects_[i].points.size() : 0; }
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
        bool exact = false;                // its exact layer is whole: `exact_mesh` is shown
        bool exact_failed = false;         // whole, but unusable (reconstruction shown)
        Mesh exact_mesh;
    };
    // Turns the objects whose exact layer has become whole exact (spec 19.4).
    void take_exact_layers(const ReceivedStream& stream);
    // Object i's exact layer is whole and not yet taken.
    bool exact_ready(const ReceivedStream& stream, size_t i) const;
    int grid_resolution_;
    bool started_ = false;
    std::vector<Object> objects_;
    StreamInfo stream_info_;
    size_t inserted_total_ = 0;
    uint64_t changes_ = 0;
    InsertIf insert_if_;
    size_t held_ = 0;
    // With a region: whether the last scan of the received points ended (not cut by its budget),
    // and how many points had been received then.
    bool scan_complete_ = false;
    size_t scanned_received_ = 0;
};

}  // namespace ellicast::cli
