#pragma once
/// @file PrimitiveMeshes.h
/// Closed, outward, UV-mapped meshes of analytic shapes, centred on the origin (tests, scenes, examples).

#include <BulletBuoyancy/mesh/TriangleMesh.h>

namespace buoyancy {

/// Box of full extents sx × sy × sz, m; each face its own UV chart.
TriangleMesh makeBoxMesh(double sx, double sy, double sz);
/// UV sphere of radius r, m, with `segments` around (longitude) and `rings` from pole to pole.
TriangleMesh makeSphereMesh(double radius, int segments = 64, int rings = 32);
/// Cylinder of radius r and full height h along y, centred at mid-height, `segments` around.
TriangleMesh makeCylinderMesh(double radius, double height, int segments = 64);
/// Torus around the y axis: major radius R (centre of tube), minor radius r.
TriangleMesh makeTorusMesh(double majorRadius, double minorRadius, int majorSegments = 64, int minorSegments = 32);

}  // namespace buoyancy
