/// @file fuzz_water_graph_json.cpp
/// libFuzzer target: a body's "water_graph" / "permeability" / "density_map" keys (scene/SceneGraph.cpp,
/// docs/scene-format.md) on arbitrary JSON, then — when they are accepted — the water graph running on a
/// 1 m box for 30 steps: ingress through the permeable samples at a pose half under water, exchange and
/// flow (plugin/graph). The input is the body object itself when it has one of those keys, else the value
/// of "water_graph". Paths (a graph file, a texture) resolve against a folder that does not exist.
/// Contract checked: bad input ends as cli::UsageError naming the key, or std::invalid_argument from the
/// graph builders; an accepted graph passes WaterGraph::validate; while running, every node holds water in
/// [0, capacity], all finite, and Σ water − initial = entered − drained (WaterGraphState.h: exact to
/// rounding).
#include "FuzzContract.h"

#include <BulletBuoyancy/atlas/UvLayout.h>
#include <BulletBuoyancy/bake/BakeSamples.h>
#include "scene/SceneErrors.h"
#include "scene/SceneGraph.h"
#include <BulletBuoyancy/graph/WaterGraphState.h>
#include <BulletBuoyancy/graph/WaterIngress.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

using buoyancy::fuzz::violated;

namespace {

/// The 1 m box and its surface samples (exact coverage at 16²), built once.
struct Box {
    buoyancy::TriangleMesh mesh = buoyancy::makeBoxMesh(1, 1, 1);
    buoyancy::SurfaceSamples samples;
    Box() {
        const buoyancy::UvLayout layout = buoyancy::chooseUvLayout(mesh, 16);
        samples = buoyancy::bakeSurfaceSamples(mesh, layout.corner_uvs, 16, buoyancy::BakeMethod::ExactCoverage);
    }
};

void checkState(const buoyancy::WaterGraphState& s) {
    double capacity = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        const double w = s.water(int(i)), c = s.graph().nodes[i].capacity;
        if (!std::isfinite(w) || w < 0 || w > c * (1 + 1e-12)) violated("node water outside [0, capacity]");
        capacity += c;
    }
    const double ledger = s.totalWater() - s.initialVolume() - (s.enteredVolume() - s.drainedVolume());
    if (!(std::abs(ledger) <= 1e-9 * capacity + 1e-15)) violated("water not conserved");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using json = nlohmann::json;
    const json parsed = json::parse(data, data + size, nullptr, /*allow_exceptions=*/false);
    if (parsed.is_discarded()) return 0;  // not JSON: the scene parser's own error (fuzz_scene_json)
    const bool isBody = parsed.is_object() &&
                        (parsed.contains("water_graph") || parsed.contains("permeability") || parsed.contains("density_map"));
    const json body = isBody ? parsed : json{{"water_graph", parsed}};

    buoyancy::cli::SceneFlooding flooding;
    try {
        flooding = buoyancy::cli::readSceneFlooding(body, "bodies[0]", "/nonexistent-fuzz-dir",
                                                    [](const std::string& key, const std::string& what) {
                                                        throw buoyancy::cli::UsageError("fuzz.json: " + key + ": " + what);
                                                    });
    } catch (const buoyancy::cli::UsageError& e) {
        if (std::string(e.what()).rfind("fuzz.json: bodies[0]", 0) != 0) violated("error does not name the key");
        return 0;
    }
    if (!flooding.enabled) return 0;
    // The automatic graph voxelises the mesh: keep each run small (resolution and nodes up to 256 are valid,
    // but 256³ voxels per input would stall the fuzzer; the CLI tests cover them).
    if (flooding.automatic && (flooding.autoSettings.resolution > 24 || flooding.autoSettings.nodes > 24)) return 0;

    static const Box box;
    buoyancy::WaterGraph graph;
    buoyancy::PermeableSamples permeable;
    try {
        graph = buoyancy::cli::buildSceneWaterGraph(flooding, box.mesh);
        permeable = buoyancy::cli::buildScenePermeability(flooding, graph, box.samples, box.mesh);
    } catch (const std::invalid_argument& e) {
        if (!*e.what()) violated("empty graph error message");
        return 0;
    }
    try {
        graph.validate();
    } catch (const std::invalid_argument&) {
        violated("the parser accepted a graph the library rejects");
    }
    buoyancy::WaterGraphState state(graph);
    checkState(state);

    // Half under water, tilted by an angle taken from the input (any pose must work).
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(double(size % 360) * M_PI / 180.0, Eigen::Vector3d(1, 0.3, 0.2).normalized())
                        .toRotationMatrix();
    std::vector<double> wy(permeable.size()), f(permeable.size());
    buoyancy::IngressScratch scratch;
    for (int step = 0; step < 30; ++step) {
        pose.translation().y() = step < 15 ? -0.25 : 0.5;  // in, then lifted out to drain
        state.setPose(pose);
        for (std::size_t i = 0; i < permeable.size(); ++i) {
            wy[i] = (pose * Eigen::Vector3d(permeable.px[i], permeable.py[i], permeable.pz[i])).y();
            f[i] = 0.0;  // flat water at y = 0
        }
        buoyancy::applyIngress(state, permeable, wy.data(), f.data(), 1.0 / 60.0, 9.81, scratch);
        state.flow(1.0 / 60.0, 1000.0, 9.81);
        checkState(state);
    }
    return 0;
}
