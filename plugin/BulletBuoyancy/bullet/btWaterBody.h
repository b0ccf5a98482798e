#pragma once
/// @file btWaterBody.h
/// A bounded water body of a btBuoyancyWorld: a water surface (any btWaterSurface) inside a region of the world, with
/// its own fluid density (a pool, a lake, a lock chamber, a tank). A world holds either one unbounded water
/// (btBuoyancyWorld's constructor, the default) or several water bodies whose regions do not overlap
/// (btBuoyancyWorld::addWaterBody; docs/integration.md, design.md 2.9).
///
/// A region is one of (btWaterRegionKind):
/// - Box: an axis-aligned box of the world (regionMin, regionMax);
/// - Polygon: a simple polygon footprint in the water frame's horizontal axes (x, z of btWaterFrame), extruded along
///   up from a bottom height to a top height (a lake with an irregular shore; non-convex footprints are cut into
///   triangles);
/// - Mesh: a closed, outward-oriented triangle mesh of the world (a tank, a stepped pool, an L-shaped lock, a lake
///   bed under a flat lid). A convex one with at most 32 face planes is clipped by its walls; any other is taken as
///   columns along up and must meet every vertical line in one segment at most (no overhang).
///
/// The water of a body fills its region from the region's bottom up to the surface: the region's sides and bottom
/// bound it, its top should be at or above the surface's highest point (the surface is not cut off at the top).
/// Heights are measured along the world's water frame's up (btWaterFrame), as for the unbounded water.

#include <LinearMath/btVector3.h>

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

class btWaterSurface;
class btWaterFrame;
namespace buoyancy {
struct WaterRegion;
}

/// The shape of a water body's region.
enum class btWaterRegionKind {
    Box,      ///< axis-aligned box of the world: btWaterBodyInfo::regionMin, regionMax
    Polygon,  ///< footprint polygon extruded along up: btWaterBodyInfo::footprint, bottom, top
    Mesh,     ///< closed triangle mesh: btWaterBodyInfo::meshVertices, meshTriangles
};

/// What a water body is made of (btBuoyancyWorld::addWaterBody copies it).
struct btWaterBodyInfo {
    /// Name used in messages, e.g. "pool" (empty: "water body <index>").
    std::string name;
    /// The water surface inside the region; not owned, must outlive the world. Its velocities (btFlatWaterSurface's
    /// uniform current, btRiverSurface's current along its channel, waves' orbital velocities) are the water's velocity
    /// in the region.
    const btWaterSurface* surface = nullptr;
    /// ρ_w, kg/m³ (fresh water 1000, sea water 1025), finite and > 0.
    double fluidDensity = 1000.0;
    /// Box: lower corner of the region's axis-aligned box, world, m; each coordinate finite and < regionMax's.
    btVector3 regionMin = btVector3(0, 0, 0);
    /// Box: upper corner of the region's axis-aligned box, world, m.
    btVector3 regionMax = btVector3(0, 0, 0);
    /// Which region bounds the water (Box by default: regionMin, regionMax; after them, so that the aggregate form
    /// {name, surface, density, min, max} keeps meaning a box).
    btWaterRegionKind regionKind = btWaterRegionKind::Box;
    /// Polygon: the footprint's corners in order (either winding), each (x, z) in the water frame's horizontal axes,
    /// m; at least 3, finite, a simple polygon (no edge crossing or touching a non-adjacent edge, no repeated corner,
    /// non-zero area). Non-convex footprints are allowed.
    std::vector<std::array<double, 2>> footprint = {};
    /// Polygon: height of the region's bottom along the water frame's up, m (water-frame y), finite.
    double bottom = 0.0;
    /// Polygon: height of the region's top along the water frame's up, m, finite and > bottom (at or above the
    /// surface's highest point).
    double top = 0.0;
    /// Mesh: the tank's vertices, world, m (finite).
    std::vector<btVector3> meshVertices = {};
    /// Mesh: three indices into meshVertices per triangle, counter-clockwise seen from outside (outward normals); the
    /// mesh must be closed (every edge shared by exactly two triangles, in opposite directions). A convex mesh with at
    /// most 32 distinct face planes (coplanar triangles share one) bounds the water by its walls' planes; any other
    /// mesh must meet every vertical line (along the water frame's up) in one segment at most, and bounds the water by
    /// its footprint seen from above (the shadows of its upward-facing triangles), from its floor up.
    std::vector<int> meshTriangles = {};
};

/// A water body as the world holds it (the region in double precision).
struct btWaterBody {
    std::string name;                          ///< as given, or "water body <index>"
    const btWaterSurface* surface = nullptr;   ///< not owned
    double fluidDensity = 1000.0;              ///< kg/m³
    btWaterRegionKind kind = btWaterRegionKind::Box;  ///< the region's shape
    /// Box: lower box corner, world, m (Polygon, Mesh: lower corner of the region's world bounding box; a polygon's
    /// in the water frame given to setRegion).
    Eigen::Vector3d regionMin = Eigen::Vector3d::Zero();
    /// Box: upper box corner, world, m (Polygon, Mesh: upper corner of the region's world bounding box).
    Eigen::Vector3d regionMax = Eigen::Vector3d::Zero();
    /// Polygon: the footprint's corners, water-frame (x, z), m, ordered so that the signed area
    /// ½ Σ (x_i z_{i+1} − x_{i+1} z_i) is positive (reversed if given the other way).
    std::vector<Eigen::Vector2d> footprint;
    /// Polygon: the footprint cut into triangles (indices into footprint, ordered as footprint).
    std::vector<std::array<int, 3>> footprintTriangles;
    double bottom = 0.0;  ///< Polygon: bottom height along up, m
    double top = 0.0;     ///< Polygon: top height along up, m
    std::vector<Eigen::Vector3d> meshVertices;       ///< Mesh: vertices, world, m
    std::vector<std::array<int, 3>> meshTriangles;   ///< Mesh: triangles, outward
    std::vector<Eigen::Vector3d> meshNormals;        ///< Mesh: the distinct face planes' outward unit normals, world
    std::vector<double> meshOffsets;                 ///< Mesh: the region is meshNormals[k] · p ≤ meshOffsets[k], m
    /// Mesh: true when the mesh is not convex or has more than 32 face planes: the region is then the columns along
    /// up between its floor triangles and its top triangles (meshNormals and meshOffsets are empty).
    bool meshColumns = false;
    /// Mesh with columns: for each triangle, the triangle across each of its edges (edge k runs from corner k to k + 1).
    std::vector<std::array<int, 3>> meshNeighbours;

    /// Set the region from `info` (kind, corners, footprint or mesh), checking it; the frame gives up for a mesh's
    /// top and bottom faces and places a footprint in the world (bounding box).
    /// @throws std::invalid_argument starting with `who` and naming the field and the problem (a degenerate or
    ///         self-intersecting footprint, bottom >= top, an open or inward mesh, a non-convex mesh that overhangs)
    void setRegion(const btWaterBodyInfo& info, const btWaterFrame& frame, const std::string& who);
    /// Distance from `point` (world, m) to the region, m (0 inside or on it).
    double distanceTo(const btWaterFrame& frame, const Eigen::Vector3d& point) const;
    /// True when `point` (world, m) is within the region's sides and not below its bottom (above its top is
    /// accepted: the water's surface may rise above it), with a tolerance `slack`, m.
    bool inColumn(const btWaterFrame& frame, const Eigen::Vector3d& point, double slack) const;
    /// True when `point` (world, m) is within the region's sides (every face but its top and bottom), with a tolerance
    /// `slack`, m.
    bool withinSides(const btWaterFrame& frame, const Eigen::Vector3d& point, double slack) const;
    /// True when the sphere (`centre`, world, m; `radius`, m) is within the region's sides (as withinSides).
    bool sphereWithinSides(const btWaterFrame& frame, const Eigen::Vector3d& centre, double radius) const;
    /// Append the region's convex pieces but their tops and bottoms, as half-spaces of the water frame, each with the
    /// body's water and density (a box, a convex mesh: one piece; a footprint: one per triangle; a mesh taken as
    /// columns: one vertical prism per upward-facing triangle). Allocates only when `out` grows.
    void appendWaterRegions(const btWaterFrame& frame, std::vector<buoyancy::WaterRegion>& out) const;
    /// True when the regions' interiors overlap (regions sharing only a face, an edge or a corner do not): an exact
    /// separating-axis test between their convex pieces, within a tolerance of 1e-9 of their size.
    bool overlaps(const btWaterBody& other, const btWaterFrame& frame) const;
    /// The region's extent in the water frame's x and z, m (a grid covering its footprint).
    void footprintBounds(const btWaterFrame& frame, double& x0, double& x1, double& z0, double& z1) const;
    /// The region in words, e.g. "[0, -5, 0] to [10, 1, 10]" (a box), "polygon of 6 corners, bottom -3, top 1",
    /// "mesh of 12 triangles".
    std::string regionText() const;
};
