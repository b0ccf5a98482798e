#include <BulletBuoyancy/bullet/btConvexHullMesh.h>

#include <LinearMath/btConvexHullComputer.h>

#include <Eigen/Geometry>

#include <stdexcept>
#include <utility>

buoyancy::TriangleMesh btConvexHullMesh(const std::vector<Eigen::Vector3d>& points, const std::string& what) {
    if (points.size() < 4)
        throw std::invalid_argument(what + ": " + std::to_string(points.size()) +
                                    " points enclose no volume (at least 4 needed)");
    for (const Eigen::Vector3d& p : points)
        if (!p.allFinite()) throw std::invalid_argument(what + ": a point is not finite (NaN or Inf)");
    // Packed x, y, z doubles: Eigen::Vector3d is three contiguous doubles.
    btConvexHullComputer computer;
    computer.compute(points.front().data(), int(sizeof(Eigen::Vector3d)), int(points.size()), btScalar(0), btScalar(0));
    buoyancy::TriangleMesh m;
    m.vertices.reserve(std::size_t(computer.vertices.size()));
    for (int i = 0; i < computer.vertices.size(); ++i) {
        const int original = i < computer.original_vertex_index.size() ? computer.original_vertex_index[i] : -1;
        if (original >= 0 && std::size_t(original) < points.size()) {
            m.vertices.push_back(points[std::size_t(original)]);
        } else {
            const btVector3& v = computer.vertices[i];
            m.vertices.emplace_back(double(v.x()), double(v.y()), double(v.z()));
        }
    }
    for (int f = 0; f < computer.faces.size(); ++f) {
        const btConvexHullComputer::Edge* start = &computer.edges[computer.faces[f]];
        std::vector<int> polygon;
        const btConvexHullComputer::Edge* e = start;
        do {
            polygon.push_back(e->getSourceVertex());
            e = e->getNextEdgeOfFace();
        } while (e != start && polygon.size() <= std::size_t(computer.vertices.size()));
        for (std::size_t k = 1; k + 1 < polygon.size(); ++k) m.triangles.emplace_back(polygon[0], polygon[k], polygon[k + 1]);
    }
    // Outward: the signed volume Σ a·(b×c)/6 about the vertices' mean must be positive.
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& v : m.vertices) centre += v;
    if (!m.vertices.empty()) centre /= double(m.vertices.size());
    double six = 0;
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
        six += (m.corner(t, 0) - centre).dot((m.corner(t, 1) - centre).cross(m.corner(t, 2) - centre));
    if (m.triangles.size() < 4 || six == 0.0)
        throw std::invalid_argument(what + ": the points are flat or collinear: their hull encloses no volume");
    if (six < 0)
        for (Eigen::Vector3i& t : m.triangles) std::swap(t[1], t[2]);
    return m;
}
