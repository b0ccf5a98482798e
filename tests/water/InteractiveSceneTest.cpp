// Regression: interactive water run through the scene runner (`buoyancy run`) must not launch or lift bodies.
// Before the fix the coupler's footprint (a disc of the waterline area) left a box's corners in the ring of
// raised water: the box read the water it had just pushed up and the loop heaped water under it (a crate
// dropped from y = 1 was flung to y = 3; bodies ended floating 0.5 m high). Expected values are analytic:
// a wall-sided box of height c and density ratio s floats with draft s·c (Archimedes), COM at h − c/2 + s·c.
#include "cli/RunCommand.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>
#include <unistd.h>  // getpid: a private temporary folder per test process

namespace {
struct Track {
    std::vector<double> t, cy, vsub;
};

std::map<std::string, Track> readTracks(const std::string& csv) {
    std::ifstream f(csv);
    std::string line;
    std::getline(f, line);
    std::vector<std::string> head;
    {
        std::stringstream ss(line);
        std::string c;
        while (std::getline(ss, c, ',')) head.push_back(c);
    }
    const auto col = [&](const std::string& name) {
        return std::size_t(std::find(head.begin(), head.end(), name) - head.begin());
    };
    const std::size_t it = col("t"), ib = col("body"), icy = col("cy"), iv = col("submerged_volume");
    REQUIRE(icy < head.size());
    REQUIRE(iv < head.size());
    std::map<std::string, Track> out;
    while (std::getline(f, line)) {
        std::vector<std::string> v;
        std::stringstream ss(line);
        std::string c;
        while (std::getline(ss, c, ',')) v.push_back(c);
        if (v.size() != head.size()) continue;
        Track& tr = out[v[ib]];
        tr.t.push_back(std::stod(v[it]));
        tr.cy.push_back(std::stod(v[icy]));
        tr.vsub.push_back(std::stod(v[iv]));
    }
    return out;
}
}  // namespace

TEST_CASE("interactive water in the scene runner: dropped and neighbouring boxes end at their analytic drafts",
          "[water][interactive][scene]") {
    const int resolution = GENERATE(64, 128, 256);
    const double dropHeight = GENERATE(1.0, 0.3);
    const auto dir = std::filesystem::temp_directory_path() /
                     ("buoyancy_interactive_scene_" + std::to_string(::getpid()) + "_" + std::to_string(resolution) + "_" + std::to_string(int(dropHeight * 10)));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string scene = (dir / "scene.json").string();
    {
        std::ofstream s(scene);
        s << R"({"duration": 10, "output_interval": 0.05,
 "water": {"type": "interactive", "size": [20, 20], "resolution": )"
          << resolution << R"(, "wave_speed": 2, "damping": 0.1},
 "bodies": [{"name": "drop", "shape": {"type": "box", "size": [1, 0.5, 1]}, "density": 500, "position": [0, )"
          << dropHeight << R"(, 0]},
            {"name": "neighbour", "shape": {"type": "box", "size": [1, 0.5, 1]}, "density": 500, "position": [2, 0, 0]}]})";
    }
    REQUIRE(buoyancy::cli::runSceneCommand(scene, (dir / "out").string(), std::nullopt) == 0);
    const auto tracks = readTracks((dir / "out" / "trajectory.csv").string());
    REQUIRE(tracks.size() == 2);
    // Archimedes: draft s·c = 0.5·0.5 = 0.25 m, so COM y = 0 − 0.25 + 0.25 = 0 and V_sub = 0.25 m³.
    const double comY = 0.0, vSub = 0.25;
    for (const auto& kv : tracks) {
        const Track& tr = kv.second;
        const std::size_t n = tr.t.size();
        REQUIRE(n > 100);
        double late = 0, lateV = 0, top = -1e9;
        int lateCount = 0;
        for (std::size_t i = 0; i < n; ++i) {
            if (tr.t[i] > 0.5) top = std::max(top, tr.cy[i]);  // after the drop has reached the water
            if (tr.t[i] >= 8.0) {
                late += tr.cy[i];
                lateV += tr.vsub[i];
                ++lateCount;
            }
        }
        late /= lateCount;
        lateV /= lateCount;
        INFO(kv.first << " at resolution " << resolution << ", dropped from " << dropHeight << ": mean COM y over 8..10 s "
                      << late << " m, mean V_sub " << lateV << " m^3, highest COM after 0.5 s " << top << " m");
        CHECK(std::abs(late - comY) <= 0.03);
        CHECK(std::abs(lateV - vSub) <= 0.03 * vSub);
        // Bounded: never thrown above the drop height, the neighbour only rocked (a few cm).
        CHECK(top <= (kv.first == "drop" ? dropHeight : 0.1));
    }
    std::filesystem::remove_all(dir);
}
