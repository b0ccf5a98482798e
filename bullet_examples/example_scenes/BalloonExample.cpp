#include "example_scenes/BalloonExample.h"

#include <algorithm>
#include <cmath>

namespace buoyancy::examples {

BalloonExample::BalloonExample(ExampleOptions& options) : SceneFileExample(options, "balloon_air.json") {}

double BalloonExample::inflation(double t) {
    const double s = std::clamp(t / 3.0, 0.0, 1.0);
    return 0.8 + 0.2 * s * s * (3 - 2 * s);  // smoothstep from 0.8 to 1
}

void BalloonExample::initPhysics() {
    SceneFileExample::initPhysics();
    m_skin.reset();
    if (!m_world || m_world->actions.empty() || !m_world->actions[0]) return;
    btBuoyancyAction& action = *m_world->actions[0];
    m_skin = btBuoyancyDeformable::create(*action.getShape(), m_scene.bodies[0].buoyancy);
    action.setDeformable(m_skin);
    m_mesh = action.getShape()->getMesh();
    deform();
}

void BalloonExample::deform() {
    if (!m_skin || !m_world) return;
    // Inflate about the rest centre, and stretch along the vertical velocity (a rising balloon elongates a
    // little; volume kept by the 1/sqrt(s) squeeze across).
    const TriangleMesh& rest = m_world->actions[0]->getShape()->getMesh();
    const double k = inflation(m_world->time());
    const double vy = double(m_world->bodies[0]->getRigidBody()->getLinearVelocity().y());
    const double stretch = 1.0 + 0.04 * std::tanh(vy / 2.0);
    const double across = 1.0 / std::sqrt(stretch);
    std::vector<Eigen::Vector3d> v(rest.vertices.size());
    for (std::size_t i = 0; i < v.size(); ++i) {
        const Eigen::Vector3d& p = rest.vertices[i];
        v[i] = k * Eigen::Vector3d(across * p.x(), stretch * p.y(), across * p.z());
    }
    m_skin->setVertices(v);
    m_mesh.vertices = v;
    ++m_version;
}

void BalloonExample::afterFrame() { deform(); }

void BalloonExample::renderScene() {
    if (!m_world) return;
    render::buildSceneFrame(m_scene, *m_world, m_frameOptions, m_frame);
    if (m_skin && !m_frame.bodies.empty()) {  // draw the deformed surface, not the rest mesh
        m_frame.bodies[0].mesh = &m_mesh;
        m_frame.bodies[0].meshVersion = m_version;
    }
    if (m_options.guiHelper) m_options.guiHelper->render(m_frame);
}

}  // namespace buoyancy::examples
