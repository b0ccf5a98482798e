#include <BulletBuoyancy/bullet/btBuoyancyDeformable.h>

#include <BulletBuoyancy/atlas/UvLayout.h>
#include <BulletBuoyancy/bullet/btBuoyancySettings.h>
#include <BulletBuoyancy/bullet/btBuoyancyShape.h>

#include <algorithm>
#include <stdexcept>
#include <string>

std::shared_ptr<btBuoyancyDeformable> btBuoyancyDeformable::create(const btBuoyancyShape& shape,
                                                                   const btBuoyancySettings& settings) {
    const buoyancy::IntegrationMethod& method = shape.getIntegrationMethod();
    if (!method.sampled)
        throw std::invalid_argument(std::string("deformable: the shape uses method '") + method.name +
                                    "'; deformable bodies need a sampled method (exact-coverage or texel-centre)");
    const int n = shape.getTextureSize();
    const buoyancy::TriangleMesh& mesh = shape.getMesh();
    const buoyancy::UvLayout layout = buoyancy::chooseUvLayout(mesh, n, settings.preferModelUvs);
    std::shared_ptr<btBuoyancyDeformable> d(new btBuoyancyDeformable());
    d->m_map = buoyancy::buildRebakeMap(mesh, layout.corner_uvs, n, method.bake);
    if (d->m_map.size() != shape.getSamples().size() || d->m_map.texel != shape.getSamples().texel)
        throw std::invalid_argument("deformable: the UV layout rebuilt from settings gives " +
                                    std::to_string(d->m_map.size()) + " samples, the shape has " +
                                    std::to_string(shape.getSamples().size()) +
                                    " (pass the settings the shape was created with)");
    d->m_vertices = mesh.vertices;
    buoyancy::rebakeSamples(d->m_map, d->m_vertices, d->m_samples);
    d->updateBounds();
    return d;
}

void btBuoyancyDeformable::setVertices(const std::vector<Eigen::Vector3d>& vertices) {
    // The checks of rebakeSamples, now, so that a bad call changes nothing; the re-bake itself waits for getSamples.
    buoyancy::checkRebakeVertices(m_map, vertices);
    m_vertices = vertices;
    updateBounds();
    ++m_version;
}

const buoyancy::SurfaceSamples& btBuoyancyDeformable::getSamples() const {
    if (m_bakedVersion.load(std::memory_order_acquire) != m_version) {
        std::lock_guard<std::mutex> lock(m_bakeMutex);
        if (m_bakedVersion.load(std::memory_order_relaxed) != m_version) {
            buoyancy::rebakeSamples(m_map, m_vertices, m_samples);
            m_bakedVersion.store(m_version, std::memory_order_release);
        }
    }
    return m_samples;
}

void btBuoyancyDeformable::updateBounds() {
    if (m_vertices.empty()) return;
    Eigen::Vector3d lo = m_vertices.front(), hi = lo;
    for (const Eigen::Vector3d& v : m_vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    m_boundsCentre = 0.5 * (lo + hi);
    m_boundsRadius = 0;
    for (const Eigen::Vector3d& v : m_vertices) m_boundsRadius = std::max(m_boundsRadius, (v - m_boundsCentre).norm());
}

void btBuoyancyDeformable::setVertices(const std::vector<btVector3>& vertices) {
    std::vector<Eigen::Vector3d> v(vertices.size());
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = Eigen::Vector3d(double(vertices[i].x()), double(vertices[i].y()),
                                                                       double(vertices[i].z()));
    setVertices(v);
}

double btBuoyancyDeformable::getVolume() const {
    const buoyancy::SurfaceSamples& samples = getSamples();
    double v = 0;
    for (std::size_t i = 0; i < samples.size(); ++i) v += samples.ay[i] * samples.py[i];
    return v;
}
