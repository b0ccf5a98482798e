#pragma once
/// @file BenchShapes.h
/// The shapes and poses of the speed-against-error benchmark: analytic meshes from
/// PrimitiveMeshes, a real model from assimp-testmodels, the bundled low-poly boat, and high-poly cases.

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <Eigen/Geometry>
#include <string>
#include <vector>

class btWaterSurface;

namespace buoyancy::bench {

/// One benchmark shape (closed, outward mesh in its own frame, m).
struct BenchShape {
    std::string name;  ///< id used in the CSVs, e.g. "sphere", "duck-x4"
    std::string note;  ///< how it was made, for the README
    TriangleMesh mesh; ///< the mesh
};

/// Flat 1→4 subdivision (edge midpoints, UVs interpolated per corner): the same solid with 4× the
/// triangles, so exact values are unchanged and only the cost grows.
TriangleMesh subdivideMesh(const TriangleMesh& mesh);

/// The bundled low-poly boat (bullet_examples/models/boat_hull.obj, 850 triangles), imported and prepared.
/// @throws std::runtime_error when the file is missing or unusable
TriangleMesh loadBoatHull();

/// The benchmark shapes. Quick: box, sphere, boat. Full: + torus, duck (assimp-testmodels Collada/duck.dae,
/// 4212 triangles), duck-x4 (the duck subdivided once, 16848 triangles) and torus-fine (160×64, 20480
/// triangles), the ≥ 10k-triangle cases. A model that cannot be loaded is left out with a line in `warnings`.
std::vector<BenchShape> benchShapes(bool quick, std::vector<std::string>& warnings);

/// The low-poly boat hull of the wave rows (bullet_examples/models/hull_lowpoly.obj, 84 triangles, 5 m long, made by
/// scripts/make_lowpoly_hull.py), imported and prepared.
/// @throws std::runtime_error when the file is missing or unusable
TriangleMesh loadLowPolyHull();

/// The shapes of the wave rows (docs/benchmarks/README.md, "Wave rows"): `box` (the 12-triangle box of the flat
/// rows, 2 × 0.6 × 1 m), `cylinder` (a closed 16-sided log, radius 0.4 m, 3 m long along x, 64 triangles) and `hull`
/// (loadLowPolyHull, 84 triangles). A model that cannot be loaded is left out with a line in `warnings`.
std::vector<BenchShape> waveBenchShapes(std::vector<std::string>& warnings);

/// One pose of a body relative to flat water at y = 0 (flat rows) or to a wave surface at a time (wave rows).
struct BenchPose {
    std::string id;          ///< flat: "d0.30_h20" (draft fraction, heel in degrees); waves: "t3.20_dy-0.25_heel15"
    double draftFraction = 0; ///< flat: submerged part of the posed body's height, 0..1
    double heelDegrees = 0;   ///< rotation about the body's x axis (the boat's roll axis), degrees
    double time = 0;          ///< waves: the water's time, s
    double offsetFraction = 0; ///< waves: height of the body's centre above the local water, fraction of its height
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity(); ///< mesh frame → world
};

/// Draft × heel sweep: the mesh is rotated by the heel about x through its bounding-box centre, then moved
/// so that the water plane y = 0 cuts its vertical extent at each draft fraction (0 = lowest point, 1 = top).
std::vector<BenchPose> benchPoses(const TriangleMesh& mesh, const std::vector<double>& draftFractions,
                                  const std::vector<double>& heelDegrees);

/// Poses near the local water surface (wave rows): for every time t_i (s) and offset o_j (fraction of the heeled
/// body's height), the mesh is heeled by heelDegrees[(i + j) mod size] about its x axis through its bounding-box
/// centre, and that centre is put at (x, z) = (0, 0) and y = η(0, 0, t_i) + o_j · height, the water's height there
/// (a height query, not a wave particle). Id "t3.20_dy-0.25_heel15".
std::vector<BenchPose> waveBenchPoses(const TriangleMesh& mesh, const btWaterSurface& water,
                                      const std::vector<double>& times, const std::vector<double>& offsetFractions,
                                      const std::vector<double>& heelDegrees);

/// Length of the diagonal of the mesh's axis-aligned bounding box (mesh frame), m.
double boundingBoxDiagonal(const TriangleMesh& mesh);

}  // namespace buoyancy::bench
