#pragma once
/// @file SceneGraph.h
/// The body keys "water_graph" and "permeability" of a scene (issue 6; docs/scene-format.md): parsing
/// with errors that name the file and key, and building the graph and the permeable samples of a body.

#include "cli/SceneJsonReader.h"  // SceneFailFn
#include "graph/AutoWaterGraph.h"
#include "graph/WaterGraph.h"
#include "graph/WaterIngress.h"

#include <nlohmann/json_fwd.hpp>

#include <functional>
#include <string>
#include <vector>

namespace buoyancy::cli {

/// One body's water graph and permeability as read from the scene.
struct SceneFlooding {
    bool enabled = false;           ///< the body has a "water_graph"
    bool automatic = false;         ///< "water_graph": {"auto": {...}}: built from the mesh at run time
    WaterGraph graph;               ///< the hand-made graph (or the parameters of the automatic one)
    AutoWaterGraphSettings autoSettings; ///< automatic graph settings
    std::vector<PermeabilityRegion> regions;  ///< "permeability": {"regions": [...]}; node resolved below
    std::vector<std::string> regionNodes;     ///< #regions node name each region feeds ("" = nearest node)
};

/// Read the "water_graph" and "permeability" keys of body object `body` (key = "bodies[i]").
/// "water_graph" may be an object or the path of a JSON file with the same schema (relative to `directory`).
SceneFlooding readSceneFlooding(const nlohmann::json& body, const std::string& key, const std::string& directory,
                                const SceneFailFn& fail);

/// The body's graph: the hand-made one, or the automatic one built from `mesh`.
/// @throws std::invalid_argument (automatic graph of a mesh with no interior, region node names unknown)
WaterGraph buildSceneWaterGraph(const SceneFlooding& flooding, const TriangleMesh& mesh);

/// The permeable samples of the body from its regions (node names resolved in `graph`).
/// @throws std::invalid_argument naming a region whose node does not exist
PermeableSamples buildScenePermeability(const SceneFlooding& flooding, const WaterGraph& graph,
                                        const SurfaceSamples& samples);

}  // namespace buoyancy::cli
