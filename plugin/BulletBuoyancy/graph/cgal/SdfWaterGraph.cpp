#include <BulletBuoyancy/graph/cgal/SdfWaterGraph.h>

#include <BulletBuoyancy/graph/AutoWaterGraph.h>
#include <BulletBuoyancy/integrals/MassProperties.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/mesh_segmentation.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace buoyancy {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using CgalMesh = CGAL::Surface_mesh<Point>;
using Face = CgalMesh::Face_index;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<CgalMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

/// Our welded mesh as a CGAL Surface_mesh; refuses what CGAL cannot hold (non-manifold, open, degenerate).
CgalMesh toSurfaceMesh(const TriangleMesh& mesh) {
    CgalMesh out;
    std::vector<CgalMesh::Vertex_index> vi;
    vi.reserve(mesh.vertices.size());
    for (const Eigen::Vector3d& v : mesh.vertices) {
        if (!v.allFinite()) throw std::invalid_argument("mesh: a vertex is not finite");
        vi.push_back(out.add_vertex(Point(v.x(), v.y(), v.z())));
    }
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        for (int k = 0; k < 3; ++k)
            if (tri[k] < 0 || std::size_t(tri[k]) >= vi.size())
                throw std::invalid_argument("mesh: triangle " + std::to_string(t) + " has a vertex index out of range");
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
            throw std::invalid_argument("mesh: triangle " + std::to_string(t) + " repeats a vertex");
        const Face f = out.add_face(vi[std::size_t(tri[0])], vi[std::size_t(tri[1])], vi[std::size_t(tri[2])]);
        if (f == CgalMesh::null_face())
            throw std::invalid_argument("mesh: triangle " + std::to_string(t) +
                                        " makes the surface non-manifold or inconsistently oriented "
                                        "(the SDF water graph needs a closed 2-manifold)");
    }
    if (!CGAL::is_closed(out))
        throw std::invalid_argument("mesh: not closed (the SDF water graph needs a closed 2-manifold)");
    return out;
}
}  // namespace

void SdfWaterGraphSettings::validate() const {
    if (nodes < 1 || nodes > 64) throw std::invalid_argument("sdf.nodes: must be in [1, 64]");
    if (!std::isfinite(smoothing) || smoothing < 0 || smoothing > 1)
        throw std::invalid_argument("sdf.smoothing: must be in [0, 1]");
    if (!std::isfinite(coneAngle) || !(coneAngle > 0) || !(coneAngle < 3.14159265358979323846))
        throw std::invalid_argument("sdf.cone_angle: must be in (0, pi) rad");
    if (rays < 1 || rays > 1000) throw std::invalid_argument("sdf.rays: must be in [1, 1000]");
    if (resolution < 4 || resolution > 256) throw std::invalid_argument("sdf.resolution: must be in [4, 256]");
    if (!std::isfinite(fill) || !(fill > 0) || fill > 1) throw std::invalid_argument("sdf.fill: must be in (0, 1]");
}

WaterGraph sdfWaterGraph(const TriangleMesh& mesh, const SdfWaterGraphSettings& settings) {
    settings.validate();
    if (mesh.triangleCount() == 0) throw std::invalid_argument("mesh: no triangles");
    CgalMesh sm = toSurfaceMesh(mesh);

    // Paper section 4 / [YL18]: SDF per face, then k-cluster GMM + graph cut into connected segments.
    auto sdf = sm.add_property_map<Face, double>("f:sdf", 0.0).first;
    auto segment = sm.add_property_map<Face, std::size_t>("f:segment", 0).first;
    std::size_t segments = 0;
    try {
        CGAL::sdf_values(sm, sdf, settings.coneAngle, std::size_t(settings.rays), true);
        segments = CGAL::segmentation_from_sdf_values(sm, sdf, segment, std::size_t(settings.nodes), settings.smoothing);
    } catch (const std::exception& e) {  // CGAL's precondition/assertion failures are std::logic_error
        throw std::invalid_argument(std::string("mesh: CGAL's SDF segmentation failed: ") + e.what());
    }
    if (segments == 0) throw std::invalid_argument("mesh: the SDF segmentation found no segment");

    const InteriorVoxels vox = voxeliseInterior(mesh, settings.resolution);
    Tree tree(faces(sm).first, faces(sm).second, sm);
    tree.accelerate_distance_queries();

    // Each interior voxel joins the segment of its nearest surface face.
    std::vector<int> cellSegment(vox.inside.size(), -1);
    std::vector<Eigen::Vector3d> sum(segments, Eigen::Vector3d::Zero());
    std::vector<std::size_t> count(segments, 0);
    std::size_t total = 0;
    for (int k = 0; k < vox.nz; ++k)
        for (int j = 0; j < vox.ny; ++j)
            for (int i = 0; i < vox.nx; ++i) {
                const std::size_t c = vox.index(i, j, k);
                if (!vox.inside[c]) continue;
                const Eigen::Vector3d p = vox.centre(i, j, k);
                const Face f = tree.closest_point_and_primitive(Point(p.x(), p.y(), p.z())).second;
                const std::size_t s = std::min<std::size_t>(segment[f], segments - 1);
                cellSegment[c] = int(s);
                sum[s] += p;
                ++count[s];
                ++total;
            }
    if (total == 0)
        throw std::invalid_argument("mesh: no interior voxel at resolution " + std::to_string(settings.resolution) +
                                    " (is it closed? try a higher sdf.resolution)");

    // Nodes: one per segment owning voxels, capacity = its voxel share of fill × the enclosed volume.
    WaterGraph g;
    g.seed = settings.seed;
    const double volume = std::abs(polyhedronMassProperties(mesh, 1.0).volume);
    const double perVoxel = settings.fill * volume / double(total);
    std::vector<int> nodeOf(segments, -1);
    for (std::size_t s = 0; s < segments; ++s) {
        if (count[s] == 0) continue;
        nodeOf[s] = int(g.nodes.size());
        WaterNode n;
        n.name = "sdf" + std::to_string(g.nodes.size());
        n.position = sum[s] / double(count[s]);
        n.capacity = perVoxel * double(count[s]);
        g.nodes.push_back(n);
    }

    // Edges between segments with face-adjacent voxels (the rules of autoWaterGraph).
    std::map<std::pair<int, int>, int> shared;
    auto nodeAt = [&](int i, int j, int k) {
        const int s = cellSegment[vox.index(i, j, k)];
        return s < 0 ? -1 : nodeOf[std::size_t(s)];
    };
    for (int k = 0; k < vox.nz; ++k)
        for (int j = 0; j < vox.ny; ++j)
            for (int i = 0; i < vox.nx; ++i) {
                const int a = nodeAt(i, j, k);
                if (a < 0) continue;
                const int nb[3] = {i + 1 < vox.nx ? nodeAt(i + 1, j, k) : -1, j + 1 < vox.ny ? nodeAt(i, j + 1, k) : -1,
                                   k + 1 < vox.nz ? nodeAt(i, j, k + 1) : -1};
                for (int b : nb)
                    if (b >= 0 && b != a) ++shared[{std::min(a, b), std::max(a, b)}];
            }
    constexpr double kPi = 3.14159265358979323846;
    for (const auto& [pair, facesShared] : shared) {
        WaterEdge e;
        e.from = pair.first;
        e.to = pair.second;
        e.radius = std::sqrt(facesShared * vox.h * vox.h / kPi);
        e.length = std::max((g.nodes[std::size_t(e.from)].position - g.nodes[std::size_t(e.to)].position).norm(), vox.h);
        g.edges.push_back(e);
    }
    g.validate();
    return g;
}

}  // namespace buoyancy
