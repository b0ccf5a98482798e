#pragma once
/// @file ModelSize.h
/// A model whose largest bounding-box side is outside 1 mm .. 1 km is most likely written in another unit
/// (millimetres, centimetres of a ship, kilometres): the tools warn with its size and a scale that would bring it
/// near 1 m, and still run it.

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <Eigen/Core>

#include <optional>

namespace buoyancy::cli {

/// Smallest and largest usual model side, m.
constexpr double kSmallestModelSide = 1e-3;
constexpr double kLargestModelSide = 1e3;

/// What the warning says: the model's largest side and the scale to suggest.
struct ModelSizeHint {
    double side = 0;            ///< largest bounding-box side of the mesh as given (already scaled), m
    double suggestedScale = 1;  ///< the current scale times the power of 1000 that brings the side nearest to 1 m
};

/// The hint for `mesh` (already scaled by `scale`), or nothing when its largest side is within the usual range.
inline std::optional<ModelSizeHint> modelSizeHint(const TriangleMesh& mesh, double scale) {
    if (mesh.vertices.empty()) return std::nullopt;
    Eigen::Vector3d lo = mesh.vertices.front(), hi = lo;
    for (const auto& v : mesh.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    const double side = (hi - lo).maxCoeff();
    if (!(side < kSmallestModelSide || side > kLargestModelSide)) return std::nullopt;
    double factor = 1;
    double s = side;
    while (s > kLargestModelSide) {
        s *= 1e-3;
        factor *= 1e-3;
    }
    while (s < kSmallestModelSide && s > 0) {
        s *= 1e3;
        factor *= 1e3;
    }
    return ModelSizeHint{side, scale * factor};
}

}  // namespace buoyancy::cli
