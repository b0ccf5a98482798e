#pragma once
/// @file MeshImport.h
/// Loading meshes through assimp. assimp itself can crash or hang on malformed files: a program that
/// loads untrusted files should call this in a child process with a time limit (the `buoyancy` CLI does,
/// see bullet_examples/cli/ChildProcessImport.h).

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace buoyancy {

/// Thrown for every mesh that cannot be used; what() names the file and the problem with a count,
/// e.g. "boat.obj: open surface: 12 boundary edges".
class MeshError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// File extensions (lower case, with dot) we import and test: .obj .ply .stl .gltf .glb .dae .fbx .3ds
const std::vector<std::string>& supportedMeshExtensions();

/// Import every mesh of a file as one triangle soup in the scene's frame (assimp node transforms
/// applied), scaled by `scale`, UVs of channel 0 per corner. No welding or checking yet.
/// Node transforms with a negative determinant (mirrors) have their triangles' winding reversed so that
/// outward stays outward. Point and line primitives are skipped (with a warning).
/// @param[in] path  file to read; the extension (case-insensitive) must be in supportedMeshExtensions()
/// @param[in] scale  uniform scale (> 0, finite) applied after the node transforms
/// @param[out] warnings  when not null, receives what was skipped (points, lines, extra UV channels)
/// @throws MeshError for a missing file, an empty file, an extension off the allow-list, an importer
///         error, no triangles (point clouds, line sets), a bad scale.
TriangleMesh importMeshFile(const std::string& path, double scale = 1.0,
                            std::vector<MeshWarning>* warnings = nullptr);

}  // namespace buoyancy
