#pragma once
/// @file BuoyancyMethod.h
/// The one enumeration of the ways the library can integrate buoyancy, their names, and the default choice per mesh.
/// What each method does is its entry in the registry of IntegrationMethod.h (design.md 8.2).

#include <cstddef>
#include <optional>
#include <string>

namespace buoyancy {

/// How the surface integrals are evaluated (design.md 2.4). The Bullet layer's public name for it is
/// btBuoyancyMethod (btBuoyancySettings.h), the same type. Each value but Auto has one IntegrationMethod.
enum class BuoyancyMethod {
    Auto,          ///< let the library choose per mesh (resolveMethod): exact-mesh for small meshes, else exact-coverage
    TexelCentre,   ///< the paper's texture sampling, texel-centre baking (erratic convergence, Σ A ≠ 0; design.md 1.1)
    ExactCoverage, ///< texture sampling with exact-coverage baking (Σ A = 0, exact area, O(h²) waterline error)
    ExactMesh,     ///< clip every triangle against the water: exact in flat water, cost ∝ triangles
};

/// Name on the command line, in scene files and JSON: "default" (Auto), "texel-centre", "exact-coverage",
/// "exact-mesh" (the registry's IntegrationMethod::name); "unknown" for a value that is no method.
const char* buoyancyMethodName(BuoyancyMethod method);

/// Parse a name of buoyancyMethodName ("default" gives Auto); std::nullopt for an unknown one.
std::optional<BuoyancyMethod> parseBuoyancyMethod(const std::string& name);

/// Largest triangle count for which Auto picks exact-mesh: it is exact in flat water, and measured
/// (docs/benchmarks) 12–15× cheaper per body-substep than exact-coverage 512² on 17–20k-triangle
/// meshes; the two costs meet at roughly 10⁵–2·10⁵ triangles.
constexpr std::size_t kDefaultExactMeshMaxTriangles = 131072;

/// The library's default: exact-mesh for meshes of at most kDefaultExactMeshMaxTriangles triangles,
/// otherwise exact-coverage at 512² (its O(h²) error is then ≈ 16× below the 128² figures, which the default accuracy
/// goals need on curved meshes with a generated atlas). Methods other than Auto are returned unchanged.
BuoyancyMethod resolveMethod(BuoyancyMethod requested, std::size_t triangleCount);

/// Texture size Auto uses when it resolves to a texture method.
constexpr int kDefaultLargeMeshTexture = 512;

}  // namespace buoyancy
