#pragma once
/// @file BuoyancyMethod.h
/// The ways the library can integrate buoyancy, their names, and the default choice per mesh.

#include <optional>
#include <string>

namespace buoyancy {

/// How the surface integrals are evaluated.
enum class BuoyancyMethod {
    Default,       ///< let the library choose per mesh (resolveMethod)
    TexelCentre,   ///< the paper's texture sampling, texel-centre baking (design.md 1.1)
    ExactCoverage, ///< texture sampling with exact-coverage baking (Σ A = 0, exact area)
    ExactMesh,     ///< clip every triangle against the water: exact in flat water, cost ∝ triangles
};

/// Name on the command line, in scene files and JSON: "default", "texel-centre", "exact-coverage", "exact-mesh".
const char* buoyancyMethodName(BuoyancyMethod method);

/// Parse a name of buoyancyMethodName; std::nullopt for an unknown one.
std::optional<BuoyancyMethod> parseBuoyancyMethod(const std::string& name);

/// True for the methods that bake a texture (texel-centre, exact-coverage).
bool methodUsesTexture(BuoyancyMethod method);

/// Texture side used when the user gives none: 128 for exact-coverage (meets the default accuracy goals (docs/accuracy.md) on
/// the shapes and models we test), 512 for texel-centre (the paper's own smallest size), 0 for exact-mesh.
int defaultTextureSize(BuoyancyMethod method);

/// Largest triangle count for which Default picks exact-mesh: it is exact in flat water, and measured
/// (docs/benchmarks) 12–15× cheaper per body-substep than exact-coverage 512² on 17–20k-triangle
/// meshes; the two costs meet at roughly 10⁵–2·10⁵ triangles.
constexpr std::size_t kDefaultExactMeshMaxTriangles = 131072;

/// The library's default: exact-mesh for meshes of at most kDefaultExactMeshMaxTriangles triangles,
/// otherwise exact-coverage at 512² (its O(h²) error is then ≈ 16× below the 128² figures, which the default accuracy goals need on curved meshes with a generated atlas). Methods other than
/// Default are returned unchanged.
BuoyancyMethod resolveMethod(BuoyancyMethod requested, std::size_t triangleCount);

/// Texture size Default uses when it resolves to a texture method.
constexpr int kDefaultLargeMeshTexture = 512;

}  // namespace buoyancy
