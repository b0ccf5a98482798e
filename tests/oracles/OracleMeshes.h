#pragma once
/// @file OracleMeshes.h
/// Small closed, outward triangle meshes generated inside the tests (independent of plugin/mesh), as plain
/// vectors for the oracle, plus a conversion to the library's TriangleMesh.

#include <Eigen/Core>
#include <vector>

namespace buoyancy {
struct TriangleMesh;
}

namespace buoyancy_test {

/// A closed triangle mesh as plain vectors (outward CCW).
struct OracleMesh {
    std::vector<Eigen::Vector3d> verts; ///< #V positions, m
    std::vector<Eigen::Vector3i> tris;  ///< #T index triples
};

/// Axis-aligned box of extents a × b × c (x, y, z), centred at the origin, 12 triangles.
OracleMesh oracleBox(double a, double b, double c);
/// Tetrahedron with corners 0, e_x, e_y, e_z scaled by s, m.
OracleMesh oracleTetrahedron(double s);
/// UV sphere of radius R with `seg` longitudes and `rings` latitude bands.
OracleMesh oracleSphere(double R, int seg, int rings);
/// Torus about the y axis, tube centre radius R, tube radius r.
OracleMesh oracleTorus(double R, double r, int segMajor, int segMinor);
/// Closed cylinder of radius r, height h along y, centred at the origin.
OracleMesh oracleCylinder(double r, double h, int seg);
/// Copy into the library's mesh type (no UVs).
buoyancy::TriangleMesh toTriangleMesh(const OracleMesh& m);

}  // namespace buoyancy_test
