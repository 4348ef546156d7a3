// Refinement where the viewer looks: the region of interest (a box, a camera's view cone) and
// `decode --region`, which inserts only the points inside and holds the others.
#include "ellicast/codec/region.h"
#include "ellicast/codec/surface_distance.h"
#include "ellicast/converters/mesh_input.h"
#include "support.h"

#include <doctest/doctest.h>

using namespace ellicast;
using namespace ellicast::test;
namespace fs = std::filesystem;

TEST_CASE("a region of interest: a box, or the cone a camera sees through the corners of its frame") {
    const Region box = Region::box({0, 0, 0}, {1, 2, 3});
    CHECK(box.problem().empty());
    CHECK(box.contains({0.5, 1, 2.9}));
    CHECK(box.contains({0, 0, 0}));
    CHECK_FALSE(box.contains({1.01, 1, 1}));
    CHECK(Region::box({1, 0, 0}, {0, 1, 1}).problem().find("axis x") != std::string::npos);
    CHECK(Region::box({0, 0, 0}, {1, std::nan(""), 1}).problem().find("finite") != std::string::npos);

    // Looking down -z from (0, 0, 10) with a 40-degree vertical field of view, square frame: the
    // half-angle to the corners is atan(tan(20) * sqrt(2)) = 27.2 degrees.
    const Region view = Region::view({0, 0, 10}, {0, 0, 0}, 40, 1);
    CHECK(view.problem().empty());
    CHECK(view.contains({0, 0, 0}));
    CHECK(view.contains({0, 0, -100}));                   // far along the line of sight
    CHECK(view.contains({4.5, 0, 0}));                    // 24.2 degrees off axis
    CHECK_FALSE(view.contains({5.5, 0, 0}));              // 28.8 degrees
    CHECK_FALSE(view.contains({0, 0, 11}));               // behind the camera
    CHECK(Region::view({1, 1, 1}, {1, 1, 1}, 40).problem().find("looks nowhere") != std::string::npos);
    CHECK(Region::view({0, 0, 1}, {0, 0, 0}, 180).problem().find("field of view") != std::string::npos);
    CHECK(Region::view({0, 0, 1}, {0, 0, 0}, 40, 0).problem().find("aspect") != std::string::npos);
}

TEST_CASE("decode --region inserts the points inside a box or a camera's view and holds the others") {
    const fs::path dir = scratch_dir("region");
    const fs::path trefoil = source_dir() / "samples" / "trefoil.obj";
    auto run = [&](const std::string& args, std::string& log) {
        int status = 0;
        log = run_command(shell_quoted(ellicast_exe().string()) + " " + args + " 2>&1", status);
        return status;
    };
    std::string log;
    const std::string stream = shell_quoted((dir / "t.ellc").string());
    REQUIRE(run("encode -q " + shell_quoted(trefoil.string()) + " -o " + stream + " --repair 0", log) == 0);

    // Everything: every point inserted (the reconstruction, not the exact layer).
    REQUIRE(run("decode -q --no-exact " + stream + " -o " + shell_quoted((dir / "all.ply").string()), log) == 0);
    CHECK(log.find("held outside") == std::string::npos);
    // The trefoil spans about -3..3 on x and y: the half with x > 0.
    REQUIRE(run("decode -q --no-exact " + stream + " -o " + shell_quoted((dir / "half.ply").string()) +
                    " --region box:0,-10,-10,10,10,10",
                log) == 0);
    const auto held_at = log.find("points held outside the region of interest");
    REQUIRE_MESSAGE(held_at != std::string::npos, log);
    const size_t held = std::stoul(log.substr(log.rfind(':', held_at) + 2));
    CHECK(held > 1000);
    CHECK(held < 3000);
    // Inside the box the surface is as close to the original as with every point; outside it keeps
    // the coarser base. Measured from the original's triangles on either side (a margin left out).
    const Mesh original = load_meshes(trefoil.string()).meshes.at(0);
    auto side = [&](bool positive) {
        Mesh m = original;
        m.triangles.clear();
        for (const auto& t : original.triangles) {
            const float x = (original.positions[t[0]][0] + original.positions[t[1]][0] + original.positions[t[2]][0]) / 3;
            if (positive ? x > 0.5f : x < -0.5f) m.triangles.push_back(t);
        }
        return m;
    };
    auto rms = [&](const Mesh& from, const fs::path& decoded) {
        SurfaceDistanceOptions o;
        o.samples = 20000;
        SurfaceDistance d;
        std::string error;
        REQUIRE(surface_distance({from}, load_meshes(decoded.string()).meshes, o, d, error));
        return d.a_to_b.rms;
    };
    const Mesh inside = side(true), outside = side(false);
    CHECK(rms(inside, dir / "half.ply") < 1.5 * rms(inside, dir / "all.ply"));
    CHECK(rms(outside, dir / "half.ply") > 2 * rms(outside, dir / "all.ply"));
    // A camera looking at nothing of the model: every point is held, the base is still written.
    REQUIRE(run("decode -q --no-exact " + stream + " -o " + shell_quoted((dir / "away.ply").string()) +
                    " --region view:0,0,50,0,0,100,30",
                log) == 0);
    CHECK_MESSAGE(log.find("4087 of 4087 points held") != std::string::npos, log);
    // The exact layer, when whole, is written whatever the region.
    REQUIRE(run("decode -q " + stream + " -o " + shell_quoted((dir / "exact.ply").string()) +
                    " --region box:0,-10,-10,10,10,10",
                log) == 0);
    CHECK(log.find("held outside") == std::string::npos);
    CHECK_MESSAGE(log.find("exact: the original triangles") != std::string::npos, log);
    CHECK(load_meshes((dir / "exact.ply").string()).meshes.at(0).triangles.size() ==
          load_meshes(trefoil.string()).meshes.at(0).triangles.size());
    // Bad regions: a usage error naming the problem, nothing written.
    CHECK(run("decode -q " + stream + " -o " + shell_quoted((dir / "bad.ply").string()) + " --region box:1,0,0,0,1,1", log) == 2);
    CHECK_MESSAGE(log.find("minimum corner is above its maximum on axis x") != std::string::npos, log);
    CHECK(run("decode -q " + stream + " -o " + shell_quoted((dir / "bad.ply").string()) + " --region view:0,0,1,0,0,1,40", log) == 2);
    CHECK_MESSAGE(log.find("looks nowhere") != std::string::npos, log);
    CHECK(run("decode -q " + stream + " -o " + shell_quoted((dir / "bad.ply").string()) + " --region sphere:1,2,3", log) == 2);
    CHECK_MESSAGE(log.find("expected box:") != std::string::npos, log);
    CHECK(run("decode -q " + stream + " -o " + shell_quoted((dir / "bad.ply").string()) + " --region box:0,0,0,1,1,x", log) == 2);
    CHECK_MESSAGE(log.find("\"x\" is not a number") != std::string::npos, log);
    CHECK_FALSE(fs::exists(dir / "bad.ply"));
}
