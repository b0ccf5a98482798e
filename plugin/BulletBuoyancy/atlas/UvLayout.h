#pragma once
/// @file UvLayout.h
/// Choosing the texture parameterisation (design.md 1.2): the model's own UVs when they are a valid
/// layout, otherwise an atlas we generate.

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <string>
#include <vector>

namespace buoyancy {

/// Why a model's UVs cannot be used (empty `problems` means they can).
struct UvLayoutCheck {
    bool usable = false;               ///< true when the model's UVs are a valid layout at this texture size
    std::vector<std::string> problems; ///< e.g. "no UVs", "37 triangles outside [0,1]", "overlapping UVs (120 triangles)"
};

/// Check the model's per-corner UVs: present, finite, inside [0,1]², no zero-area UV triangles, no two
/// triangles overlapping in UV space, and unrelated triangles not sharing texels at `textureSize`.
UvLayoutCheck checkUvLayout(const TriangleMesh& mesh, int textureSize);

/// Generate an atlas for a texture of textureSize×textureSize texels: charts grown from neighbouring,
/// near-coplanar triangles, each flattened without overlap, packed with at least one texel of gap between
/// charts. Returns 3·#T per-corner UVs in [0,1]².
/// @throws std::runtime_error when the charts cannot fit at this texture size (says the smallest size that fits)
std::vector<Eigen::Vector2d> generateAtlas(const TriangleMesh& mesh, int textureSize);

/// The UVs the baker uses and where they came from.
struct UvLayout {
    std::vector<Eigen::Vector2d> corner_uvs; ///< 3·#T
    bool generated = false;                  ///< false: the model's own UVs
    std::vector<std::string> reasons;        ///< why the model's UVs were not used (when generated)
};

/// The model's UVs when checkUvLayout accepts them (and preferModelUvs), else generateAtlas.
UvLayout chooseUvLayout(const TriangleMesh& mesh, int textureSize, bool preferModelUvs = true);

}  // namespace buoyancy
