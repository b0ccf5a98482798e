/// @file MeshImport.cpp
/// assimp 5.2 loader: one triangle soup in the scene's frame (node transforms applied by our own walk of
/// the node tree), scaled, with per-corner UVs of channel 0. Welding and checks live in MeshRepair.cpp.

#include <BulletBuoyancy/mesh/MeshImport.h>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <system_error>

namespace buoyancy {

namespace {

std::string lowerCase(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

std::string allowListText() {
    std::string out;
    for (const std::string& e : supportedMeshExtensions()) out += (out.empty() ? "" : " ") + e;
    return out;
}

/// Counts of what the walk found, for warnings and the "no triangles" error.
struct WalkStats {
    std::size_t points = 0;
    std::size_t lines = 0;
    std::size_t polygons = 0;  ///< faces with > 3 corners left after triangulation (should be none)
    std::size_t bad_indices = 0;
    std::size_t mirrored_instances = 0;
    std::size_t faceless_vertices = 0;  ///< vertices of meshes without any face (point clouds)
};

/// Appends every mesh instance below `node` (recursively) to `out`, with `parent` the accumulated transform.
void walkNode(const aiScene& scene, const aiNode& node, const Eigen::Matrix4d& parent, double scale,
              TriangleMesh& out, bool& anyUvs, WalkStats& stats, int depth) {
    if (depth > 1000) throw std::runtime_error("node tree deeper than 1000 levels (recursive nodes?)");
    const aiMatrix4x4& m = node.mTransformation;  // row-major, column vectors: p' = M p
    Eigen::Matrix4d local;
    local << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
    const Eigen::Matrix4d global = parent * local;
    const Eigen::Matrix3d linear = global.topLeftCorner<3, 3>();
    const Eigen::Vector3d translation = global.topRightCorner<3, 1>();
    // A mirroring transform turns counter-clockwise into clockwise: swap two corners to keep outward.
    const bool mirrored = linear.determinant() < 0.0;

    for (unsigned k = 0; k < node.mNumMeshes; ++k) {
        const unsigned meshIndex = node.mMeshes[k];
        if (meshIndex >= scene.mNumMeshes || scene.mMeshes[meshIndex] == nullptr) {
            ++stats.bad_indices;
            continue;
        }
        const aiMesh& mesh = *scene.mMeshes[meshIndex];
        if (mesh.mNumVertices > 0 && mesh.mVertices == nullptr) { ++stats.bad_indices; continue; }
        if (mesh.mNumFaces > 0 && mesh.mFaces == nullptr) { ++stats.bad_indices; continue; }
        if (mirrored) ++stats.mirrored_instances;
        if (mesh.mNumFaces == 0) stats.faceless_vertices += mesh.mNumVertices;
        const std::size_t base = out.vertices.size();
        for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
            const aiVector3D& p = mesh.mVertices[v];
            const Eigen::Vector3d local3(p.x, p.y, p.z);
            out.vertices.push_back(scale * (linear * local3 + translation));
        }
        const bool hasUv = mesh.HasTextureCoords(0) && mesh.mNumUVComponents[0] >= 2;
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const aiFace& face = mesh.mFaces[f];
            if (face.mNumIndices > 0 && face.mIndices == nullptr) { ++stats.bad_indices; continue; }
            if (face.mNumIndices == 1) { ++stats.points; continue; }
            if (face.mNumIndices == 2) { ++stats.lines; continue; }
            if (face.mNumIndices != 3) { ++stats.polygons; continue; }
            bool ok = true;
            for (int c = 0; c < 3; ++c) ok = ok && face.mIndices[c] < mesh.mNumVertices;
            if (!ok) { ++stats.bad_indices; continue; }
            int order[3] = {0, 1, 2};
            if (mirrored) std::swap(order[1], order[2]);
            out.triangles.emplace_back(static_cast<int>(base + face.mIndices[order[0]]),
                                       static_cast<int>(base + face.mIndices[order[1]]),
                                       static_cast<int>(base + face.mIndices[order[2]]));
            for (int c = 0; c < 3; ++c) {
                if (hasUv) {
                    const aiVector3D& t = mesh.mTextureCoords[0][face.mIndices[order[c]]];
                    out.corner_uvs.emplace_back(t.x, t.y);
                } else {
                    // Placeholder; dropped below unless every triangle of the scene has UVs.
                    out.corner_uvs.emplace_back(std::nan(""), std::nan(""));
                }
            }
            anyUvs = anyUvs || hasUv;
        }
        if (out.vertices.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
            throw std::runtime_error("too many vertices for 32-bit indices");
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c)
        if (node.mChildren[c] != nullptr)
            walkNode(scene, *node.mChildren[c], global, scale, out, anyUvs, stats, depth + 1);
}

}  // namespace

const std::vector<std::string>& supportedMeshExtensions() {
    static const std::vector<std::string> extensions = {".obj", ".ply", ".stl", ".gltf",
                                                        ".glb", ".dae", ".fbx", ".3ds"};
    return extensions;
}

TriangleMesh importMeshFile(const std::string& path, double scale, std::vector<MeshWarning>* warnings) {
    namespace fs = std::filesystem;
    const std::string name = fs::path(path).filename().string().empty() ? path : fs::path(path).filename().string();
    auto fail = [&](const std::string& problem) { return MeshError(name + ": " + problem); };

    if (!(std::isfinite(scale) && scale > 0.0)) {
        std::ostringstream s;
        s << "scale must be finite and > 0 (got " << scale << ")";
        throw fail(s.str());
    }
    const std::string ext = lowerCase(fs::path(path).extension().string());
    const auto& allowed = supportedMeshExtensions();
    if (std::find(allowed.begin(), allowed.end(), ext) == allowed.end())
        throw fail("unknown format '" + (ext.empty() ? std::string("(no extension)") : ext) +
                   "' (supported: " + allowListText() + ")");
    std::error_code ec;
    if (!fs::exists(path, ec)) throw fail("file not found");
    if (!fs::is_regular_file(path, ec)) throw fail("not a regular file");
    const auto size = fs::file_size(path, ec);
    if (ec) throw fail("cannot read file (" + ec.message() + ")");
    if (size == 0) throw fail("empty file");

    Assimp::Importer importer;
    // Triangulate polygons only. We weld ourselves (MeshRepair.cpp), so no JoinIdenticalVertices;
    // transforms are applied by our walk; indices are checked by the walk (aiProcess_ValidateDataStructure
    // would reject whole files for one empty mesh and turns point clouds into an opaque message).
    const aiScene* scene = nullptr;
    try {
        scene = importer.ReadFile(path, aiProcess_Triangulate);
    } catch (const std::exception& e) {
        throw fail(std::string("importer error: ") + e.what());
    }
    if (scene == nullptr) {
        std::string err = importer.GetErrorString();
        while (!err.empty() && std::isspace(static_cast<unsigned char>(err.back()))) err.pop_back();
        throw fail("importer error: " + (err.empty() ? std::string("unknown") : err));
    }
    if (scene->mRootNode == nullptr) throw fail("no triangles (the scene has no node tree)");

    TriangleMesh out;
    bool anyUvs = false;
    WalkStats stats;
    try {
        walkNode(*scene, *scene->mRootNode, Eigen::Matrix4d::Identity(), scale, out, anyUvs, stats, 0);
    } catch (const std::exception& e) {
        throw fail(e.what());
    }
    if (out.triangles.empty()) {
        std::ostringstream s;
        s << "no triangles";
        if (stats.points > 0 || stats.lines > 0)
            s << " (" << stats.points << " points, " << stats.lines << " line segments: a point cloud or line set)";
        else if (stats.faceless_vertices > 0)
            s << " (a point cloud: " << stats.faceless_vertices << " vertices without faces)";
        throw fail(s.str());
    }
    // Keep UVs only when every triangle has them (a partly mapped scene is treated as unmapped).
    const bool allUvs = anyUvs && std::none_of(out.corner_uvs.begin(), out.corner_uvs.end(),
                                               [](const Eigen::Vector2d& t) { return std::isnan(t.x()); });
    if (!allUvs) out.corner_uvs.clear();

    if (warnings != nullptr) {
        auto warn = [&](std::size_t n, const char* what) {
            if (n == 0) return;
            std::ostringstream s;
            s << name << ": skipped " << n << ' ' << what;
            warnings->push_back({s.str()});
        };
        warn(stats.points, "point primitives");
        warn(stats.lines, "line primitives");
        warn(stats.polygons, "faces the importer could not triangulate");
        warn(stats.bad_indices, "faces or mesh references with out-of-range indices");
        if (anyUvs && !allUvs) warnings->push_back({name + ": only some meshes have UVs; UVs ignored"});
    }
    return out;
}

}  // namespace buoyancy
