// The accuracy goals, end to end (import → UVs → bake → integrals), against the independent polyhedral
// oracle of tests/oracles on analytic shapes made by the library and on real models nobody here wrote
// (Debian's assimp-testmodels).
#include "AccuracyHarness.h"
#include <BulletBuoyancy/bullet/btBuoyancySettings.h>
#include "oracles/OracleMeshes.h"

#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/MeshRepair.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

using namespace buoyancy;
using buoyancy_test::describe;
using buoyancy_test::measureAccuracy;

namespace {

struct NamedMesh {
    std::string name;
    TriangleMesh mesh;
};

std::vector<NamedMesh> analyticShapes() {
    return {{"box 2x0.6x1", makeBoxMesh(2.0, 0.6, 1.0)},
            {"sphere R0.5", makeSphereMesh(0.5, 64, 32)},
            {"cylinder r0.4 h1.5", makeCylinderMesh(0.4, 1.5, 64)},
            {"torus 1/0.3", makeTorusMesh(1.0, 0.3, 64, 32)}};
}

/// Every closed model of more than 100 triangles in assimp-testmodels (the others are open, non-manifold or
/// boxes). All formats but STL occur (none of the package's STL files is closed).
std::vector<NamedMesh> realModels() {
    const std::string dir = BUOYANCY_ASSIMP_MODELS_DIR;
    const std::vector<std::string> files = {
        "Collada/duck.dae",          "3DS/fels.3ds",        "Collada/earthCylindrical.DAE",
        "FBX/animation_with_skeleton.fbx", "FBX/global_settings.fbx", "OBJ/empty_mat.obj", "FBX/huesitos.fbx",
    };
    std::vector<NamedMesh> out;
    for (const auto& f : files) {
        TriangleMesh m = importMeshFile(dir + "/" + f);
        prepareMesh(m, f);
        out.push_back({f, std::move(m)});
    }
    return out;
}

void checkDefaultGoals(const NamedMesh& m) {
    const auto r = measureAccuracy(m.mesh, BuoyancyMethod::Auto, 0);
    INFO(m.name << ": " << describe(r));
    WARN(m.name << " default: " << describe(r));
    buoyancy_test::recordAccuracyRow(m.name, m.mesh.triangleCount(), "default", r);
    CHECK(r.dry_volume_pct <= 0.01);
    CHECK(r.centre_pct_diag <= 0.1);
    CHECK(r.inertia_pct <= 0.5);
    CHECK(r.sub_volume_pct <= 0.01);
    CHECK(r.cob_pct_diag <= 0.1);
}

void checkTextureGoals(const NamedMesh& m) {
    const auto r = measureAccuracy(m.mesh, BuoyancyMethod::ExactCoverage, 128);
    INFO(m.name << ": " << describe(r));
    WARN(m.name << " texture path: " << describe(r));
    buoyancy_test::recordAccuracyRow(m.name, m.mesh.triangleCount(), "texture path", r);
    CHECK(r.dry_volume_pct <= 0.1);
    CHECK(r.centre_pct_diag <= 0.5);
    CHECK(r.inertia_pct <= 1.0);
    CHECK(r.sub_volume_pct <= 0.1);
    CHECK(r.cob_pct_diag <= 0.5);
}

}  // namespace

TEST_CASE("accuracy: default settings meet the goals on analytic shapes", "[accuracy]") {
    for (const auto& m : analyticShapes()) checkDefaultGoals(m);
}

TEST_CASE("accuracy: exact-coverage 128 meets the texture-path goals on analytic shapes", "[accuracy]") {
    for (const auto& m : analyticShapes()) checkTextureGoals(m);
}

TEST_CASE("accuracy: default settings on high-poly meshes (exact-coverage 512) meet the goals", "[accuracy][slow]") {
    // Above kDefaultExactMeshMaxTriangles the default switches to the texture path: these meshes take it.
    const std::vector<NamedMesh> meshes = {{"sphere 384x192", makeSphereMesh(0.5, 384, 192)},
                                           {"torus 512x160", makeTorusMesh(1.0, 0.3, 512, 160)}};
    for (const auto& m : meshes) {
        REQUIRE(m.mesh.triangleCount() > kDefaultExactMeshMaxTriangles);
        auto r = measureAccuracy(m.mesh, BuoyancyMethod::Auto, 0);
        REQUIRE(r.method == "exact-coverage");
        checkDefaultGoals(m);
        // The same meshes with their own UVs removed: the generated atlas must do as well.
        TriangleMesh noUv = m.mesh;
        noUv.corner_uvs.clear();
        checkDefaultGoals({m.name + " (no UVs)", noUv});
    }
}

TEST_CASE("accuracy: default settings meet the goals on real models", "[accuracy]") {
    for (const auto& m : realModels()) checkDefaultGoals(m);
}

TEST_CASE("accuracy: exact-coverage 128 meets the texture-path goals on real models", "[accuracy]") {
    for (const auto& m : realModels()) checkTextureGoals(m);
}

/// Every model of assimp-testmodels 5.2.5 in a format the importer accepts that passes the mesh checks (closed,
/// oriented, finite, a positive volume), found by running `buoyancy hydrostatics --method exact-mesh` on each
/// (docs/accuracy.md, "Every assimp test model"): 63 of the package's 149 files in those formats.
const std::vector<std::string> kEveryClosedModel = {
        "3DS/CameraRollAnim.3ds",
        "3DS/CameraRollAnimWithChildObject.3ds",
        "3DS/RotatingCube.3DS",
        "3DS/TargetCameraAnim.3ds",
        "3DS/cube_with_diffuse_texture.3DS",
        "3DS/cube_with_specular_texture.3DS",
        "3DS/cubes_with_alpha.3DS",
        "3DS/fels.3ds",
        "3DS/test1.3ds",
        "Collada/anims_with_full_rotations_between_keys.DAE",
        "Collada/box_nested_animation.dae",
        "Collada/cube_UTF8BOM.dae",
        "Collada/cube_emptyTags.dae",
        "Collada/cube_triangulate.dae",
        "Collada/cube_tristrips.dae",
        "Collada/cube_with_2UVs.DAE",
        "Collada/cube_xmlspecialchars.dae",
        "Collada/duck.dae",
        "Collada/duck_triangulate.dae",
        "Collada/earthCylindrical.DAE",
        "Collada/kwxport_test_vcolors.dae",
        "Collada/sphere.dae",
        "Collada/sphere_triangulate.dae",
        "FBX/animation_with_skeleton.fbx",
        "FBX/box.fbx",
        "FBX/boxWithCompressedCTypeArray.FBX",
        "FBX/boxWithUncompressedCTypeArray.FBX",
        "FBX/box_orphant_embedded_texture.fbx",
        "FBX/close_to_identity_transforms.fbx",
        "FBX/cubes_nonames.fbx",
        "FBX/cubes_with_mirroring_and_pivot.fbx",
        "FBX/cubes_with_names.fbx",
        "FBX/embedded_ascii/box.FBX",
        "FBX/embedded_ascii/box_embedded_texture_fragmented.fbx",
        "FBX/global_settings.fbx",
        "FBX/huesitos.fbx",
        "FBX/maxPbrMaterial_metalRough.fbx",
        "FBX/maxPbrMaterial_specGloss.fbx",
        "FBX/phong_cube.fbx",
        "OBJ/box.obj",
        "OBJ/box_mat_with_spaces.obj",
        "OBJ/box_without_lineending.obj",
        "OBJ/cube_mtllib_after_g.obj",
        "OBJ/cube_usemtl.obj",
        "OBJ/cube_with_vertexcolors.obj",
        "OBJ/cube_with_vertexcolors_uni.obj",
        "OBJ/empty_mat.obj",
        "OBJ/testmixed.obj",
        "PLY/cube.ply",
        "PLY/cube_binary.ply",
        "PLY/cube_uv.ply",
        "glTF/BoxTextured-glTF-Embedded/BoxTextured.gltf",
        "glTF/BoxTextured-glTF-MaterialsCommon/BoxTextured.gltf",
        "glTF/BoxTextured-glTF/BoxTextured.gltf",
        "glTF/TwoBoxes/TwoBoxes.gltf",
        "glTF2/BoxBadNormals-glTF-Binary/BoxBadNormals.glb",
        "glTF2/BoxTexcoords-glTF/boxTexcoords.gltf",
        "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb",
        "glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf",
        "glTF2/BoxTextured-glTF-pbrSpecularGlossiness/BoxTextured.gltf",
        "glTF2/BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf",
        "glTF2/BoxTextured-glTF/BoxTextured.gltf",
        "glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf"};

TEST_CASE("accuracy: exact-coverage 128 meets the texture-path goals on every closed assimp test model with its own "
          "UVs and with the generated atlas", "[accuracy]") {
    const std::string dir = BUOYANCY_ASSIMP_MODELS_DIR;
    for (const std::string& file : kEveryClosedModel) {
        TriangleMesh m = importMeshFile(dir + "/" + file);
        prepareMesh(m, file);
        const bool ownUvs = !m.corner_uvs.empty();
        checkTextureGoals({file + (ownUvs ? " (its UVs)" : " (no UVs: atlas)"), m});
        if (!ownUvs) continue;
        m.corner_uvs.clear();  // the same model through the generated atlas
        checkTextureGoals({file + " (atlas)", m});
    }
}

TEST_CASE("accuracy: the paper's texel-centre method at 256, 512, 1024 (report)", "[accuracy][long]") {
    auto all = analyticShapes();
    for (auto& m : realModels()) all.push_back(std::move(m));
    for (const auto& m : all)
        for (int n : {256, 512, 1024}) {
            const auto r = measureAccuracy(m.mesh, BuoyancyMethod::TexelCentre, n, 5);
            WARN(m.name << " texel-centre: " << describe(r));
            buoyancy_test::recordAccuracyRow(m.name, m.mesh.triangleCount(), "paper", r);
            CHECK(r.dry_volume_pct < 100);  // sanity only: this test reports, the goals are for the methods above
        }
}

// ---- Automatic level of detail (btBuoyancySettings::errorBudget, integrals/LevelOfDetail.h) ---------
// The model's errors come from docs/benchmarks; here the picked configuration is measured against the oracle.
TEST_CASE("automatic level of detail: the picked configuration meets its budget on analytic shapes, tighter never "
          "picks cheaper-but-worse",
          "[accuracy][lod]") {
    const std::vector<std::pair<std::string, buoyancy::TriangleMesh>> shapes = {
        {"sphere", buoyancy_test::toTriangleMesh(buoyancy_test::oracleSphere(0.5, 64, 32))},
        {"torus", buoyancy_test::toTriangleMesh(buoyancy_test::oracleTorus(0.6, 0.2, 64, 32))},
        {"box", buoyancy_test::toTriangleMesh(buoyancy_test::oracleBox(2.0, 0.6, 1.0))}};
    const std::vector<double> budgets = {1.0, 0.3, 0.1, 0.03};  // loosest first
    for (const auto& [name, mesh] : shapes) {
        // A texture method must be picked to test anything: as for a mesh too big to clip (10⁶ triangles).
        btBuoyancySettings st;
        double prevCost = -1, prevMeasured = 1e300;
        int prevN = 0;
        for (double b : budgets) {
            st.errorBudget = b;
            const btBuoyancyLevelOfDetail pick = btBuoyancyPickLevelOfDetail(st, 1000000);
            REQUIRE(pick.method == btBuoyancyMethod::ExactCoverage);
            REQUIRE(pick.withinBudget);
            const buoyancy_test::AccuracyReport r =
                buoyancy_test::measureAccuracy(mesh, buoyancy::BuoyancyMethod::ExactCoverage, pick.textureSize, 5);
            INFO(name << ": budget " << b << " % -> " << pick.description << "; measured " << buoyancy_test::describe(r));
            CHECK(r.sub_volume_pct <= b);
            // Tighter budget: never a cheaper configuration that is worse (here: N never shrinks, and the measured
            // worst error never grows by more than rounding).
            CHECK(pick.textureSize >= prevN);
            if (pick.textureSize == prevN) CHECK(r.sub_volume_pct <= prevMeasured * (1 + 1e-9));
            else CHECK(r.sub_volume_pct <= prevMeasured);
            prevN = pick.textureSize;
            prevMeasured = r.sub_volume_pct;
            (void)prevCost;
        }
        // On the real (small) mesh Auto may pick exact-mesh; whatever it picks, the measured error is within budget.
        st.errorBudget = 0.1;
        const btBuoyancyLevelOfDetail own = btBuoyancyPickLevelOfDetail(st, mesh.triangleCount());
        const buoyancy_test::AccuracyReport r = buoyancy_test::measureAccuracy(
            mesh, own.method == btBuoyancyMethod::ExactMesh ? buoyancy::BuoyancyMethod::ExactMesh : buoyancy::BuoyancyMethod::ExactCoverage,
            own.textureSize, 5);
        INFO(name << " (" << mesh.triangleCount() << " triangles): " << own.description);
        CHECK(r.sub_volume_pct <= 0.1);
    }
}

TEST_CASE("automatic level of detail: the model's picks are ordered and explained", "[accuracy][lod]") {
    btBuoyancySettings st;
    CHECK(btBuoyancyPickLevelOfDetail(st, 1000).description.find("no error budget") != std::string::npos);
    double prevError = 1e300, prevCost = -1;
    for (double b : {5.0, 1.0, 0.3, 0.1, 0.03, 0.01, 0.003, 0.001, 1e-6}) {
        st.errorBudget = b;
        for (std::size_t tris : {std::size_t(800), std::size_t(20000), std::size_t(2000000)}) {
            const btBuoyancyLevelOfDetail p = btBuoyancyPickLevelOfDetail(st, tris);
            INFO("budget " << b << ", " << tris << " triangles: " << p.description);
            CHECK(p.withinBudget);
            CHECK(p.modelVolumeErrorPct <= b);
            CHECK(!p.description.empty());
        }
        // For one mesh size: tighter budget → model error never larger, model cost never smaller.
        const btBuoyancyLevelOfDetail p = btBuoyancyPickLevelOfDetail(st, 2000000);
        const double cost = p.method == btBuoyancyMethod::ExactMesh ? 2e6 : double(p.textureSize) * p.textureSize;
        CHECK(p.modelVolumeErrorPct <= prevError);
        CHECK(cost >= prevCost);
        prevError = p.modelVolumeErrorPct;
        prevCost = cost;
    }
    st.errorBudget = -1;
    CHECK_THROWS_AS(btBuoyancyPickLevelOfDetail(st, 100), std::invalid_argument);
    st.errorBudget = std::nan("");
    CHECK_THROWS_AS(btBuoyancyPickLevelOfDetail(st, 100), std::invalid_argument);
}
