#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>

#include <BulletBuoyancy/bullet/btBuoyancyState.h>

#include <BulletBuoyancy/bullet/btBuoyancyInvariants.h>

#include <BulletBuoyancy/bullet/btBulletConvert.h>

#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btEmptyShape.h>
#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

using buoyancy::MassProperties;

namespace {

/// Bullet's motion state speaks the centre-of-mass frame; the user's speaks the mesh frame (mesh = COM · meshInCom).
/// `meshInCom` is read at each call: it follows updateMassProperties.
class MeshFrameMotionState : public btMotionState {
public:
    MeshFrameMotionState(btMotionState* user, const btTransform* meshInCom) : m_user(user), m_meshInCom(meshInCom) {}
    void getWorldTransform(btTransform& com) const override {
        btTransform mesh;
        m_user->getWorldTransform(mesh);
        com = mesh * m_meshInCom->inverse();
    }
    void setWorldTransform(const btTransform& com) override { m_user->setWorldTransform(com * *m_meshInCom); }

private:
    btMotionState* m_user;
    const btTransform* m_meshInCom;
};

void requireRange(double v, double lo, bool strict, const std::string& field) {
    if (!std::isfinite(v) || (strict ? !(v > lo) : !(v >= lo)))
        throw std::invalid_argument(field + ": must be a finite number " + (strict ? "> " : ">= ") +
                                    std::to_string(lo) + " (got " + std::to_string(v) + ")");
}

/// A pose Bullet can use: finite, with an orthonormal basis (no NaN, scale or shear reaches a body).
void requireRigidTransform(const btTransform& t, const std::string& field) {
    const btMatrix3x3& R = t.getBasis();
    bool ok = std::isfinite(t.getOrigin().x()) && std::isfinite(t.getOrigin().y()) && std::isfinite(t.getOrigin().z());
    for (int i = 0; i < 3 && ok; ++i)
        for (int j = 0; j < 3 && ok; ++j) {
            ok = std::isfinite(R[i][j]) && std::abs(double(R[i].dot(R[j])) - (i == j ? 1.0 : 0.0)) <= 1e-3;
        }
    if (!ok) throw std::invalid_argument(field + ": must be finite with an orthonormal rotation");
}

/// Parallel-axis term M(|d|² E − d dᵀ) (Steiner).
Eigen::Matrix3d steiner(double mass, const Eigen::Vector3d& d) {
    return mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
}

}  // namespace

void btBuoyantBodySettings::validate() const {
    if (massModel != btBuoyantMassModel::Solid && massModel != btBuoyantMassModel::Shell &&
        massModel != btBuoyantMassModel::DensityMap)
        throw std::invalid_argument("massModel: not a btBuoyantMassModel value");
    if (!fixed && massModel == btBuoyantMassModel::DensityMap && !arealDensity)
        throw std::invalid_argument("arealDensity: the DensityMap mass model needs a function");
    if (!fixed) {
        requireRange(mass, 0.0, false, "mass");
        if (mass == 0.0) requireRange(density, 0.0, true, "density");
        if (massModel == btBuoyantMassModel::Shell) requireRange(shellThickness, 0.0, true, "shellThickness");
        for (std::size_t i = 0; i < ballast.size(); ++i) {
            const std::string name = "ballast[" + std::to_string(i) + "]";
            requireRange(ballast[i].mass, 0.0, true, name + ".mass");
            if (!ballast[i].position.allFinite()) throw std::invalid_argument(name + ".position: must be finite");
        }
    }
    requireRange(collisionMargin, 0.0, false, "collisionMargin");
    requireRange(friction, 0.0, false, "friction");
    requireRange(restitution, 0.0, false, "restitution");
    requireRange(linearSleepingThreshold, 0.0, false, "linearSleepingThreshold");
    requireRange(angularSleepingThreshold, 0.0, false, "angularSleepingThreshold");
}

MassProperties btBuoyantBodyMassProperties(const btBuoyancyShape& shape, const btBuoyantBodySettings& settings) {
    settings.validate();
    MassProperties mapped;
    if (settings.massModel == btBuoyantMassModel::DensityMap) {
        // σ at every surface sample of the shape (the baked samples, or the per-face samples of exact-mesh).
        const buoyancy::SurfaceSamples& smp = shape.getDragSamples();
        std::vector<double> sigma(smp.size());
        for (std::size_t i = 0; i < smp.size(); ++i) {
            sigma[i] = settings.arealDensity(Eigen::Vector3d(smp.px[i], smp.py[i], smp.pz[i]));
            if (!std::isfinite(sigma[i]) || sigma[i] < 0.0)
                throw std::invalid_argument("arealDensity: must be finite and >= 0 (got " + std::to_string(sigma[i]) +
                                            " at a surface point)");
        }
        mapped = buoyancy::shellMassProperties(smp, sigma);
        if (settings.mass > 0.0) {  // rescale the map to the given mass
            const double k = settings.mass / mapped.mass;
            mapped.mass *= k;
            mapped.inertia *= k;
        }
    }
    const MassProperties& unit = settings.massModel == btBuoyantMassModel::Solid   ? shape.getUnitSolid()
                                 : settings.massModel == btBuoyantMassModel::Shell ? shape.getUnitShell()
                                                                                   : mapped;
    if (!(unit.mass > 0.0)) throw std::invalid_argument("mesh: zero mass for this mass model");
    // Unit data is at density 1 (and thickness 1 m for the shell): everything scales linearly.
    double scale = settings.massModel == btBuoyantMassModel::Solid   ? settings.density
                   : settings.massModel == btBuoyantMassModel::Shell ? settings.density * settings.shellThickness
                                                                     : 1.0;  // the map carries its own density
    if (settings.mass > 0.0 && settings.massModel != btBuoyantMassModel::DensityMap) scale = settings.mass / unit.mass;
    MassProperties mp = unit;
    mp.mass = unit.mass * scale;
    mp.inertia = unit.inertia * scale;
    if (settings.ballast.empty()) return mp;

    // Compose with point masses about the common centre (parallel-axis theorem).
    double total = mp.mass;
    Eigen::Vector3d moment = mp.mass * mp.centre;
    for (const btBuoyantBallast& b : settings.ballast) {
        total += b.mass;
        moment += b.mass * b.position;
    }
    const Eigen::Vector3d c = moment / total;
    Eigen::Matrix3d inertia = mp.inertia + steiner(mp.mass, mp.centre - c);
    for (const btBuoyantBallast& b : settings.ballast) inertia += steiner(b.mass, b.position - c);
    mp.mass = total;
    mp.centre = c;
    mp.inertia = inertia;
    return mp;
}

btTransform btBuoyantMeshWorldTransform(const btRigidBody& body, const btTransform& meshInCom) {
    return body.getWorldTransform() * meshInCom;
}

void btBuoyantBody::applyMassProperties(const MassProperties& mp, btTransform& outMeshInCom,
                                        btVector3& outMoments) const {
    if (!(mp.mass > 0.0) || !std::isfinite(mp.mass) || !mp.centre.allFinite() || !mp.inertia.allFinite())
        throw std::invalid_argument("mass properties: mass must be > 0 and everything finite");
    const buoyancy::PrincipalFrame pf = buoyancy::principalFrame(mp.inertia);
    Eigen::Vector3d moments = pf.moments;
    // A body of point masses on a line has a zero moment: keep Bullet's inverse inertia finite.
    const double floor = std::max(1e-9 * moments.maxCoeff(), 1e-12 * mp.mass);
    for (int k = 0; k < 3; ++k) moments[k] = std::max(moments[k], floor);
    // Principal frame (R, c) maps COM-frame coordinates to mesh coordinates; its inverse places the mesh
    // in the COM frame (design.md 3).
    Eigen::Isometry3d principal = Eigen::Isometry3d::Identity();
    principal.linear() = pf.rotation;
    principal.translation() = mp.centre;
    outMeshInCom = buoyancy::toBullet(principal.inverse());
    outMoments = btVector3(btScalar(moments.x()), btScalar(moments.y()), btScalar(moments.z()));
    const std::string range = btBuoyancyCheckInertiaRange(outMoments, "mass properties");
    if (!range.empty()) throw std::invalid_argument(range);
}

btBuoyantBody::btBuoyantBody(std::shared_ptr<const btBuoyancyShape> shape, const btBuoyantBodySettings& settings,
                             const btTransform& meshWorldTransform)
    : m_shape(std::move(shape)), m_settings(settings) {
    if (!m_shape) throw std::invalid_argument("shape: null");
    m_settings.validate();
    requireRigidTransform(meshWorldTransform, "meshWorldTransform");
    const buoyancy::TriangleMesh& mesh = m_shape->getMesh();

    btVector3 moments(0, 0, 0);
    m_meshInCom.setIdentity();
    if (!m_settings.fixed) {
        m_massProperties = btBuoyantBodyMassProperties(*m_shape, m_settings);
        applyMassProperties(m_massProperties, m_meshInCom, moments);
    }

    // Collision shape in mesh coordinates.
    const btScalar margin = btScalar(m_settings.collisionMargin);
    switch (m_settings.collision) {
        case btBuoyantCollision::ConvexHull: {
            auto hull = std::make_unique<btConvexHullShape>();
            for (const Eigen::Vector3d& v : mesh.vertices) hull->addPoint(buoyancy::toBullet(v), false);
            hull->recalcLocalAabb();
            hull->optimizeConvexHull();
            hull->setMargin(margin);
            m_childShape = std::move(hull);
            break;
        }
        case btBuoyantCollision::TriangleMesh: {
            m_vertices.reserve(3 * mesh.vertices.size());
            for (const Eigen::Vector3d& v : mesh.vertices)
                for (int k = 0; k < 3; ++k) m_vertices.push_back(btScalar(v[k]));
            m_indices.reserve(3 * mesh.triangleCount());
            for (const Eigen::Vector3i& t : mesh.triangles)
                for (int k = 0; k < 3; ++k) m_indices.push_back(t[k]);
            m_meshInterface = std::make_unique<btTriangleIndexVertexArray>(
                int(mesh.triangleCount()), m_indices.data(), int(3 * sizeof(int)), int(mesh.vertices.size()),
                m_vertices.data(), int(3 * sizeof(btScalar)));
            if (m_settings.fixed) {
                m_childShape = std::make_unique<btBvhTriangleMeshShape>(m_meshInterface.get(), true);
            } else {
                auto gimpact = std::make_unique<btGImpactMeshShape>(m_meshInterface.get());
                gimpact->setMargin(margin);
                gimpact->updateBound();
                m_childShape = std::move(gimpact);
            }
            break;
        }
        case btBuoyantCollision::None: m_childShape = std::make_unique<btEmptyShape>(); break;
    }

    btCollisionShape* bodyShape = m_childShape.get();
    if (!m_settings.fixed && m_settings.collision != btBuoyantCollision::None) {
        m_compound = std::make_unique<btCompoundShape>(false, 1);
        m_compound->addChildShape(m_meshInCom, m_childShape.get());
        bodyShape = m_compound.get();
    }

    const btScalar bodyMass = m_settings.fixed ? btScalar(0) : btScalar(m_massProperties.mass);
    if (m_settings.motionState) {
        m_settings.motionState->setWorldTransform(meshWorldTransform);
        m_motionState = std::make_unique<MeshFrameMotionState>(m_settings.motionState, &m_meshInCom);
    }
    btRigidBody::btRigidBodyConstructionInfo info(bodyMass, m_motionState.get(), bodyShape, moments);
    info.m_startWorldTransform = meshWorldTransform * m_meshInCom.inverse();
    info.m_friction = btScalar(m_settings.friction);
    info.m_restitution = btScalar(m_settings.restitution);
    info.m_linearSleepingThreshold = btScalar(m_settings.linearSleepingThreshold);
    info.m_angularSleepingThreshold = btScalar(m_settings.angularSleepingThreshold);
    m_body = std::make_unique<btRigidBody>(info);
    if (m_settings.collision == btBuoyantCollision::None)
        m_body->setCollisionFlags(m_body->getCollisionFlags() | btCollisionObject::CF_NO_CONTACT_RESPONSE);
}

btBuoyantBody::~btBuoyantBody() = default;

btTransform btBuoyantBody::getMeshWorldTransform() const { return btBuoyantMeshWorldTransform(*m_body, m_meshInCom); }

void btBuoyantBody::updateMassProperties(double mass, const Eigen::Vector3d& centre, const Eigen::Matrix3d& inertia) {
    if (m_settings.fixed) throw std::invalid_argument("updateMassProperties: the body is fixed");
    MassProperties mp = m_massProperties;
    mp.mass = mass;
    mp.centre = centre;
    mp.inertia = 0.5 * (inertia + inertia.transpose());
    if (mp.inertia.allFinite()) {  // non-finite input is refused by applyMassProperties
        // A negative principal moment is not a rigid body: refuse it rather than clamp it.
        const Eigen::Vector3d moments = buoyancy::principalFrame(mp.inertia).moments;
        if (moments.minCoeff() < -1e-9 * moments.cwiseAbs().maxCoeff()) {
            std::ostringstream os;
            os << "inertia: not positive semi-definite (smallest principal moment " << moments.minCoeff() << ")";
            throw std::invalid_argument(os.str());
        }
    }
    btTransform meshInCom;
    btVector3 moments;
    applyMassProperties(mp, meshInCom, moments);  // throws before anything changes

    const btTransform meshWorld = getMeshWorldTransform();
    const btTransform newCom = meshWorld * meshInCom.inverse();
    const btVector3 dc = newCom.getOrigin() - m_body->getCenterOfMassPosition();
    // Velocity of the material point that becomes the COM: the rigid velocity field is unchanged.
    const btVector3 v = m_body->getLinearVelocity() + m_body->getAngularVelocity().cross(dc);

    m_body->setCenterOfMassTransform(newCom);
    m_body->setMassProps(btScalar(mass), moments);
    m_body->updateInertiaTensor();  // setMassProps does not update the world inverse inertia
    m_body->setLinearVelocity(v);
    m_body->setInterpolationLinearVelocity(v);
    if (m_compound) m_compound->updateChildTransform(0, meshInCom);
    m_meshInCom = meshInCom;
    m_massProperties = mp;
}

// ---- save and restore (btBuoyancyState.h) ----
std::vector<unsigned char> btBuoyantBody::saveState() const {
    btBuoyancyStateWriter out(btBuoyancyStateKind::BuoyantBody);
    out.boolean(m_settings.fixed);
    out.f64(m_massProperties.mass);
    out.f64(m_massProperties.volume);
    out.f64(m_massProperties.area);
    out.f64s(m_massProperties.centre.data(), 3);
    out.f64s(m_massProperties.inertia.data(), 9);
    return out.bytes();
}

void btBuoyantBody::restoreState(const unsigned char* data, std::size_t size) {
    btBuoyancyStateReader in(data, size, btBuoyancyStateKind::BuoyantBody, "btBuoyantBody::restoreState");
    const bool fixed = in.boolean("fixed");
    if (fixed != m_settings.fixed)
        in.fail(std::string("the blob is a ") + (fixed ? "fixed" : "dynamic") + " body's, this body is " +
                (m_settings.fixed ? "fixed" : "dynamic"));
    MassProperties mp;
    mp.mass = in.f64("mass");
    mp.volume = in.f64("volume");
    mp.area = in.f64("area");
    in.f64s(mp.centre.data(), 3, "centre");
    in.f64s(mp.inertia.data(), 9, "inertia");
    in.finish();
    if (m_settings.fixed) {
        m_massProperties = mp;
        return;
    }
    btTransform meshInCom;
    btVector3 moments;
    try {
        // The same function of the same numbers as when they were applied: the same frame and moments, bit for bit.
        applyMassProperties(mp, meshInCom, moments);
    } catch (const std::invalid_argument& e) {
        in.fail(e.what());
    }
    m_body->setMassProps(btScalar(mp.mass), moments);
    m_body->updateInertiaTensor();
    if (m_compound) m_compound->updateChildTransform(0, meshInCom);
    m_meshInCom = meshInCom;
    m_massProperties = mp;
}
