#include <BulletBuoyancy/graph/AutoWaterGraph.h>

#include <BulletBuoyancy/integrals/MassProperties.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace buoyancy {

void AutoWaterGraphSettings::validate() const {
    if (nodes < 1 || nodes > 256) throw std::invalid_argument("auto.nodes: must be in [1, 256]");
    if (resolution < 4 || resolution > 256) throw std::invalid_argument("auto.resolution: must be in [4, 256]");
    if (!std::isfinite(fill) || !(fill > 0) || fill > 1) throw std::invalid_argument("auto.fill: must be in (0, 1]");
}

InteriorVoxels voxeliseInterior(const TriangleMesh& mesh, int resolution) {
    if (resolution < 1) throw std::invalid_argument("voxeliseInterior: resolution must be >= 1");
    if (mesh.triangleCount() == 0) throw std::invalid_argument("mesh: no triangles");
    Eigen::Vector3d lo = mesh.vertices.front(), hi = lo;
    for (const Eigen::Vector3d& v : mesh.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    const Eigen::Vector3d ext = hi - lo;
    const double h = ext.maxCoeff() / resolution;
    if (!(h > 0) || !std::isfinite(h)) throw std::invalid_argument("mesh: empty bounding box");
    int dims[3];
    for (int k = 0; k < 3; ++k) dims[k] = std::max(1, int(std::ceil(ext[k] / h - 1e-9)));
    const int nx = dims[0], ny = dims[1], nz = dims[2];
    auto index = [&](int i, int j, int k) { return (std::size_t(k) * ny + j) * nx + i; };
    std::vector<unsigned char> inside(std::size_t(nx) * ny * nz, 0);

    // Interior by ray parity: a ray along +x through each row's voxel centres (nudged off exact edges)
    // crosses the closed surface an even number of times; voxels between crossing pairs are inside.
    std::vector<double> xs;
    for (int k = 0; k < nz; ++k) {
        for (int j = 0; j < ny; ++j) {
            const double y = lo.y() + (j + 0.5) * h + 1.37e-7 * h;
            const double z = lo.z() + (k + 0.5) * h + 2.91e-7 * h;
            xs.clear();
            for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
                const Eigen::Vector3d& a = mesh.corner(t, 0);
                const Eigen::Vector3d& b = mesh.corner(t, 1);
                const Eigen::Vector3d& c = mesh.corner(t, 2);
                // Barycentric coordinates of (y, z) in the triangle's projection on the yz plane.
                const double d = (b.y() - a.y()) * (c.z() - a.z()) - (c.y() - a.y()) * (b.z() - a.z());
                if (d == 0) continue;
                const double u = ((y - a.y()) * (c.z() - a.z()) - (c.y() - a.y()) * (z - a.z())) / d;
                const double v = ((b.y() - a.y()) * (z - a.z()) - (y - a.y()) * (b.z() - a.z())) / d;
                if (u < 0 || v < 0 || u + v > 1) continue;
                xs.push_back(a.x() + u * (b.x() - a.x()) + v * (c.x() - a.x()));
            }
            std::sort(xs.begin(), xs.end());
            for (std::size_t p = 0; p + 1 < xs.size(); p += 2) {
                for (int i = 0; i < nx; ++i) {
                    const double x = lo.x() + (i + 0.5) * h;
                    if (x > xs[p] && x < xs[p + 1]) inside[index(i, j, k)] = 1;
                }
            }
        }
    }
    InteriorVoxels out;
    out.lo = lo;
    out.h = h;
    out.nx = nx;
    out.ny = ny;
    out.nz = nz;
    out.inside = std::move(inside);
    return out;
}

WaterGraph autoWaterGraph(const TriangleMesh& mesh, const AutoWaterGraphSettings& settings) {
    settings.validate();
    const InteriorVoxels vox = voxeliseInterior(mesh, settings.resolution);
    const Eigen::Vector3d lo = vox.lo;
    const double h = vox.h;
    const int nx = vox.nx, ny = vox.ny, nz = vox.nz;
    auto index = [&](int i, int j, int k) { return vox.index(i, j, k); };
    const std::vector<unsigned char>& inside = vox.inside;
    std::vector<Eigen::Vector3d> centres;
    std::vector<std::size_t> cellOf;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
                if (inside[index(i, j, k)]) {
                    centres.push_back(lo + h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5));
                    cellOf.push_back(index(i, j, k));
                }
    if (centres.empty())
        throw std::invalid_argument("mesh: no interior voxel at resolution " + std::to_string(settings.resolution) +
                                    " (is it closed? try a higher auto.resolution)");
    const int K = std::min<int>(settings.nodes, int(centres.size()));

    // k-means: farthest-point start from the voxel nearest the interior centroid (deterministic), then Lloyd.
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : centres) mean += p;
    mean /= double(centres.size());
    std::vector<Eigen::Vector3d> seeds;
    std::vector<double> dist(centres.size(), std::numeric_limits<double>::infinity());
    {
        std::size_t first = 0;
        for (std::size_t p = 1; p < centres.size(); ++p)
            if ((centres[p] - mean).squaredNorm() < (centres[first] - mean).squaredNorm()) first = p;
        seeds.push_back(centres[first]);
        while (int(seeds.size()) < K) {
            std::size_t far = 0;
            for (std::size_t p = 0; p < centres.size(); ++p) {
                dist[p] = std::min(dist[p], (centres[p] - seeds.back()).squaredNorm());
                if (dist[p] > dist[far]) far = p;
            }
            seeds.push_back(centres[far]);
        }
    }
    std::vector<int> label(centres.size(), 0);
    for (int it = 0; it < 50; ++it) {
        bool changed = false;
        for (std::size_t p = 0; p < centres.size(); ++p) {
            int best = 0;
            for (int c = 1; c < K; ++c)
                if ((centres[p] - seeds[std::size_t(c)]).squaredNorm() < (centres[p] - seeds[std::size_t(best)]).squaredNorm())
                    best = c;
            if (best != label[p] || it == 0) changed = changed || best != label[p];
            label[p] = best;
        }
        std::vector<Eigen::Vector3d> sum(std::size_t(K), Eigen::Vector3d::Zero());
        std::vector<int> count(std::size_t(K), 0);
        for (std::size_t p = 0; p < centres.size(); ++p) {
            sum[std::size_t(label[p])] += centres[p];
            ++count[std::size_t(label[p])];
        }
        for (int c = 0; c < K; ++c)
            if (count[std::size_t(c)] > 0) seeds[std::size_t(c)] = sum[std::size_t(c)] / count[std::size_t(c)];
        if (!changed && it > 0) break;
    }

    // Nodes: one per non-empty cluster, capacity = its share of fill × the enclosed volume.
    std::vector<int> count(std::size_t(K), 0);
    for (int l : label) ++count[std::size_t(l)];
    std::vector<int> nodeOf(std::size_t(K), -1);
    WaterGraph g;
    g.seed = settings.seed;
    const double volume = std::abs(polyhedronMassProperties(mesh, 1.0).volume);
    const double perVoxel = settings.fill * volume / double(centres.size());
    for (int c = 0; c < K; ++c) {
        if (count[std::size_t(c)] == 0) continue;
        nodeOf[std::size_t(c)] = int(g.nodes.size());
        WaterNode n;
        n.name = "auto" + std::to_string(g.nodes.size());
        n.position = seeds[std::size_t(c)];
        n.capacity = perVoxel * count[std::size_t(c)];
        g.nodes.push_back(n);
    }
    // Edges between clusters with face-adjacent voxels.
    std::vector<int> cellLabel(inside.size(), -1);
    for (std::size_t p = 0; p < centres.size(); ++p) cellLabel[cellOf[p]] = nodeOf[std::size_t(label[p])];
    std::map<std::pair<int, int>, int> shared;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const int a = cellLabel[index(i, j, k)];
                if (a < 0) continue;
                const int nb[3] = {i + 1 < nx ? cellLabel[index(i + 1, j, k)] : -1,
                                   j + 1 < ny ? cellLabel[index(i, j + 1, k)] : -1,
                                   k + 1 < nz ? cellLabel[index(i, j, k + 1)] : -1};
                for (int b : nb)
                    if (b >= 0 && b != a) ++shared[{std::min(a, b), std::max(a, b)}];
            }
    constexpr double kPi = 3.14159265358979323846;
    for (const auto& [pair, faces] : shared) {
        WaterEdge e;
        e.from = pair.first;
        e.to = pair.second;
        e.radius = std::sqrt(faces * h * h / kPi);
        e.length = std::max((g.nodes[std::size_t(e.from)].position - g.nodes[std::size_t(e.to)].position).norm(), h);
        g.edges.push_back(e);
    }
    g.validate();
    return g;
}

}  // namespace buoyancy
