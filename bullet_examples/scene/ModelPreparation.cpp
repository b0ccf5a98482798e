#include "scene/ModelPreparation.h"

#include <BulletBuoyancy/bullet/btConvexHullMesh.h>
#include <BulletBuoyancy/mesh/MeshImport.h>

#include <Eigen/Geometry>

#include <cstdio>
#include <stdexcept>
#include <vector>

namespace buoyancy::cli {

namespace {

/// True for the refusals that PrepareMeshOptions::repair (or a hull) can get past.
bool repairable(const std::string& message) {
    for (const char* what : {"open surface", "non-manifold", "inconsistent orientation"})
        if (message.find(what) != std::string::npos) return true;
    return false;
}

std::string format(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

}  // namespace

PreparedModel prepareModel(TriangleMesh& mesh, const std::string& name, const ModelChoices& choices,
                           const std::string& flagHint) {
    PreparedModel out;
    PrepareMeshOptions options;
    options.repair = choices.repair;
    if (!choices.convexHull) {
        try {
            out.report = prepareMesh(mesh, name, options);
        } catch (const MeshError& e) {
            const std::string message = e.what();
            if (!choices.repair && !flagHint.empty() && repairable(message)) throw MeshError(message + " (" + flagHint + ")");
            throw;
        }
        return out;
    }
    // The model's own volume, when it has one (closed, or closed by the repair asked for).
    std::string why;
    {
        TriangleMesh copy = mesh;
        try {
            out.modelVolume = prepareMesh(copy, name, options).repair.volume_after;
            if (!(*out.modelVolume == *out.modelVolume)) {  // nothing repaired: the volume of the checked mesh
                double six = 0;
                for (std::size_t t = 0; t < copy.triangles.size(); ++t)
                    six += copy.corner(t, 0).dot(copy.corner(t, 1).cross(copy.corner(t, 2)));
                out.modelVolume = six / 6.0;
            }
        } catch (const MeshError& e) {
            out.modelVolume.reset();
            why = e.what();
        }
    }
    std::vector<char> used(mesh.vertices.size(), 0);
    for (const Eigen::Vector3i& t : mesh.triangles)
        for (int k = 0; k < 3; ++k)
            if (t[k] >= 0 && std::size_t(t[k]) < used.size()) used[std::size_t(t[k])] = 1;
    std::vector<Eigen::Vector3d> points;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        if (used[v]) points.push_back(mesh.vertices[v]);
    try {
        mesh = btConvexHullMesh(points, name);
    } catch (const std::invalid_argument& e) {
        throw MeshError(e.what());
    }
    out.report = prepareMesh(mesh, name, PrepareMeshOptions{});
    out.hulled = true;
    double six = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        six += mesh.corner(t, 0).dot(mesh.corner(t, 1).cross(mesh.corner(t, 2)));
    out.hullVolume = six / 6.0;
    std::string said = name + ": replaced by its convex hull (" + std::to_string(mesh.triangles.size()) +
                       " triangles): volume " + format(out.hullVolume) + " m^3";
    if (out.modelVolume && *out.modelVolume > 0)
        said += ", the model's " + format(*out.modelVolume) + " m^3 (+" +
                format(100.0 * (out.hullVolume - *out.modelVolume) / *out.modelVolume) + " %)";
    else
        said += "; the model's own volume is not defined (" + why + ")";
    out.report.warnings.push_back({said});
    return out;
}

}  // namespace buoyancy::cli
