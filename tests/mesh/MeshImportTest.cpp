// Import through assimp: the allow-list of formats on real closed models from Debian's assimp-testmodels,
// node transforms, UVs, and the import errors. Expected values: bounding-box volumes of box-shaped
// models, and transforms/counts written by hand in tests/data/meshes/generate.py.

#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/MeshRepair.h>
#include "mesh/MeshTestUtil.h"

#include <catch2/catch.hpp>

using namespace buoyancy;
using namespace mesh_test;
using Catch::Matchers::Equals;
using Catch::Matchers::StartsWith;

// Closed models of assimp-testmodels 5.2.5, one or more per allowed format (checked with prepareMesh:
// closed, consistently oriented, one component). The box-shaped ones have volume = bounding-box volume.
// No STL file in the package is closed (Spider, Wuson, sphereWithHole, 3DSMaxExport are open or
// non-manifold), so STL is covered by our own triangle soup tests/data/meshes/box_soup.stl.
//   OBJ  OBJ/box.obj, OBJ/cube_usemtl.obj           PLY  PLY/cube.ply, PLY/cube_binary.ply, PLY/cube_uv.ply
//   glTF glTF2/BoxTextured-glTF/BoxTextured.gltf     GLB  glTF2/BoxTextured-glTF-Binary/BoxTextured.glb
//   DAE  Collada/cube_triangulate.dae, Collada/duck.dae (4212 triangles, not a box)
//   FBX  FBX/phong_cube.fbx, FBX/boxWithCompressedCTypeArray.FBX (upper-case extension)
//   3DS  3DS/cube_with_diffuse_texture.3DS, 3DS/fels.3ds (768 triangles, not a box)
TEST_CASE("import: closed box-shaped models of every allowed format have volume = bounding-box volume", "[mesh][import]") {
    const char* files[] = {"OBJ/box.obj",
                           "OBJ/cube_usemtl.obj",
                           "PLY/cube.ply",
                           "PLY/cube_binary.ply",
                           "PLY/cube_uv.ply",
                           "glTF2/BoxTextured-glTF/BoxTextured.gltf",
                           "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb",
                           "Collada/cube_triangulate.dae",
                           "FBX/phong_cube.fbx",
                           "FBX/boxWithCompressedCTypeArray.FBX",
                           "3DS/cube_with_diffuse_texture.3DS"};
    for (const char* f : files) {
        INFO(f);
        TriangleMesh m = importMeshFile(model(f));
        REQUIRE(m.triangleCount() == 12);
        const MeshReport r = prepareMesh(m, f);
        CHECK(r.components == 1);
        CHECK(r.flipped_components == 0);
        CHECK(r.degenerate_removed == 0);
        CHECK(r.warnings.empty());
        CHECK(m.vertices.size() == 8);  // welded: a box has 8 corners
        const Eigen::Vector3d ext = bbox(m).sizes();
        CHECK(tetraVolume(m) == Approx(ext.prod()).epsilon(1e-6));
    }
}

TEST_CASE("import: closed non-box models (Collada duck, 3DS rock) are closed and outward", "[mesh][import]") {
    for (const char* f : {"Collada/duck.dae", "3DS/fels.3ds"}) {
        INFO(f);
        TriangleMesh m = importMeshFile(model(f));
        const std::size_t before = m.triangleCount();
        const MeshReport r = prepareMesh(m, f);
        CHECK(r.components == 1);
        CHECK(r.flipped_components == 0);
        CHECK(m.triangleCount() == before);
        const double v = tetraVolume(m);
        CHECK(v > 0);
        CHECK(v < bbox(m).volume());
    }
    TriangleMesh duck = importMeshFile(model("Collada/duck.dae"));
    CHECK(duck.triangleCount() == 4212);
    CHECK(duck.hasUvs());
}

TEST_CASE("import: node transforms, mirrors and the user's scale are applied", "[mesh][import]") {
    // node_transforms.gltf: a centred unit cube instanced as (a) translate (10,0,0) ∘ scale (2,3,4) and
    // (b) translate (0,-20,0) ∘ scale (-1,1,1) (a mirror: winding must be reversed to stay outward).
    for (double scale : {1.0, 2.0}) {
        TriangleMesh m = importMeshFile(data("node_transforms.gltf"), scale);
        REQUIRE(m.triangleCount() == 24);
        // Triangles 0..11 belong to the first instance met in the node walk (node 0 → child node 1).
        TriangleMesh a, b;
        a.vertices = b.vertices = m.vertices;
        a.triangles.assign(m.triangles.begin(), m.triangles.begin() + 12);
        b.triangles.assign(m.triangles.begin() + 12, m.triangles.end());
        const Eigen::AlignedBox3d ba = bbox(a), bb = bbox(b);
        CHECK(ba.min().isApprox(scale * Eigen::Vector3d(9, -1.5, -2), 1e-12));
        CHECK(ba.max().isApprox(scale * Eigen::Vector3d(11, 1.5, 2), 1e-12));
        CHECK(bb.min().isApprox(scale * Eigen::Vector3d(-0.5, -20.5, -0.5), 1e-12));
        CHECK(bb.max().isApprox(scale * Eigen::Vector3d(0.5, -19.5, 0.5), 1e-12));
        CHECK(tetraVolume(a) == Approx(24 * scale * scale * scale));
        CHECK(tetraVolume(b) == Approx(1 * scale * scale * scale));  // positive: mirror handled
        const MeshReport r = prepareMesh(m, "node_transforms.gltf");
        CHECK(r.components == 2);
        CHECK(r.flipped_components == 0);
        CHECK(r.warnings.empty());
    }
}

TEST_CASE("import: UVs of channel 0 per corner when present", "[mesh][import]") {
    TriangleMesh withUv = importMeshFile(model("glTF2/BoxTextured-glTF/BoxTextured.gltf"));
    REQUIRE(withUv.hasUvs());
    CHECK(withUv.corner_uvs.size() == 3 * withUv.triangleCount());
    for (const Eigen::Vector2d& t : withUv.corner_uvs) CHECK(t.allFinite());
    // UVs follow their triangles through welding.
    const auto uvsBefore = withUv.corner_uvs;
    prepareMesh(withUv, "BoxTextured.gltf");
    CHECK(withUv.corner_uvs == uvsBefore);
    TriangleMesh noUv = importMeshFile(model("OBJ/box.obj"));
    CHECK_FALSE(noUv.hasUvs());
    CHECK(noUv.corner_uvs.empty());
}

TEST_CASE("import: the STL triangle soup welds into a closed box", "[mesh][import]") {
    // box_soup.stl: 12 independent facets of the box [1,2]×[-1,1]×[0,3] (1 × 2 × 3).
    TriangleMesh m = importMeshFile(data("box_soup.stl"));
    CHECK(m.triangleCount() == 12);
    CHECK(m.vertices.size() == 36);  // a soup: three vertices per facet
    const MeshReport r = prepareMesh(m, "box_soup.stl");
    CHECK(m.vertices.size() == 8);
    CHECK(r.welded_vertices == 28);
    CHECK(r.components == 1);
    CHECK(tetraVolume(m) == Approx(1.0 * 2.0 * 3.0).epsilon(1e-12));
}

TEST_CASE("import: errors name the file and the problem", "[mesh][import][errors]") {
    CHECK_THROWS_WITH(importMeshFile(data("empty.obj")), Equals("empty.obj: empty file"));
    CHECK_THROWS_WITH(importMeshFile(data("box.xyz")),
                      Equals("box.xyz: unknown format '.xyz' (supported: .obj .ply .stl .gltf .glb .dae .fbx .3ds)"));
    CHECK_THROWS_WITH(importMeshFile(data("no_such_file.obj")), Equals("no_such_file.obj: file not found"));
    CHECK_THROWS_WITH(importMeshFile(model("OBJ/testpoints.obj")),
                      Equals("testpoints.obj: no triangles (24 points, 0 line segments: a point cloud or line set)"));
    CHECK_THROWS_WITH(importMeshFile(model("OBJ/testline.obj")), StartsWith("testline.obj: no triangles ("));
    CHECK_THROWS_WITH(importMeshFile(model("PLY/points.ply")), StartsWith("points.ply: no triangles"));
    CHECK_THROWS_WITH(importMeshFile(model("glTF2/RecursiveNodes/RecursiveNodes.gltf")),
                      StartsWith("RecursiveNodes.gltf: importer error: "));
    CHECK_THROWS_WITH(importMeshFile(model("OBJ/box.obj"), 0.0), StartsWith("box.obj: scale must be finite and > 0"));
    CHECK_THROWS_WITH(importMeshFile(model("OBJ/box.obj"), std::nan("")), StartsWith("box.obj: scale must be"));
    CHECK_THROWS_AS(importMeshFile(data("empty.obj")), MeshError);
    // A glTF with infinite vertex values imports, and the check rejects it.
    TriangleMesh inf = importMeshFile(model("glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb"));
    CHECK_THROWS_WITH(prepareMesh(inf, "BoxWithInfinites.glb"), StartsWith("BoxWithInfinites.glb: non-finite coordinates: "));
}

TEST_CASE("import: extensions are matched case-insensitively", "[mesh][import]") {
    CHECK(importMeshFile(model("3DS/RotatingCube.3DS")).triangleCount() == 12);
    CHECK(importMeshFile(model("Collada/cube_with_2UVs.DAE")).triangleCount() == 12);
    const auto& ext = supportedMeshExtensions();
    CHECK(ext.size() == 8);
}
