#pragma once
/// @file ModelPreparation.h
/// What the tools do to an imported model before it floats: the checks of prepareMesh, the opt-in repair
/// (`hydrostatics --repair`, a scene shape's "repair") and the opt-in convex hull (`--convex-hull`,
/// "convex_hull"), with what each did said in warnings.

#include <BulletBuoyancy/mesh/MeshRepair.h>

#include <optional>
#include <string>

namespace buoyancy::cli {

/// The user's choices for one model.
struct ModelChoices {
    bool repair = false;      ///< repair what is safe to repair (PrepareMeshOptions::repair)
    bool convexHull = false;  ///< replace the model by the convex hull of its vertices
};

/// What preparation gave besides the mesh.
struct PreparedModel {
    MeshReport report;                   ///< prepareMesh's report of the mesh that floats (the hull, with convexHull)
    bool hulled = false;                 ///< the model was replaced by its hull
    std::optional<double> modelVolume;   ///< with convexHull: the model's own volume, m³ (absent when it is not closed)
    double hullVolume = 0;               ///< with convexHull: the hull's volume, m³
};

/// Prepare `mesh` in place. Warnings (repairs done, the volume a hull adds) are in report.warnings.
/// @param name  the file name, in messages
/// @param flagHint  how the user turns repair and hull on, for the hint in a refusal, e.g.
///                  "--repair closes holes ...; --convex-hull ..." (empty: no hint)
/// @throws MeshError naming the file and the problem (with `flagHint` when repairing could help)
PreparedModel prepareModel(TriangleMesh& mesh, const std::string& name, const ModelChoices& choices,
                           const std::string& flagHint);

}  // namespace buoyancy::cli
