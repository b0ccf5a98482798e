#include <BulletBuoyancy/bullet/btBuoyancyAction.h>

#include <BulletBuoyancy/bullet/btBulletConvert.h>
#include <BulletBuoyancy/bullet/btBuoyancyDeformable.h>
#include <BulletBuoyancy/bullet/btBuoyancyInvariants.h>
#include <BulletBuoyancy/bullet/btBuoyancyState.h>
#include <BulletBuoyancy/integrals/BoxHydrostatics.h>
#include <BulletBuoyancy/integrals/CapsuleHydrostatics.h>
#include <BulletBuoyancy/integrals/SphereHydrostatics.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/integrals/DragKernel.h>
#include <BulletBuoyancy/geometry/SampleFormulas.h>
#include <BulletBuoyancy/bullet/btBuoyancyDeviceBackend.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <LinearMath/btIDebugDraw.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <utility>

using buoyancy::toBullet;
using buoyancy::toEigen;

/// Keeps a rarely taken branch out of line, so the common path's code is laid out as without it.
#if defined(__GNUC__)
#define BB_NOT_INLINED __attribute__((noinline))
#else
#define BB_NOT_INLINED
#endif

namespace {

/// Drag clusters shared by every action of one shape at one dragClusters setting (built once: clustering a
/// 16k-sample shape takes milliseconds, too slow to repeat for 1,000 bodies). Entries of dead shapes are dropped.
std::shared_ptr<const buoyancy::DragClusters> sharedDragClusters(const std::shared_ptr<const btBuoyancyShape>& shape,
                                                                 int maxClusters, int maxProbes) {
    struct Entry {
        std::weak_ptr<const btBuoyancyShape> shape;
        int maxClusters, maxProbes;
        std::shared_ptr<const buoyancy::DragClusters> clusters;
    };
    static std::mutex mutex;
    static std::vector<Entry> entries;
    std::lock_guard<std::mutex> lock(mutex);
    entries.erase(std::remove_if(entries.begin(), entries.end(), [](const Entry& e) { return e.shape.expired(); }),
                  entries.end());
    for (const Entry& e : entries)
        if (e.maxClusters == maxClusters && e.maxProbes == maxProbes && e.shape.lock() == shape) return e.clusters;
    buoyancy::DragClusters c = buoyancy::clusterDragSamples(shape->getDragSamples(), std::size_t(maxClusters));
    buoyancy::assignVelocityProbes(c, std::size_t(maxProbes));
    auto clusters = std::make_shared<const buoyancy::DragClusters>(std::move(c));
    entries.push_back(Entry{shape, maxClusters, maxProbes, clusters});
    return clusters;
}

}  // namespace

btBuoyancyAction::btBuoyancyAction(btRigidBody* body, std::shared_ptr<const btBuoyancyShape> shape,
                                   btBuoyancyWorld* world, const btBuoyancySettings& settings,
                                   const btTransform& meshInCom)
    : btBuoyancyAction(body, nullptr, std::move(shape), world, settings, meshInCom) {}

btBuoyancyAction::btBuoyancyAction(btBuoyancyBody& body, std::shared_ptr<const btBuoyancyShape> shape,
                                   btBuoyancyWorld* world, const btBuoyancySettings& settings,
                                   const btTransform& meshInCom)
    : btBuoyancyAction(nullptr, &body, std::move(shape), world, settings, meshInCom) {}

btBuoyancyAction::btBuoyancyAction(btRigidBody* rigid, btBuoyancyBody* body, std::shared_ptr<const btBuoyancyShape> shape,
                                   btBuoyancyWorld* world, const btBuoyancySettings& settings,
                                   const btTransform& meshInCom)
    : m_rigidBody(rigid), m_body(body ? body : &m_rigidBody), m_shape(std::move(shape)), m_world(world),
      m_settings(settings), m_meshInCom(meshInCom) {
    if (!rigid && !body) throw std::invalid_argument("body: null");
    if (!m_shape) throw std::invalid_argument("shape: null");
    if (!m_world) throw std::invalid_argument("world: null");
    m_settings.validate();
    if (m_body->getInvMass() > 0) {
        const std::string range = btBuoyancyCheckInertiaRange(m_body->getLocalInertia(), "body");
        if (!range.empty()) throw std::invalid_argument(range);
    }
    m_ws.resize(m_shape->getSamples().size());
    selectDragClusters();
    m_activeDensity = m_world->getFluidDensity();
    m_baseLinearSleep = double(m_body->getLinearSleepingThreshold());
    m_baseAngularSleep = double(m_body->getAngularSleepingThreshold());
    // Bodies take turns at their exact evaluations (temporal level of detail): staggered by registration order.
    m_lod = btTemporalLevelOfDetail(m_shape->getUnitSolid().volume, m_shape->getBoundsRadius());
    m_lod.setPhase(m_world->registerAction(this));
}

namespace {
std::shared_ptr<const btBuoyancyShape> shapeOfBody(const btRigidBody* body, const btBuoyancySettings& settings) {
    if (!body) throw std::invalid_argument("body: null");
    if (!body->getCollisionShape()) throw std::invalid_argument("body: has no collision shape");
    return btBuoyancyShape::fromCollisionShape(*body->getCollisionShape(), settings);
}
}  // namespace

btBuoyancyAction::btBuoyancyAction(btRigidBody* body, btBuoyancyWorld* world, const btBuoyancySettings& settings)
    : btBuoyancyAction(body, shapeOfBody(body, settings), world, settings, btTransform::getIdentity()) {}

btBuoyancyAction::btBuoyancyAction(btBuoyantBody& body, btBuoyancyWorld* world, const btBuoyancySettings& settings)
    : btBuoyancyAction(body.getRigidBody(), body.getShape(), world, settings, body.getMeshInComFrame()) {
    m_owner = &body;
}

btBuoyancyAction::~btBuoyancyAction() { m_world->unregisterAction(this); }

void btBuoyancyAction::setSettings(const btBuoyancySettings& settings) {
    settings.validate();
    if (m_marine.enabled && settings.addedMass)
        throw std::invalid_argument("addedMass: must be false while the marine hydrodynamics are enabled (their "
                                    "added-mass matrix replaces the scalar added mass)");
    const bool recluster = settings.dragClusters != m_settings.dragClusters ||
                           settings.waterVelocityProbes != m_settings.waterVelocityProbes;
    m_settings = settings;
    m_lod.restart();  // the records may have been made with other drag or method settings
    if (recluster) selectDragClusters();
}

void btBuoyancyAction::setMarineHydrodynamics(const btMarineHydrodynamics& hydrodynamics) {
    hydrodynamics.validate();
    if (hydrodynamics.enabled && m_settings.addedMass)
        throw std::invalid_argument("btMarineHydrodynamics.enabled: the settings' scalar added mass is on "
                                    "(btBuoyancySettings::addedMass); set it to false first: the added-mass matrix "
                                    "replaces it");
    m_marine = hydrodynamics;
    m_marineSubstep = 0;  // start afresh from the body's velocity
}

bool btBuoyancyAction::marineImpulse(const buoyancy::HydrostaticsResult& h, double dt, btVector3& J, btVector3& L) {
    // design.md 2.10: Fossen's model solved with the body's mass at the end of the substep, world frame.
    const btWaterFrame& frame = m_world->getWaterFrame();
    const double m = 1.0 / double(m_body->getInvMass());
    const Eigen::Matrix3d R = toEigen(m_body->getWorldTransform()).linear();
    const btVector3 invI = m_body->getInvInertiaDiagLocal();
    Eigen::Vector3d inertia;
    for (int k = 0; k < 3; ++k)  // a locked axis (inverse inertia 0) as a very large inertia
        inertia[k] = invI[k] > 0 ? 1.0 / double(invI[k]) : 1e12 * std::max(m, 1.0);
    buoyancy::MarineStepInput in;
    in.dt = dt;
    in.mass = m;
    in.inertia = R * inertia.asDiagonal() * R.transpose();
    in.rotation = R;
    const Eigen::Vector3d gdt = toEigen(m_body->getGravity()) * dt;  // the kick Bullet applies at the next substep
    in.bulletVelocity << toEigen(m_body->getLinearVelocity()), toEigen(m_body->getAngularVelocity());
    // Every coefficient scaled by the submerged fraction (btMarineHydrodynamics::scaleBySubmergedFraction).
    double phi = 1.0;
    if (m_marine.scaleBySubmergedFraction && m_settings.buoyancyEnabled) {
        const double volume = m_deformable ? m_deformable->getVolume() : m_shape->getVolume();
        const double f = volume > 0 ? h.submerged_volume / volume : 0.0;
        phi = std::isfinite(f) ? std::min(std::max(f, 0.0), 1.0) : 0.0;
    }
    // The water's velocity at the centre of mass (currents, orbital velocity).
    Eigen::Vector3d u = Eigen::Vector3d::Zero();
    if (m_marine.useWaterVelocity && m_activeWater) {
        const Eigen::Vector3d c = frame.toWaterPoint(toEigen(m_body->getCenterOfMassPosition()));
        double ux = 0, uy = 0, uz = 0;
        m_activeWater->velocities(&c.x(), &c.y(), &c.z(), 1, m_world->getTime(), &ux, &uy, &uz);
        u = frame.toWorldVector(Eigen::Vector3d(ux, uy, uz));
        if (!u.allFinite()) u.setZero();
    }
    in.current = u;
    // The step's start: the end of the previous substep when the model ran then; else the velocity Bullet integrated
    // with, less the kicks of the forces accumulated on the body (below).
    const std::uint64_t substep = m_world->getSubstep();
    const bool history = m_marineSubstep != 0 && m_marineSubstep + 1 == substep;
    if (history) {
        in.startVelocity = m_marineVelocity;
        in.previousRotation = m_marineRotation;
        in.previousCurrent = m_marineCurrent;
    } else {
        // Bullet's kicks of this substep from the forces accumulated on the body (contacts are not known): the user's
        // forces and torques, and the weight unless the action had already counted on it (a body primed before).
        Eigen::Vector3d force = toEigen(m_body->getTotalForce());
        if (!m_needsPrime) force -= m * toEigen(m_body->getGravity());
        in.startVelocity = in.bulletVelocity;
        in.startVelocity.head<3>() -= force * (dt / m);
        in.startVelocity.tail<3>() -= toEigen(m_body->getInvInertiaTensorWorld() * m_body->getTotalTorque()) * dt;
        in.previousRotation = R;
        in.previousCurrent = u;
    }
    // The matrices about the centre of mass in the body's axes; damping stays in the reference frame.
    const Eigen::Isometry3d ref = toEigen(getMeshInComFrame() * m_marine.referenceFrame);
    in.reference = buoyancy::marineFrameJacobian(ref.linear(), ref.translation());
    buoyancy::Matrix6d ma, dl;
    for (int i = 0; i < 6; ++i) {
        for (int j = 0; j < 6; ++j) {
            ma(i, j) = m_marine.addedMass[std::size_t(6 * i + j)];
            dl(i, j) = m_marine.linearDamping[std::size_t(6 * i + j)];
        }
        in.quadraticDamping[i] = phi * m_marine.quadraticDamping[std::size_t(i)];
    }
    in.addedMass = phi * (in.reference.transpose() * ma * in.reference);
    in.linearDamping = phi * dl;
    // The action's own impulses for the next substep plus the weight Bullet will add (at the total mass here).
    in.impulse << toEigen(J) + m * gdt, toEigen(L);
    const buoyancy::Vector6d nu = buoyancy::marineStep(in);
    if (!nu.allFinite()) return false;
    // Leave the body at ν less the gravity kick Bullet adds before it integrates the next substep.
    const Eigen::Vector3d dv = nu.head<3>() - gdt - in.bulletVelocity.head<3>();
    const Eigen::Vector3d dw = nu.tail<3>() - in.bulletVelocity.tail<3>();
    J = toBullet(Eigen::Vector3d(m * dv));
    L = toBullet(Eigen::Vector3d(in.inertia * dw));
    // The next substep starts from what the body gets: Bullet scales the changes by its linear and angular factors
    // (a locked axis keeps its velocity).
    const Eigen::Vector3d fl = toEigen(m_body->getLinearFactor()), fa = toEigen(m_body->getAngularFactor());
    m_marineVelocity << in.bulletVelocity.head<3>() + fl.cwiseProduct(dv) + gdt,
        in.bulletVelocity.tail<3>() + fa.cwiseProduct(dw);
    m_marineRotation = R;
    m_marineCurrent = u;
    m_marineSubstep = substep;
    return true;
}

void btBuoyancyAction::selectDragClusters() {
    m_drag = sharedDragClusters(m_shape, m_settings.dragClusters, m_settings.waterVelocityProbes);
    const std::size_t k = m_drag->size();
    for (auto* v : {&m_dh, &m_ux, &m_uy, &m_uz}) v->assign(k, 0.0);
    m_dragCache.reset();
}

namespace {
/// What one drag evaluation computes and uses up (computeDrag): the clusters' world centres, area vectors and vertical
/// half extents, the velocity probes' world points and velocities, and which clusters an earlier region's pass made
/// wet. The calling thread's scratch, grown and never shrunk (no allocation once grown): held per body, these 256
/// clusters' worth (15 KB) went out to memory and back at every drag evaluation of a large fleet (measured: 1,500
/// boats, 2 threads, 5 % of the time per body-substep).
struct DragScratch {
    std::vector<double> x, y, z, ax, ay, az, half;  ///< per cluster: centre (m), area vector (m²), half height (m)
    std::vector<double> px, py, pz, pux, puy, puz;  ///< per probe: world point (m) and water velocity (m/s)
    std::vector<std::uint8_t> assigned;             ///< per cluster: wet in an earlier region's pass (straddling)
};
DragScratch& dragScratch(std::size_t clusters, std::size_t probes) {
    thread_local DragScratch d;
    if (d.x.size() < clusters) {
        for (auto* v : {&d.x, &d.y, &d.z, &d.ax, &d.ay, &d.az, &d.half}) v->resize(clusters);
        d.assigned.resize(clusters);
    }
    if (d.px.size() < probes)
        for (auto* v : {&d.px, &d.py, &d.pz, &d.pux, &d.puy, &d.puz}) v->resize(probes);
    return d;
}
}  // namespace

buoyancy::HydrostaticsResult btBuoyancyAction::submergedClosedForm(const Eigen::Isometry3d& pose, double rho, double g,
                                                                   const Eigen::Vector3d& com) const {
    // design.md 2.5: the whole body under flat water: V_sub = V, C_B = the centre of volume, F = ρ g V ŷ
    // through C_B (Archimedes; the pressure integral of a closed surface in a linear pressure field).
    const buoyancy::MassProperties& dry = m_shape->getUnitSolid();
    buoyancy::HydrostaticsResult h;
    h.submerged_volume = dry.volume;
    h.centre_of_buoyancy = pose * dry.centre;
    h.force = Eigen::Vector3d(0, rho * g * dry.volume, 0);
    h.torque = (h.centre_of_buoyancy - com).cross(h.force);
    h.waterline_area = 0;
    h.waterplane.valid = true;  // no waterline: every moment 0
    h.wetted_area = m_shape->getUnitShell().mass;  // shell of unit density and thickness: mass = area
    return h;
}

bool btBuoyancyAction::reachesOnlyWaterBody(std::size_t index, const Eigen::Vector3d& centre, double radius) const {
    const std::vector<btWaterBody>& bodies = m_world->getWaterBodies();
    const btWaterBody& body = bodies[index];
    const btWaterFrame& frame = m_world->getWaterFrame();
    // Inside the region's sides: neither its top (the water fills the region up to the surface, whatever is above
    // it) nor its bottom (the bed: a body resting on it, or pressed a little into it by the contact solver, has water
    // under it, as appendRegionsOf says).
    if (!body.sphereWithinSides(frame, centre, radius)) return false;
    for (std::size_t i = 0; i < bodies.size(); ++i)
        if (i != index && bodies[i].distanceTo(frame, centre) <= radius) return false;
    return true;
}

void btBuoyancyAction::appendRegionsOf(const btWaterBody& body) {
    // The region's convex pieces but their tops and bottoms, as half-spaces of the water frame (btWaterBody::
    // appendWaterRegions). Not the top (the water ends at its surface) nor the bottom: below the bed the pressure goes
    // on as if the water did (design.md 2.9). The bed itself is the collision world's business; a body resting on
    // it, or pressed a little into it, keeps water under it instead of being sucked down by the weight of the water
    // column above it (with the bottom as a wall, its bottom face had no pressure at all).
    body.appendWaterRegions(m_world->getWaterFrame(), m_regionsReached);
}

btTransform btBuoyancyAction::getMeshInComFrame() const {
    return m_owner ? m_owner->getMeshInComFrame() : m_meshInCom;
}

btBuoyancyMassResult btBuoyancyAction::setBodyMassFromShape(double density) {
    if (!std::isfinite(density) || !(density > 0))
        throw std::invalid_argument("setBodyMassFromShape: density must be finite and > 0 kg/m3 (got " +
                                    std::to_string(density) + ")");
    if (m_owner)
        throw std::invalid_argument("setBodyMassFromShape: a btBuoyantBody keeps its own mass properties "
                                    "(btBuoyantBody::updateMassProperties)");
    // The solid at unit density (mass = volume) in the mesh frame; a sphere's in closed form (its mesh is a
    // tessellation, 0.1 % short at the default tolerance).
    buoyancy::MassProperties unit = m_shape->getUnitSolid();
    if (const double R = m_shape->getSphereRadius(); R > 0) {
        constexpr double kPi = 3.14159265358979323846;
        unit.volume = unit.mass = 4.0 / 3.0 * kPi * R * R * R;
        unit.centre.setZero();
        unit.inertia = Eigen::Matrix3d::Identity() * (0.4 * unit.mass * R * R);
    } else if (const double r = m_shape->getCapsuleRadius(); r > 0) {
        // A capsule's in closed form too (design.md 2.5 "Capsules in flat water"): a cylinder of mass m_c and two
        // half balls of mass m_s together; about its axis m_c r²/2 + 2 m_s r²/5, across it
        // m_c (r²/4 + h²/3) + m_s (2r²/5 + h² + 3hr/4) (each half ball's centroid 3r/8 past its flat face).
        constexpr double kPi = 3.14159265358979323846;
        const double h = m_shape->getCapsuleHalfHeight();
        const double cylinder = kPi * r * r * 2.0 * h, balls = 4.0 / 3.0 * kPi * r * r * r;
        unit.volume = unit.mass = cylinder + balls;
        unit.centre.setZero();
        const double along = cylinder * r * r / 2.0 + balls * 0.4 * r * r;
        const double across =
            cylinder * (r * r / 4.0 + h * h / 3.0) + balls * (0.4 * r * r + h * h + 0.75 * h * r);
        unit.inertia = Eigen::Matrix3d::Identity() * across;
        unit.inertia(m_shape->getCapsuleAxis(), m_shape->getCapsuleAxis()) = along;
    }
    const Eigen::Isometry3d meshInCom = toEigen(getMeshInComFrame());
    const double mass = density * unit.volume;
    const Eigen::Vector3d c = meshInCom * unit.centre;  // centroid, body frame
    // About the centroid in body axes, then moved to the frame's origin (parallel-axis theorem): Bullet turns the body
    // about that origin.
    Eigen::Matrix3d I = meshInCom.linear() * (density * unit.inertia) * meshInCom.linear().transpose();
    I += mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    btBuoyancyMassResult r;
    r.mass = mass;
    r.localInertia = btVector3(btScalar(I(0, 0)), btScalar(I(1, 1)), btScalar(I(2, 2)));
    r.centroidOffset = toBullet(c);
    const double smallest = std::max(I.diagonal().minCoeff(), 1e-300);
    r.productOfInertiaRatio = std::max({std::abs(I(0, 1)), std::abs(I(0, 2)), std::abs(I(1, 2))}) / smallest;
    if (const std::string range = btBuoyancyCheckInertiaRange(r.localInertia, "setBodyMassFromShape"); !range.empty())
        throw std::invalid_argument(range);
    m_body->setMassProps(btScalar(mass), r.localInertia);
    m_body->activate(true);
    return r;
}

void btBuoyancyAction::computeDrag(const Eigen::Isometry3d& pose, const buoyancy::WaterPatch* patch,
                                   const Eigen::Vector3d& com, const Eigen::Vector3d& v, const Eigen::Vector3d& w,
                                   double density, double time, Eigen::Vector3d& force, Eigen::Vector3d& torque,
                                   Eigen::Vector3d& meanWaterVelocity, double& linearPower, bool reuseWater) {
    // design.md 2.6 (paper eq. 12): per wetted sample, relative velocity v_i = v + ω × (p_i − c) − u(p_i);
    // pressure drag on front-facing samples F_i = −½ ρ C_d (A_i·v̂_i)|v_i|² v̂_i = −½ ρ C_d (A_i·v_i) v_i;
    // skin friction on the tangential part −½ ρ C_f |A_i| |v_t| v_t. The samples are the drag clusters
    // (design.md 2.5, drag level of detail; settings.dragClusters = 0 keeps every fine sample).
    const buoyancy::DragClusters& c = *m_drag;
    const std::size_t n = c.size();
    DragScratch& d = dragScratch(n, m_drag->probeX.size());
    const btWaterSurface& water = *m_activeWater;
    const Eigen::Matrix3d R = pose.linear();
    const Eigen::Vector3d t = pose.translation();
    const double r10 = R(1, 0), r11 = R(1, 1), r12 = R(1, 2);
    {
        // Centres, area vectors and vertical half extents in the world (design.md 2.4's covariance ramp), several
        // clusters per instruction (integrals/DragKernel.h).
        const double Rm[9] = {R(0, 0), R(0, 1), R(0, 2), r10, r11, r12, R(2, 0), R(2, 1), R(2, 2)};
        const double tv[3] = {t.x(), t.y(), t.z()};
        buoyancy::DragClusterPose out;
        out.x = d.x.data();
        out.y = d.y.data();
        out.z = d.z.data();
        out.ax = d.ax.data();
        out.ay = d.ay.data();
        out.az = d.az.data();
        out.halfHeight = d.half.data();
        buoyancy::poseDragClusters(c, Rm, tv, out);
    }
    double flatH = 0;
    const bool flat = water.isFlat(time, flatH);
    if (m_straddling) {
        // Each cluster takes the water of the region it is in: queried per region below.
    } else if (reuseWater) {
        // Temporal level of detail: the clusters' water heights and velocities of the last exact evaluation
        // (at most hydrostaticsInterval − 1 substeps old) are kept in m_dh and m_ux/m_uy/m_uz.
    } else if (flat)
        std::fill(m_dh.begin(), m_dh.end(), flatH);
    else if (patch)
        patch->heights(d.x.data(), d.z.data(), n, m_dh.data());
    else
        water.heightsCached(d.x.data(), d.z.data(), n, time, m_dh.data(), m_dragCache);
    if (reuseWater || m_straddling) {
    } else if (flat || m_drag->probeX.size() >= n) {
        water.velocitiesCached(d.x.data(), d.y.data(), d.z.data(), n, time, m_ux.data(), m_uy.data(), m_uz.data(),
                               m_dragCache);
    } else {
        // Velocity probes (design.md 2.5): one query per probe, each cluster takes its probe's velocity.
        const std::size_t np = m_drag->probeX.size();
        for (std::size_t j = 0; j < np; ++j) {
            const double x = m_drag->probeX[j], y = m_drag->probeY[j], z = m_drag->probeZ[j];
            d.px[j] = R(0, 0) * x + R(0, 1) * y + R(0, 2) * z + t.x();
            d.py[j] = r10 * x + r11 * y + r12 * z + t.y();
            d.pz[j] = R(2, 0) * x + R(2, 1) * y + R(2, 2) * z + t.z();
        }
        water.velocitiesCached(d.px.data(), d.py.data(), d.pz.data(), np, time, d.pux.data(), d.puy.data(),
                               d.puz.data(), m_probeCache);
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint32_t j = m_drag->probeOf[i];
            m_ux[i] = d.pux[j];
            m_uy[i] = d.puy[j];
            m_uz[i] = d.puz[j];
        }
    }
    // the per-sample drag lives in geometry/SampleFormulas.h, shared with the OpenCL kernels;
    // the CPU sums it several clusters per instruction (integrals/DragKernel.h, the same formulas lane by lane).
    // A body straddling water bodies (design.md 2.9): one pass per region reached, with its water and density; each
    // cluster is wet only in the first region piece that holds its centre (dry in the others).
    const std::size_t passes = m_straddling ? m_regionsReached.size() : 1;
    if (m_straddling) std::fill(d.assigned.begin(), d.assigned.end(), std::uint8_t(0));
    double sum[BB_DRAG_TERMS] = {};
    for (std::size_t pass = 0; pass < passes; ++pass) {
        double rho = density;
        if (m_straddling) {
            const buoyancy::WaterRegion& region = m_regionsReached[pass];
            rho = region.fluidDensity;
            region.water->heights(d.x.data(), d.z.data(), n, time, m_dh.data());
            region.water->velocities(d.x.data(), d.y.data(), d.z.data(), n, time, m_ux.data(), m_uy.data(), m_uz.data());
            bool anyInside = false;
            for (std::size_t i = 0; i < n; ++i) {
                const Eigen::Vector3d p(d.x[i], d.y[i], d.z[i]);
                bool inside = !d.assigned[i];
                for (int k = 0; k < region.planeCount && inside; ++k) inside = region.normal[k].dot(p) <= region.offset[k];
                if (inside) {
                    d.assigned[i] = 1;
                    anyInside = true;
                } else {
                    m_dh[i] = d.y[i] - 2.0 * d.half[i] - 1.0;  // below the cluster's lowest point: dry in this pass
                }
            }
            if (!anyInside) continue;
        }
        buoyancy::DragMotion motion;
        motion.kd = 0.5 * rho * m_settings.dragCoefficient;
        motion.kf = 0.5 * rho * m_settings.skinFriction;
        motion.kl = rho * m_linearDamping;  // radiation (faded with depth) and viscous: linearDampingNow
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) motion.R[3 * i + j] = R(i, j);
            motion.com[i] = com[i];
            motion.v[i] = v[i];
            motion.w[i] = w[i];
        }
        buoyancy::DragClusterBatch batch;
        batch.n = n;
        batch.x = d.x.data();
        batch.y = d.y.data();
        batch.z = d.z.data();
        batch.ax = d.ax.data();
        batch.ay = d.ay.data();
        batch.az = d.az.data();
        batch.area = c.area.data();
        batch.cxx = c.cxx.data();
        batch.cxy = c.cxy.data();
        batch.cxz = c.cxz.data();
        batch.cyy = c.cyy.data();
        batch.cyz = c.cyz.data();
        batch.czz = c.czz.data();
        batch.halfHeight = d.half.data();
        batch.waterHeight = m_dh.data();
        batch.ux = m_ux.data();
        batch.uy = m_uy.data();
        batch.uz = m_uz.data();
        double part[BB_DRAG_TERMS] = {};
        buoyancy::accumulateClusterDrag(batch, motion, part);
        for (int k = 0; k < BB_DRAG_TERMS; ++k) sum[k] += part[k];
    }
    force = Eigen::Vector3d(sum[0], sum[1], sum[2]);
    torque = Eigen::Vector3d(sum[3], sum[4], sum[5]);
    const Eigen::Vector3d uSum(sum[6], sum[7], sum[8]);
    const double areaSum = sum[9];
    meanWaterVelocity = areaSum > 0 ? Eigen::Vector3d(uSum / areaSum) : Eigen::Vector3d::Zero();
    linearPower = sum[10];
}

Eigen::Vector3d btBuoyancyAction::addedMassOf(const buoyancy::HydrostaticsResult& h, double rho) const {
    if (!m_settings.addedMass) return Eigen::Vector3d::Zero();
    // design.md 2.7, "Added mass": C_a ρ V_sub across the water's up; along it the larger of that and the
    // waterplane's c_wp ρ A_wp^(3/2) (a flat floating body's heave added mass is set by its waterplane).
    const double volumeTerm = m_settings.addedMassCoefficient * rho * std::max(h.submerged_volume, 0.0);
    const double area = std::isfinite(h.waterline_area) ? std::max(h.waterline_area, 0.0) : 0.0;
    const double waterplaneTerm = m_settings.addedMassWaterplaneCoefficient * rho * area * std::sqrt(area);
    return Eigen::Vector3d(volumeTerm, std::max(volumeTerm, waterplaneTerm), volumeTerm);
}

double btBuoyancyAction::linearDampingAt(const buoyancy::HydrostaticsResult& h, double topDepth) const {
    // design.md 2.6, "Radiation damping": b = b_v + β g / ω_n · e^(−2 k d) · (1 − d / 3D)², zero from d = 3D down.
    const double viscous = m_settings.linearDamping;
    const double beta = m_settings.radiationDamping;
    if (!(beta > 0)) return viscous;
    const double radius = m_deformable ? m_deformable->getBoundsRadius() : m_shape->getBoundsRadius();
    const double size = 2.0 * radius;  // D: the bounding sphere's diameter
    const double d = std::max(topDepth, 0.0);
    if (!(d < 3.0 * size)) return viscous;  // deeper than three sizes (or a NaN depth): no waves reach the surface
    const double rho = m_world->getWaterBodies().empty() ? m_world->getFluidDensity() : m_activeDensity;
    const double g = m_world->getGravity();
    const double invMass = double(m_body->getInvMass());
    if (!(invMass > 0) || !(g > 0) || !(rho > 0)) return viscous;
    const double m = 1.0 / invMass;
    const double ma = addedMassOf(h, rho).y();  // heave
    // Heave frequency ω_n² = ρ g A_ref / (m + m_a): the waterline area, at least ½ V^(2/3) so that a body leaving or
    // entering the water (A_waterline → 0) or under it keeps a finite frequency of its own size.
    const double volume23 = std::cbrt(m_shape->getUnitSolid().volume) * std::cbrt(m_shape->getUnitSolid().volume);
    const double area = std::max(std::isfinite(h.waterline_area) ? h.waterline_area : 0.0, 0.5 * volume23);
    const double k = rho * area / (m + ma);  // ω_n² / g: the wavenumber of the waves made at ω_n, 1/m
    if (!(k > 0) || !std::isfinite(k)) return viscous;
    const double taper = 1.0 - d / (3.0 * size);
    return viscous + beta * std::sqrt(g / k) * std::exp(-2.0 * k * d) * taper * taper;
}

double btBuoyancyAction::linearDampingNow(const buoyancy::HydrostaticsResult& h, const Eigen::Isometry3d& pose) const {
    const btWaterSurface* water = m_world->getWaterBodies().empty() ? m_world->getWater() : m_activeWater;
    if (!water) return m_settings.linearDamping;
    const Eigen::Vector3d bc = pose * (m_deformable ? m_deformable->getBoundsCentre() : m_shape->getBoundsCentre());
    const double br = m_deformable ? m_deformable->getBoundsRadius() : m_shape->getBoundsRadius();
    double lo = 0, hi = 0;
    water->heightBounds(bc.x() - br, bc.z() - br, bc.x() + br, bc.z() + br, m_world->getTime(), lo, hi);
    return linearDampingAt(h, lo - (bc.y() + br));
}

// ---- deformable bodies and device backends ----
void btBuoyancyAction::setDeformable(std::shared_ptr<btBuoyancyDeformable> deformable) {
    if (deformable && deformable->getSamples().size() != m_shape->getSamples().size())
        throw std::invalid_argument("deformable: " + std::to_string(deformable->getSamples().size()) +
                                    " samples, the action's shape has " + std::to_string(m_shape->getSamples().size()));
    m_deformable = std::move(deformable);
}

const buoyancy::SurfaceSamples& btBuoyancyAction::getSamplesInUse() const {
    return m_deformable ? m_deformable->getSamples() : m_shape->getSamples();
}

void btBuoyancyAction::dragEvaluationVelocity(const buoyancy::HydrostaticsResult& h, double dt, Eigen::Vector3d& v,
                                              Eigen::Vector3d& w) const {
    // Added mass as in updateAction (design.md 2.7): (m + m_a) a = F − m g. The density of the water chosen for this
    // substep (water bodies), or the unbounded water's as it is now.
    const double rho = m_world->getWaterBodies().empty() ? m_world->getFluidDensity() : m_activeDensity;
    const double m = 1.0 / double(m_body->getInvMass());
    const Eigen::Vector3d ma = addedMassOf(h, rho);  // per water axis
    const Eigen::Vector3d meff = Eigen::Vector3d::Constant(m) + ma;
    // In the water frame, as h (btWaterFrame: a rotation of the world's vectors).
    const btWaterFrame& frame = m_world->getWaterFrame();
    const Eigen::Vector3d gravityAcc = frame.toWaterVector(toEigen(m_body->getGravity()));
    v = frame.toWaterVector(toEigen(m_body->getLinearVelocity()));
    w = frame.toWaterVector(toEigen(m_body->getAngularVelocity()));
    v += ((h.force - ma.cwiseProduct(gravityAcc)) * dt).cwiseQuotient(meff) + gravityAcc * dt;
    w += frame.toWaterVector(toEigen(m_body->getInvInertiaTensorWorld() *
                                     toBullet(frame.toWorldVector(Eigen::Vector3d(h.torque * dt)))));
}

bool btBuoyancyAction::deviceRecord(const btWaterSurface& water, double time, btBuoyancyDeviceRecord& out) const {
    // The gating of evaluate: the bodies it would compute with the sampled method.
    const btBuoyancyBody* b = m_body;
    if (!b->isInWorld() || b->getInvMass() == btScalar(0)) return false;
    if (!b->isActive() && !water.isTimeVarying()) return false;
    if (!m_shape->getIntegrationMethod().deviceBatched || !m_settings.buoyancyEnabled) return false;
    // In the water frame, as evaluate (which maps the results back).
    const btWaterFrame& frame = m_world->getWaterFrame();
    out.pose = frame.toWater(toEigen(b->getWorldTransform() * getMeshInComFrame()));
    out.com = frame.toWaterPoint(toEigen(b->getCenterOfMassPosition()));
    if (!out.pose.matrix().allFinite() || !out.com.allFinite()) return false;
    const btBuoyancyDeformable* def = m_deformable.get();
    const Eigen::Vector3d bc = out.pose * (def ? def->getBoundsCentre() : m_shape->getBoundsCentre());
    const double br = def ? def->getBoundsRadius() : m_shape->getBoundsRadius();
    double lo = 0, hi = 0;
    water.heightBounds(bc.x() - br, bc.z() - br, bc.x() + br, bc.z() + br, time, lo, hi);
    if (bc.y() - br >= hi) return false;  // dry
    double flatH = 0;
    if (!def && water.isFlat(time, flatH) && bc.y() + br <= flatH) return false;  // the closed form (design.md 2.5)
    out.samples = &getSamplesInUse();
    if (out.samples->size() == 0) return false;
    out.samplesOwner = def ? std::shared_ptr<const void>(m_deformable) : std::shared_ptr<const void>(m_shape);
    out.deformable = def;
    out.dragClusters = m_drag.get();
    out.dragCoefficient = m_settings.dragCoefficient;
    out.skinFriction = m_settings.skinFriction;
    out.dragOn = dragIsOn();
    return true;
}

void btBuoyancyAction::updateAction(btCollisionWorld* collisionWorld, btScalar deltaTimeStep) {
    const double dt = double(deltaTimeStep);
    // A zero, negative or non-finite step applies nothing and leaves the water's clock alone.
    if (!(dt > 0) || !std::isfinite(dt)) {
        m_result.applied = false;
        m_result.status = btBuoyancyStatus::Ok;
        return;
    }
    // At a new substep the world evaluates every body of its batch (btBuoyancyThreads.cpp), this one included.
    m_world->beginSubstepIfNew(m_lastSubstep, dt, collisionWorld);
    if (m_evaluatedSubstep != m_world->getSubstep()) evaluate(collisionWorld, dt);  // not in a batch: now
    applyPending();
}

void btBuoyancyWorldEvaluate(btBuoyancyAction& action, const btCollisionWorld* collisionWorld, double dt) {
    try {
        action.evaluate(collisionWorld, dt);
    } catch (...) {
        // Never let an exception out of a worker thread (evaluate catches the computations' own): nothing applied.
        action.m_evaluatedSubstep = action.m_world->getSubstep();
        action.m_pendingActivate = action.m_pendingSleep = action.m_pendingImpulse = false;
        action.m_result.applied = false;
        ++action.m_rejected;
        action.m_lod.clear();
    }
}

void btBuoyancyWorldPrefetch(const btBuoyancyAction& action, bool referenced) {
    const auto lines = [](const void* p, std::size_t bytes) {
        const char* c = static_cast<const char*>(p);
        for (std::size_t k = 0; k < bytes; k += 64) __builtin_prefetch(c + k);
    };
    if (!referenced) {
        lines(&action, sizeof(btBuoyancyAction));
        return;
    }
    // Reads the action's pointers: called once its own lines have arrived (a stage later).
    if (const btRigidBody* rigid = action.m_rigidBody.getRigidBody()) lines(rigid, sizeof(btRigidBody));
    if (action.m_owner) lines(&action.m_owner->getMeshInComFrame(), sizeof(btTransform));
}

void btBuoyancyAction::applyPending() {
    m_result.linearImpulse = m_result.angularImpulse = btVector3(0, 0, 0);
    if (m_pendingActivate) m_body->activate(false);
    if (m_pendingSleep) m_body->setSleepingThresholds(m_pendingLinearSleep, m_pendingAngularSleep);
    if (m_pendingImpulse) {
        m_body->applyCentralImpulses(m_pendingJ, m_pendingL);
        m_result.linearImpulse = m_pendingJ;
        m_result.angularImpulse = m_pendingL;
        m_result.applied = true;
        m_needsPrime = false;
        if (const btRigidBody* rigid = m_body->getRigidBody()) BT_BUOYANCY_CHECK_BODY(*rigid);
    }
    m_pendingActivate = m_pendingSleep = m_pendingImpulse = false;
    // Water events (btBuoyancyEvents.h): decided and delivered here, at the action's turn, never on a worker thread.
    btBuoyancyEventType types[btBuoyancyWaterState::kMaxEvents];
    int waterBodies[btBuoyancyWaterState::kMaxEvents];
    const int waterBody = m_world->getWaterBodies().empty() ? -1 : m_activeWaterBody;
    const int events = m_waterState.update(m_submergedFraction, waterBody, m_world->getEventSettings(), types, waterBodies);
    if (events > 0) m_world->dispatchEvents(*this, types, waterBodies, events, m_submergedFraction);
}

/// What the gate phases of evaluate learn about the body and its water in one substep (on evaluate's stack; read-only
/// once bodyReachesWater has let the body on). Everything is in the world's water frame (btWaterFrame).
struct btBuoyancyAction::SubstepContext {
    double dt = 0;                          ///< the substep, s (> 0, finite)
    /// The water the body is in: the world's unbounded water, then (chooseWater) the chosen water body's, or nullptr.
    const btWaterSurface* water = nullptr;
    bool bounded = false;                   ///< the world has water bodies (btBuoyancyWorld::addWaterBody)
    bool waves = false;                     ///< water that changes over time may reach the body (keeps it awake)
    double time = 0;                        ///< the water's time, s
    double g = 0;                           ///< the world's gravity along the water's down axis, m/s²
    const btWaterFrame* frame = nullptr;    ///< the world's water frame
    Eigen::Isometry3d pose;                 ///< the mesh's pose
    Eigen::Vector3d com;                    ///< the centre of mass (the torque reference), m
    Eigen::Vector3d bc;                     ///< the centre of the body's bounding sphere, m
    double br = 0;                          ///< its radius, m
    bool straddling = false;                ///< the body straddles water bodies (m_straddling)
    double lo = 0, hi = 0;                  ///< the water's lowest and highest heights over the footprint, m
    double rho = 0;                         ///< the density of the body's water, kg/m³
};

/// What the phases of evaluate for a body the water reaches hand each other (on evaluate's stack, water frame).
struct btBuoyancyAction::SubstepForces {
    btTemporalLevelOfDetailSubstep lodStep; ///< the substep as the temporal level of detail sees it
    bool evaluationSubstep = false;         ///< an exact evaluation substep of the temporal level of detail (recorded)
    bool predicted = false;                 ///< h and the drag come from the temporal level of detail's prediction
    btHydrostaticsSnapshot prediction;      ///< the prediction (when predicted)
    buoyancy::HydrostaticsResult h;         ///< this substep's hydrostatics (torque about the centre of mass)
    double flatH = 0;                       ///< the height of flat water, m (when flat)
    bool flat = false;                      ///< the water is flat at this time
    bool dragOn = false;                    ///< any drag, skin friction or damping is set
    const buoyancy::WaterPatch* patch = nullptr;     ///< the wave patch the hydrostatics use, or nullptr
    const buoyancy::WaterPatch* dragPatch = nullptr; ///< the wave patch the drag uses, or nullptr
    bool onDevice = false;                  ///< h came from the world's device backend
    double m = 0;                           ///< the body's mass, kg
    Eigen::Vector3d ma;                     ///< added mass per axis, kg
    Eigen::Vector3d meff;                   ///< m + m_a per axis, kg
    Eigen::Vector3d gravityAcc;             ///< the body's own gravity, m/s²
    Eigen::Vector3d waterForce;             ///< m_a Du/Dt [+ ρ V_sub Du/Dt], N
    Eigen::Vector3d replacedPressure;       ///< [F_p − ρ g V_sub ŷ], N
    bool waterForceOn = false;              ///< waterForce and replacedPressure apply
    Eigen::Vector3d v, w;                   ///< the velocities drag is evaluated at, m/s, rad/s
    Eigen::Vector3d dragF, dragT;           ///< drag force (N) and torque about the centre of mass (N·m)
    Eigen::Vector3d uMean;                  ///< the drag's mean water velocity, m/s
    double linearPower = 0;                 ///< the linear damping's part of the drag's power, W (≤ 0)
    bool dragComputed = false;              ///< linearPower is this substep's (not an extrapolated drag)
    Eigen::Vector3d linearImpulse;          ///< N·s
    Eigen::Vector3d angularImpulse;         ///< N·m·s
};

void btBuoyancyAction::evaluate(const btCollisionWorld* collisionWorld, double dt) {
    startEvaluation(collisionWorld);
    SubstepContext c;
    c.dt = dt;
    if (!readWorld(c) || !readBodyPose(c) || !chooseWater(c) || !bodyReachesWater(c)) return;
    SubstepForces f;
    predictHydrostatics(c, f);
    buildWaterPatch(c, f);
    if (!evaluateHydrostatics(c, f)) return;
    addedMassAndWaterForce(c, f);
    evaluateDrag(c, f);
    recordTemporalLevelOfDetail(c, f);
    implicitDragScale(c, f);
    computeImpulses(c, f);
    recordResult(c, f);
    decideImpulseAndSleep(c, f);
    requestPatchPrebuild(c);
}

void btBuoyancyAction::requestPatchPrebuild(const SubstepContext& c) {
    // The next substep's patch heights, queried on the world's helper thread while Bullet steps (design.md 3 "Queries
    // ahead"): asked for only when that substep builds a patch by the same rules as buildWaterPatch, and used only if
    // the patch it builds has the same lattice, time and water (else queried then, as without this).
    m_prebuild.wanted = false;
    if (!m_world->prebuildsPatches()) return;
    const btWaterSurface* water = c.water;
    const PatchUse use = patchUse(c, water, dragIsOn());
    if (!use.hydrostatics && !use.drag) return;
    const btWaterSurface* copy = m_world->surfaceForQueriesAhead(water);
    if (!copy) return;
    // An exact substep by the temporal level of detail's schedule (every substep without it); the substeps its checks
    // make exact are not known ahead.
    const bool temporalLod = m_lod.getInterval() > 1 && m_settings.buoyancyEnabled && !m_deformable &&
                             !m_world->getDeviceBackend();
    if (temporalLod && !m_lod.isEvaluationSubstep(m_world->getSubstep() + 1)) return;
    const int nodes = int(use.nodes);
    // Where the footprint will be: moved by the body's horizontal velocity over one substep (a guess: a wrong one
    // only costs the queries).
    const Eigen::Vector3d v = c.frame->toWaterVector(toEigen(m_body->getLinearVelocity()));
    const double cx = c.bc.x() + v.x() * c.dt, cz = c.bc.z() + v.z() * c.dt;
    if (!std::isfinite(cx) || !std::isfinite(cz)) return;
    try {
        m_prebuild.lattice = buoyancy::WaterPatch::lattice(cx, cz, c.br, nodes);
    } catch (const std::exception&) {
        return;
    }
    m_prebuild.water = water;
    m_prebuild.copy = copy;
    m_prebuild.revision = water->getRevision();
    m_prebuild.time = c.time + c.dt;  // the world's clock at the next substep (btBuoyancyWorld::beginSubstepIfNew)
    m_prebuild.nodes = nodes;
    m_prebuild.ready = false;
    m_prebuild.wanted = true;
}

bool btBuoyancyWorldPrebuildPatch(btBuoyancyAction& action) {
    btBuoyancyAction::PatchPrebuild& p = action.m_prebuild;
    if (!p.wanted) return false;
    p.wanted = false;
    p.ready = false;
    try {
        double flatH = 0;
        if (p.copy->isFlat(p.time, flatH)) return false;
        // The node positions: the querying thread's scratch (only the heights are the body's).
        thread_local std::vector<double> qx, qz;
        buoyancy::WaterPatch::nodePositions(p.lattice, p.nodes, qx, qz);
        p.f.resize(qx.size());
        // The body's warm start, as the query at the next substep would start from it; the copy answers as the
        // surface does, so its warm start is the surface's (the cache names its surface by address).
        p.cache = action.m_patchCache;
        if (p.cache.owner == p.water) p.cache.owner = p.copy;
        p.copy->heightsCached(qx.data(), qz.data(), qx.size(), p.time, p.f.data(), p.cache);
        if (p.cache.owner == p.copy) p.cache.owner = p.water;
        p.ready = true;
    } catch (...) {
        p.ready = false;
    }
    return p.ready;
}

void btBuoyancyAction::startEvaluation(const btCollisionWorld* collisionWorld) {
    m_evaluatedSubstep = m_world->getSubstep();
    m_pendingActivate = m_pendingSleep = m_pendingImpulse = false;
    m_result.applied = false;
    m_result.status = btBuoyancyStatus::Ok;
#ifndef NDEBUG
    // Misuse check: an action whose body is in another world (a removed body has no broadphase handle and
    // is skipped below).
    const btCollisionObject* object = m_body->getCollisionObject();
    if (collisionWorld && object && m_body->isInWorld() &&
        collisionWorld->getCollisionObjectArray().findLinearSearch(const_cast<btCollisionObject*>(object)) ==
                              collisionWorld->getCollisionObjectArray().size())
        btAssert(!"btBuoyancyAction: its body is not in the world; remove the action before the body");
#else
    (void)collisionWorld;
#endif
    m_result.applied = false;
}

bool btBuoyancyAction::readWorld(SubstepContext& c) {
    // A body removed from its world while this action stays in it: do nothing until it is back.
    if (!m_body->isInWorld() && !m_outsideWorld) return false;
    // The unbounded water, or water bodies (btBuoyancyWorld::addWaterBody): chosen below, once the pose is known.
    c.water = m_world->getWater();
    c.bounded = !m_world->getWaterBodies().empty();
    if ((!c.water && !c.bounded) || m_body->getInvMass() == btScalar(0)) return false;
    // No buoyancy without a gravity along the water's down axis (zero, or a world that is not y-up): say why,
    // forget the history (its fields belong to another gravity) and apply nothing; never a NaN or an exception.
    if (m_world->getGravityStatus() != btBuoyancyStatus::Ok) {
        m_result = btBuoyancyResult();
        m_result.status = m_world->getGravityStatus();
        m_result.time = m_world->getTime();
        m_lod.clear();
        m_hasLastCom = false;
        m_pendingSleep = true;
        m_pendingLinearSleep = btScalar(m_baseLinearSleep);
        m_pendingAngularSleep = btScalar(m_baseAngularSleep);
        return false;
    }
    // Water bodies: any wavy one may reach the body; narrowed to the waters it reaches once they are known (below).
    c.waves = c.bounded ? m_world->isAnyWaterBodyTimeVarying() : c.water->isTimeVarying();
    if (!m_body->isActive() && !c.waves) {  // calm water: a sleeping body stays asleep
        m_needsPrime = true;
        m_lod.clear();
        return false;
    }
    return true;
}

bool btBuoyancyAction::readBodyPose(SubstepContext& c) {
    c.time = m_world->getTime();
    c.g = m_world->getGravity();
    // Everything below is evaluated in the water frame (btWaterFrame: the surface is y = f(x, z, t) there); the
    // impulses and the result are mapped back to the world at the end. Identity for a +y-up world.
    c.frame = &m_world->getWaterFrame();
    const btWaterFrame& frame = *c.frame;
    if (m_frameVersion != m_world->getWaterFrameVersion()) {  // a new frame: records and caches of the old one go
        m_frameVersion = m_world->getWaterFrameVersion();
        m_lod.clear();
        m_hasLastCom = false;
        m_waterCache.reset();
        m_dragCache.reset();
        m_probeCache.reset();
        m_patchCache.reset();
        m_prebuild.ready = m_prebuild.wanted = false;
    }
    c.pose = frame.toWater(toEigen(m_body->getWorldTransform() * getMeshInComFrame()));
    c.com = frame.toWaterPoint(toEigen(m_body->getCenterOfMassPosition()));
    // A NaN/Inf pose (set by the user, or a body Bullet already lost) is refused here: nothing below may
    // throw through Bullet's stepSimulation (clippedHydrostatics threw invalid_argument).
    if (!c.pose.matrix().allFinite() || !c.com.allFinite()) {
        ++m_rejected;
        m_lod.clear();
        return false;
    }

    // The bounding sphere: a deformable body's bounds follow its vertices
    c.bc = c.pose * (m_deformable ? m_deformable->getBoundsCentre() : m_shape->getBoundsCentre());
    c.br = m_deformable ? m_deformable->getBoundsRadius() : m_shape->getBoundsRadius();
    return true;
}

// Water bodies (design.md 2.9): the regions the bounding sphere reaches; none: no buoyancy and no drag, as above
// the water. The one nearest the centre of mass gives the drag's water and density. A sphere inside one region
// (within its sides and above its bottom) takes the single-water path below with that water; a body reaching out
// of its region or into several straddles: its pressure comes from regionHydrostatics, each part of its surface
// pressed by the water of the region it is in. One unbounded water: nothing to choose.
bool btBuoyancyAction::chooseWater(SubstepContext& c) {
    if (c.bounded) {
        chooseWaterBody(c);
    } else {
        m_activeDensity = m_world->getFluidDensity();
        m_straddling = false;
    }
    m_activeWater = c.water;
    if (c.bounded && c.waves) {
        // Only the waters the body reaches keep it awake: a body asleep in a calm pool beside a wavy lake sleeps on.
        c.waves = c.water && c.water->isTimeVarying();
        if (c.straddling)
            for (const buoyancy::WaterRegion& region : m_regionsReached)
                c.waves = c.waves || region.water->isTimeVarying();
        if (!m_body->isActive() && !c.waves) {
            m_needsPrime = true;
            m_lod.clear();
            return false;
        }
    }
    c.rho = m_activeDensity;
    return true;
}

// Out of line, so the single-water path's code is laid out as before water bodies (measured with callgrind: the
// inlined version cost the single-water path 0.2 % more instructions, this one 0.13 %).
BB_NOT_INLINED void btBuoyancyAction::chooseWaterBody(SubstepContext& c) {
    const std::vector<btWaterBody>& waterBodies = m_world->getWaterBodies();
    const btWaterFrame& frame = *c.frame;
    const Eigen::Vector3d& bc = c.bc;
    const double br = c.br;
    const Eigen::Vector3d centreWorld = frame.toWorldPoint(bc);
    const int waterBody = m_world->findWaterBody(centreWorld, br, toEigen(m_body->getCenterOfMassPosition()));
    // (A deformable body's cut would need its deformed mesh: it takes the nearest region's water whole.)
    if (waterBody >= 0 && !m_deformable) c.straddling = !reachesOnlyWaterBody(std::size_t(waterBody), centreWorld, br);
    m_straddling = c.straddling;
    if (c.straddling) {
        // The water's bounds over the footprint: the widest of the regions reached.
        m_regionsReached.clear();
        for (std::size_t i = 0; i < waterBodies.size(); ++i) {
            if (!(waterBodies[i].distanceTo(frame, centreWorld) <= br)) continue;
            const bool first = m_regionsReached.empty();
            const std::size_t before = m_regionsReached.size();
            appendRegionsOf(waterBodies[i]);
            // Only the pieces the sphere may reach (a long shore has many footprint triangles): a piece one of
            // whose planes has the whole sphere outside is left out.
            std::size_t kept = before;
            for (std::size_t k = before; k < m_regionsReached.size(); ++k) {
                const buoyancy::WaterRegion& piece = m_regionsReached[k];
                bool reaches = true;
                for (int p = 0; p < piece.planeCount && reaches; ++p)
                    reaches = piece.normal[p].dot(bc) - br <= piece.offset[p];
                if (reaches) m_regionsReached[kept++] = piece;
            }
            m_regionsReached.resize(kept, buoyancy::WaterRegion());
            double l = 0, u = 0;
            waterBodies[i].surface->heightBounds(bc.x() - br, bc.z() - br, bc.x() + br, bc.z() + br, c.time, l, u);
            c.lo = first ? l : std::min(c.lo, l);
            c.hi = first ? u : std::max(c.hi, u);
        }
    }
    if (waterBody != m_activeWaterBody) {
        m_lod.clear();  // its records belong to another water
        m_waterCache.reset();
        m_dragCache.reset();
        m_probeCache.reset();
        m_patchCache.reset();
        m_prebuild.ready = m_prebuild.wanted = false;
        m_activeWaterBody = waterBody;
    }
    c.water = waterBody >= 0 ? waterBodies[std::size_t(waterBody)].surface : nullptr;
    m_activeDensity = waterBody >= 0 ? waterBodies[std::size_t(waterBody)].fluidDensity : m_world->getFluidDensity();
}

bool btBuoyancyAction::bodyReachesWater(SubstepContext& c) {
    const Eigen::Vector3d& bc = c.bc;
    const double br = c.br;
    if (c.water && !c.straddling)
        c.water->heightBounds(bc.x() - br, bc.z() - br, bc.x() + br, bc.z() + br, c.time, c.lo, c.hi);
    if (c.straddling) m_lod.clear();  // no temporal level of detail across regions (evaluated exactly)
    // Whole body above the highest water point: nothing to do (design.md 2.5).
    if (!c.water || bc.y() - br >= c.hi) {
        m_needsPrime = false;  // dry: the missed kick was zero
        m_lod.clear();
        m_hasLastCom = false;  // out of the water Bullet's own sleeping test is right again
        m_pendingSleep = true;
        m_pendingLinearSleep = btScalar(m_baseLinearSleep);
        m_pendingAngularSleep = btScalar(m_baseAngularSleep);
        m_result = btBuoyancyResult();
        m_result.time = c.time;
        m_submergedFraction = 0;
        return false;
    }
    if (c.waves) m_pendingActivate = true;  // written at applyPending
    return true;
}

void btBuoyancyAction::predictHydrostatics(const SubstepContext& c, SubstepForces& f) {
    // Temporal level of detail (settings.hydrostaticsInterval, btHydrostaticsHistory): exact at this body's
    // evaluation substeps, predicted in between while the checks allow it.
    const std::uint64_t substep = m_world->getSubstep();
    btTemporalLevelOfDetailSettings lodSettings;
    lodSettings.interval = btBuoyancyResolveInterval(m_settings, c.dt);
    lodSettings.tolerance = btBuoyancyResolveReuseTolerance(m_settings);
    m_lod.begin(lodSettings);
    btTemporalLevelOfDetailSubstep& lodStep = f.lodStep;
    lodStep.substep = substep;
    lodStep.time = c.time;
    lodStep.dt = c.dt;
    lodStep.density = c.rho;
    lodStep.gravity = c.g;
    {
        const btVector3& origin = m_body->getWorldTransform().getOrigin();
        const double reach = std::max({std::abs(double(origin.x())), std::abs(double(origin.y())),
                                       std::abs(double(origin.z()))});
        lodStep.positionResolution = double(std::numeric_limits<btScalar>::epsilon()) * reach;
    }
    const bool temporalLod = m_lod.getInterval() > 1 && !c.straddling && m_settings.buoyancyEnabled && !m_deformable &&
                             !m_world->getDeviceBackend();
    f.evaluationSubstep = temporalLod && m_lod.isEvaluationSubstep(substep);
    f.predicted = temporalLod && !f.evaluationSubstep && !m_needsPrime &&
                  m_lod.predict(lodStep, c.pose, c.com, c.bc.y() - c.br, c.bc.y() + c.br, c.lo, c.hi, f.prediction);
    f.h = f.predicted ? f.prediction.hydrostatics : buoyancy::HydrostaticsResult();
}

void btBuoyancyAction::buildWaterPatch(const SubstepContext& c, SubstepForces& f) {
    const btWaterSurface* water = c.water;
    // Fewer wave queries (design.md 2.5): on a non-flat surface, one query per node of a small grid over
    // the body's footprint, interpolated at every vertex, sample and drag cluster.
    f.flatH = 0;
    f.flat = water->isFlat(c.time, f.flatH);
    f.patch = nullptr;
    f.dragOn = dragIsOn();
    // Only for surfaces that say a query costs more than the interpolation (btWaterSurface::prefersHeightPatch:
    // Gerstner's Newton inversion): a grid, FFT or interactive surface answers by a lookup cheaper than the
    // interpolation, and its short ripples would be smoothed away.
    // Its spacing follows the shortest wave (btBuoyancyWaterPatchNodes). Each consumer uses the patch only when it
    // has fewer nodes than the points it stands for: the hydrostatics (the mesh's vertices for the exact-mesh
    // method, or the samples) and the drag (its clusters) decide apart, so a small
    // body's drag probes do not put its hydrostatics on interpolated heights. Not needed by either: not built.
    f.dragPatch = nullptr;
    if (!f.predicted && !f.flat) {
        const PatchUse use = patchUse(c, water, f.dragOn);
        const std::size_t nodes = use.nodes;
        if (use.hydrostatics || use.drag) {
            try {
                // Scratch of the calling thread: the patch is built afresh at every exact evaluation and used only
                // within it (its warm start, m_patchCache, is the body's). A per-body patch (8 KB of cells for 11
                // nodes) was out of the cache again by the body's next exact evaluation in a large fleet.
                thread_local buoyancy::WaterPatch patchScratch;
                PatchPrebuild& p = m_prebuild;
                if (p.ready && p.water == water && p.revision == water->getRevision() && p.time == c.time &&
                    p.nodes == int(nodes) &&
                    p.lattice == buoyancy::WaterPatch::lattice(c.bc.x(), c.bc.z(), c.br, int(nodes))) {
                    // The heights queried ahead are those this query would give (same nodes, time, surface and
                    // warm start): the patch and the warm start after it are bit for bit the same.
                    patchScratch.buildFromHeights(c.bc.x(), c.bc.z(), c.br, int(nodes), p.f.data());
                    std::swap(m_patchCache, p.cache);
                } else {
                    patchScratch.build(*water, c.bc.x(), c.bc.z(), c.br, c.time, int(nodes), m_patchCache);
                }
                p.ready = false;
                if (patchScratch.finite()) {
                    if (use.hydrostatics) f.patch = &patchScratch;
                    if (use.drag) f.dragPatch = &patchScratch;
                }
            } catch (const std::exception&) {
                f.patch = f.dragPatch = nullptr;  // a degenerate footprint: fall back to exact queries
            }
        }
    }

    const buoyancy::WaterPatch* built = f.patch ? f.patch : f.dragPatch;
    if (!f.predicted) m_lod.setWaterSlope(f.flat ? 0.0 : built ? built->slopeBound() : 1.0);
}

btBuoyancyAction::PatchUse btBuoyancyAction::patchUse(const SubstepContext& c, const btWaterSurface* water,
                                                       bool dragOn) const {
    PatchUse use;
    if (c.straddling || m_settings.waterPatchNodes <= 0 || !water->prefersHeightPatch()) return use;
    use.nodes = std::size_t(btBuoyancyWaterPatchNodes(m_settings, c.br, water->shortestWavelength()));
    // The exact-mesh method counts its vertices, not its edge midpoints too: measured in the wave benchmark (the
    // 16-sided cylinder, 34 vertices and 96 edges, swell), exact heights took 13 µs and the patch 22 µs (its
    // third-derivative estimate splits more) at the same error.
    const std::size_t hydroPoints = m_shape->getIntegrationMethod().sampled ? getSamplesInUse().size()
                                                                            : m_shape->getMesh().vertices.size();
    const std::size_t dragPoints = dragOn ? m_drag->size() : 0;
    use.hydrostatics = use.nodes * use.nodes < hydroPoints;
    use.drag = use.nodes * use.nodes < dragPoints;
    return use;
}

bool btBuoyancyAction::evaluateHydrostatics(const SubstepContext& c, SubstepForces& f) {
    const Eigen::Isometry3d& pose = c.pose;
    const Eigen::Vector3d& com = c.com;
    const double rho = c.rho, g = c.g, time = c.time, flatH = f.flatH;
    const bool flat = f.flat;
    buoyancy::HydrostaticsResult& h = f.h;
    const buoyancy::IntegrationMethod& method = m_shape->getIntegrationMethod();
    f.onDevice = false;  // h came from the world's device backend
    if (m_settings.buoyancyEnabled && !f.predicted) {
        try {  // never let an exception escape into Bullet's stepSimulation
            if (c.straddling) {
                h = buoyancy::regionHydrostatics(m_shape->getMesh(), pose, m_regionsReached.data(),
                                                 m_regionsReached.size(), time, g, com);
            } else if (flat && m_shape->getSphereRadius() > 0 && !m_deformable) {
                // A btSphereShape in flat water: the cap in closed form (design.md 2.5 "Spheres in flat water").
                h = buoyancy::sphereHydrostatics(pose.translation(), m_shape->getSphereRadius(), flatH, rho, g, com);
            } else if (flat && m_shape->isBox() && !m_deformable) {
                // A btBoxShape in flat water: its exact clip in constant time (design.md 2.5 "Boxes in flat water").
                h = buoyancy::boxHydrostatics(pose, m_shape->getBoxHalfExtents(), flatH, rho, g, com);
            } else if (flat && m_shape->getCapsuleRadius() > 0 && !m_deformable) {
                // A btCapsuleShape in flat water: sliced across its axis, exact to rounding (design.md 2.5
                // "Capsules in flat water").
                h = buoyancy::capsuleHydrostatics(pose.translation(), pose.linear().col(m_shape->getCapsuleAxis()),
                                                  m_shape->getCapsuleHalfHeight(), m_shape->getCapsuleRadius(), flatH,
                                                  rho, g, com);
            } else if (flat && c.bc.y() + c.br <= flatH && !m_deformable) {
                h = submergedClosedForm(pose, rho, g, com);  // whole body under flat water (design.md 2.5)
            } else {
                btBuoyancyDeviceBackend* dev = method.deviceBatched ? m_world->getDeviceBackend() : nullptr;
                if (dev && dev->hydrostatics(*this, pose, com, h))
                    f.onDevice = true;
                else
                    h = method.evaluate(m_shape->getGeometry(getSamplesInUse()), pose,
                                        {*c.water, time, rho, g, com, f.patch, &m_ws, &m_waterCache});
            }
        } catch (const std::exception&) {
            ++m_rejected;
            m_lod.clear();
            return false;
        }
    }
    return true;
}

void btBuoyancyAction::addedMassAndWaterForce(const SubstepContext& c, SubstepForces& f) {
    const buoyancy::HydrostaticsResult& h = f.h;
    const double rho = c.rho;
    // Added mass (design.md 2.7) on the linear motion, per axis of the water frame (heave along up, the rest across
    // it): (m + m_a) a = F − m g. Bullet already applies −g·dt, so the impulse is J = m/(m + m_a)·(F + m_a g_up)·dt.
    f.m = 1.0 / double(m_body->getInvMass());
    f.ma = addedMassOf(h, rho);
    const Eigen::Vector3d& ma = f.ma;
    f.meff = Eigen::Vector3d::Constant(f.m) + ma;
    f.gravityAcc = c.frame->toWaterVector(toEigen(m_body->getGravity()));

    // The water's acceleration Du/Dt (design.md 2.7, "The water's acceleration"), at the centre of buoyancy, one
    // query per substep, only under water that changes over time: the added mass acts on the acceleration relative
    // to the water, (m + m_a) a = F − m g + m_a Du/Dt; with AddedMassAndFroudeKrylov the pressure force's part beyond
    // ρ g V_sub ŷ is replaced by linear theory's Froude–Krylov force ρ V_sub Du/Dt. Applied with the hydrostatic
    // kick (scaled by m/(m + m_a) below); drag is evaluated without it (dragEvaluationVelocity).
    const btWaterAccelerationForce accelerationModel = m_settings.waterAcceleration;
    const bool froudeKrylov = accelerationModel == btWaterAccelerationForce::AddedMassAndFroudeKrylov &&
                              m_settings.buoyancyEnabled && !c.straddling;
    f.waterForce = Eigen::Vector3d::Zero();     // m_a Du/Dt [+ ρ V_sub Du/Dt], N
    f.replacedPressure = Eigen::Vector3d::Zero(); // [F_p − ρ g V_sub ŷ], N
    f.waterForceOn = false;
    if (accelerationModel != btWaterAccelerationForce::None && (ma.y() > 0 || froudeKrylov) && h.submerged_volume > 0 &&
        c.water->isTimeVarying()) {
        const Eigen::Vector3d& cb = h.centre_of_buoyancy;
        double du[3] = {0, 0, 0};
        c.water->accelerations(&cb.x(), &cb.y(), &cb.z(), 1, c.time, &du[0], &du[1], &du[2]);
        const Eigen::Vector3d acceleration(du[0], du[1], du[2]);
        if (acceleration.allFinite() && cb.allFinite()) {
            f.waterForce = ma.cwiseProduct(acceleration);
            if (froudeKrylov) {
                const double displaced = rho * h.submerged_volume;  // ρ V_sub, kg
                f.waterForce += displaced * acceleration;
                f.replacedPressure = h.force - Eigen::Vector3d(0.0, displaced * c.g, 0.0);
            }
            f.waterForceOn = true;
        }
    }
}

void btBuoyancyAction::evaluateDrag(const SubstepContext& c, SubstepForces& f) {
    const buoyancy::HydrostaticsResult& h = f.h;
    Eigen::Vector3d& v = f.v;
    Eigen::Vector3d& w = f.w;
    // Drag is evaluated at the velocity the next substep will integrate: this substep's hydrostatic kick
    // plus the gravity kick Bullet applies next. At rest in equilibrium that is exactly 0, so drag cannot
    // shift the draft (with the bare body velocity, −g·dt at rest, linear damping would sink it by b·g·dt/g).
    dragEvaluationVelocity(h, c.dt, v, w);
    // Linear damping (design.md 2.6): the radiation damping faded by the depth of the body's top, plus the viscous.
    m_linearDamping = f.dragOn ? linearDampingAt(h, c.lo - (c.bc.y() + c.br)) : 0.0;
    f.dragF = Eigen::Vector3d::Zero();
    f.dragT = Eigen::Vector3d::Zero();
    f.uMean = Eigen::Vector3d::Zero();
    f.linearPower = 0;
    f.dragComputed = false;  // linearPower is this substep's (not an extrapolated drag)
    if (f.predicted && f.dragOn && m_lod.dragFollows(v, w, m_lastMeanWaterVelocity, f.prediction, c.g)) {
        // Temporal level of detail: the extrapolated drag, while the motion follows the extrapolated one.
        f.dragF = f.prediction.dragForce;
        f.dragT = f.prediction.dragTorque;
        f.uMean = m_lastMeanWaterVelocity;
    } else if (f.dragOn) {
        if (!(f.onDevice &&
              m_world->getDeviceBackend()->drag(*this, c.com, v, w, f.dragF, f.dragT, f.uMean, f.linearPower)))
            computeDrag(c.pose, f.dragPatch, c.com, v, w, c.rho, c.time, f.dragF, f.dragT, f.uMean, f.linearPower,
                        f.predicted);
        f.dragComputed = true;
    }
    if (!f.predicted) m_lastMeanWaterVelocity = f.uMean;
}

void btBuoyancyAction::recordTemporalLevelOfDetail(const SubstepContext& c, const SubstepForces& f) {
    if (f.evaluationSubstep) {
        btHydrostaticsSnapshot exact;
        exact.hydrostatics = f.h;
        exact.com = c.com;
        exact.rotation = c.pose.linear();
        exact.dragForce = f.dragF;
        exact.dragTorque = f.dragT;
        exact.linearVelocity = f.v;
        exact.angularVelocity = f.w;
        m_lod.record(f.lodStep, exact, f.meff.y());  // the heave's
    }
}

void btBuoyancyAction::implicitDragScale(const SubstepContext& c, SubstepForces& f) {
    const double dt = c.dt;
    const Eigen::Vector3d& v = f.v;
    const Eigen::Vector3d& w = f.w;
    const Eigen::Vector3d& meff = f.meff;
    Eigen::Vector3d& dragF = f.dragF;
    Eigen::Vector3d& dragT = f.dragT;
    // Drag solved at the end-of-step velocity (design.md 2.6, "Implicit drag"): the impulse (J, L) is scaled by s so
    // that the velocity after it is the one the drag is evaluated at, as far as the drag's direction stays that of
    // the explicit one. In the mass metric ⟨x,y⟩ = m_eff x_v·y_v + x_ω·I y_ω, with a = −⟨Δ,V⟩/|V|² the explicit
    // fraction removed, split into the linear damping's a_l and the quadratic drag's a_q (by their shares of the
    // drag's power): quadratic drag scales with x² and linear damping with x when the relative velocity scales by x,
    // so V' = x V with x = 1 − a_q x² − a_l x, and s = (a_q x² + a_l x) / a. Pure linear damping gives s = 1/(1+a);
    // pure quadratic drag along a fixed direction the exact implicit step, whose terminal velocity is the drag law's
    // at any dt. The second bound s ≤ a|V|²/|Δ|² keeps |V'|² ≤ |V|²(1 − s a) when Δ is not parallel to V: the drag
    // never adds relative kinetic energy nor reverses the relative motion.
    double sLinear = 1.0, sAngular = 1.0;
    if (f.dragOn) {
        const Eigen::Vector3d J = dragF * dt, L = dragT * dt;
        const Eigen::Vector3d vr = v - f.uMean;
        const btMatrix3x3& basis = m_body->getWorldTransform().getBasis();
        const Eigen::Vector3d invI = toEigen(m_body->getInvInertiaDiagLocal());
        Eigen::Matrix3d R;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) R(i, j) = double(basis[i][j]);
        if (!c.frame->isIdentity()) R = c.frame->rotation().transpose() * R;  // body → water axes, as w and L
        const Eigen::Vector3d wl = R.transpose() * w, Ll = R.transpose() * L;
        double rotE = 0, rotD = 0;
        for (int k = 0; k < 3; ++k) {
            if (invI[k] > 0) rotE += wl[k] * wl[k] / invI[k];
            rotD += invI[k] * Ll[k] * Ll[k];
        }
        const double linE = meff.dot(vr.cwiseProduct(vr)), linD = J.cwiseProduct(J).dot(meff.cwiseInverse());
        const double power = dragF.dot(vr) + dragT.dot(w);  // W, < 0 when the drag removes energy
        if (f.dragComputed) m_linearShare = power < 0 ? std::min(std::max(f.linearPower / power, 0.0), 1.0) : 0.0;
        // The scale for a block with energy V2 (in the metric), drag change D2 and removed fraction a.
        const double share = m_linearShare;
        const auto implicitScale = [share](double a, double V2, double D2) {
            if (!(a > 0 && D2 > 0)) return 1.0;
            const double al = share * a, aq = a - al;
            const double x = 2.0 / ((1.0 + al) + std::sqrt((1.0 + al) * (1.0 + al) + 4.0 * aq));
            return std::min((aq * x * x + al * x) / a, a * V2 / D2);
        };
        const double V2 = linE + rotE, D2 = linD + rotD;
        const double a = V2 > 0 ? -(J.dot(vr) + L.dot(w)) / V2 : 0.0;
        const double s = implicitScale(a, V2, D2);
        // Each block (linear, angular) on its own where its drag removes its energy: a body whose heave carries most
        // of the metric (a light body with a large heave added mass) keeps its rotation's damping implicit too.
        const double aLinear = linE > 0 ? -J.dot(vr) / linE : 0.0, aAngular = rotE > 0 ? -L.dot(w) / rotE : 0.0;
        sLinear = aLinear > 0 ? implicitScale(aLinear, linE, linD) : s;
        sAngular = aAngular > 0 ? implicitScale(aAngular, rotE, rotD) : s;
    }
    dragF *= sLinear;
    dragT *= sAngular;
}

void btBuoyancyAction::computeImpulses(const SubstepContext& c, SubstepForces& f) {
    const buoyancy::HydrostaticsResult& h = f.h;
    const Eigen::Vector3d& ma = f.ma;
    const double dt = c.dt;
    // Priming: the body's velocity is meant as the velocity after every kick at its current pose, but in
    // the first substep after creation or wake-up Bullet applied gravity (and integrated) with no buoyancy
    // kick for the starting pose. Give that missed hydrostatic kick once (evaluated at the current pose),
    // else a neutrally buoyant body keeps the −g·dt it got and drifts (design.md 3, symplectic Euler).
    const double prime = m_needsPrime ? 2.0 : 1.0;
    Eigen::Vector3d linearForce = prime * (h.force - ma.cwiseProduct(f.gravityAcc)) + f.dragF;
    // A heave added mass that grew since the last substep (a body entering the water, a waterplane widening): the
    // momentum form d/dt((m + m_a) v) = F keeps (m + m_a) v relative to the water across the change (von Kármán's
    // water entry, design.md 2.7), a force −Δm_a v_rel / dt along up; a shrinking one gives nothing back. Without it a
    // light body meeting a large added mass keeps its speed and gains the energy ½ Δm_a v². Not at a priming substep
    // (a body placed in the water, or waking up: its water moves with it).
    if (!m_needsPrime && ma.y() > m_result.addedMass) {
        const double relative = c.frame->toWaterVector(toEigen(m_body->getLinearVelocity())).y() - f.uMean.y();
        linearForce.y() -= (ma.y() - m_result.addedMass) * relative / dt;
    }
    // (Flat or steady water: not even a zero added. The priming gives the replaced pressure's kick twice too.)
    if (f.waterForceOn) linearForce += f.waterForce - prime * f.replacedPressure;
    f.linearImpulse = (f.m * linearForce * dt).cwiseQuotient(f.meff);
    f.angularImpulse = (prime * h.torque + f.dragT) * dt;
}

void btBuoyancyAction::recordResult(const SubstepContext& c, const SubstepForces& f) {
    const buoyancy::HydrostaticsResult& h = f.h;
    const btWaterFrame& frame = *c.frame;
    // Back to the world (the result and the impulses are world-frame).
    m_result.submergedVolume = h.submerged_volume;
    m_result.centreOfBuoyancy = toBullet(frame.toWorldPoint(h.centre_of_buoyancy));
    m_result.buoyancyForce = toBullet(frame.toWorldVector(h.force));
    m_result.buoyancyTorque = toBullet(frame.toWorldVector(h.torque));
    m_result.dragForce = toBullet(frame.toWorldVector(f.dragF));
    m_result.dragTorque = toBullet(frame.toWorldVector(f.dragT));
    m_result.wettedArea = h.wetted_area;
    m_result.waterlineArea = h.waterline_area;
    m_result.addedMass = f.ma.y();
    m_result.time = c.time;
    m_result.predicted = f.predicted;
    {
        const double bodyVolume = m_deformable ? m_deformable->getVolume() : m_shape->getVolume();
        const double fraction = bodyVolume > 0 ? h.submerged_volume / bodyVolume : 0.0;
        if (std::isfinite(fraction)) m_submergedFraction = std::min(std::max(fraction, 0.0), 1.0);
    }
}

void btBuoyancyAction::decideImpulseAndSleep(const SubstepContext& c, const SubstepForces& f) {
    const buoyancy::HydrostaticsResult& h = f.h;
    const btWaterFrame& frame = *c.frame;
    const Eigen::Vector3d& linearImpulse = f.linearImpulse;
    const Eigen::Vector3d& angularImpulse = f.angularImpulse;
    // Never write NaN/Inf into a body (design.md 3): checked after rounding to btScalar (a finite double
    // can overflow a float) and on the velocities the impulses would give.
    btVector3 J = toBullet(frame.toWorldVector(linearImpulse)), L = toBullet(frame.toWorldVector(angularImpulse));
    if (m_marine.enabled && !marineImpulse(h, c.dt, J, L)) {  // Fossen's model (design.md 2.10)
        ++m_rejected;
        m_lod.clear();
        return;
    }
    const btVector3 v1 = m_body->getLinearVelocity() + J * m_body->getInvMass() * m_body->getLinearFactor();
    const btVector3 w1 = m_body->getAngularVelocity() + m_body->getInvInertiaTensorWorld() * L * m_body->getAngularFactor();
    if (!linearImpulse.allFinite() || !angularImpulse.allFinite() || !toEigen(v1).allFinite() ||
        !toEigen(w1).allFinite() || !toEigen(J).allFinite() || !toEigen(L).allFinite()) {
        ++m_rejected;
        m_marineSubstep = 0;
        m_lod.clear();
        return;
    }
    // Sleeping (design.md 3): at rest when the energy above the hydrostatic equilibrium is a small fraction of
    // m g L, whatever Bullet's velocity thresholds are; Bullet then counts down to sleep as usual.
    const bool atRest =
        m_hasLastCom && energyAboveEquilibrium(h, c.com, c.dt, f.m, f.gravityAcc) < restEnergy(h, f.m, f.gravityAcc);
    m_lastCom = c.com;
    m_hasLastCom = true;
    const btScalar open = atRest ? btScalar(1e6) : btScalar(0);
    m_pendingSleep = true;
    m_pendingLinearSleep = m_pendingAngularSleep = open;
    m_pendingImpulse = true;
    m_pendingJ = J;
    m_pendingL = L;
}

double btBuoyancyAction::restEnergy(const buoyancy::HydrostaticsResult& h, double mass,
                                    const Eigen::Vector3d& gravityAcc) const {
    const double g = gravityAcc.norm();
    const double area = h.waterline_area;
    if (area > 0 && std::isfinite(area) && h.submerged_volume > 0) {
        // Afloat: the energy of a heave whose amplitude moves the submerged volume by kRestVolumeFraction of it,
        // ½ k a² with k = ρ g A and a = ε V / A. A body put to sleep is then that close to its Archimedes draft.
        const double a = kRestVolumeFraction * h.submerged_volume / area;
        return 0.5 * m_activeDensity * g * area * a * a;
    }
    // Under water, on the bottom or in the air: the kinetic energy of a speed of kRestSpeedFraction √(g L).
    const double v = kRestSpeedFraction * std::sqrt(g * m_shape->getBoundsRadius());
    return 0.5 * mass * v * v;
}

double btBuoyancyAction::energyAboveEquilibrium(const buoyancy::HydrostaticsResult& h, const Eigen::Vector3d& com,
                                                 double dt, double mass, const Eigen::Vector3d& gravityAcc) const {
    // Kinetic energy from the real motion of the centre of mass over the substep (Bullet's stored velocity holds
    // the next kick: at rest on the water it is +g dt, not 0) and the stored angular velocity.
    const Eigen::Vector3d v = (com - m_lastCom) / dt;
    double energy = 0.5 * mass * v.squaredNorm();
    const btVector3 wl = m_body->getWorldTransform().getBasis().transpose() * m_body->getAngularVelocity();
    const btVector3 invI = m_body->getInvInertiaDiagLocal();
    for (int k = 0; k < 3; ++k)
        if (invI[k] > 0) energy += 0.5 * double(wl[k]) * double(wl[k]) / double(invI[k]);
    // Potential energy stored in the hydrostatic spring, from the force and torque still unbalanced: a body at
    // the top of a bob has no speed but a net force F, which a spring of stiffness k holds with energy F²/(2k).
    // Heave: k = ρ g A_waterline. Roll and pitch: k = ρ g I_waterplane, about the weakest axis of the waterplane
    // (its metacentric part; the torque's energy is then not underestimated by a stiffer axis). A body with no
    // waterline (under water, or out of it) has no such spring: its kinetic energy alone decides.
    const double g = gravityAcc.norm();
    const double rhoG = m_activeDensity * g;
    const double area = h.waterline_area;
    if (rhoG > 0 && area > 0 && std::isfinite(area)) {
        const Eigen::Vector3d up = g > 0 ? Eigen::Vector3d(-gravityAcc / g) : Eigen::Vector3d::UnitY();
        const double netVertical = (h.force + mass * gravityAcc).dot(up);
        energy += netVertical * netVertical / (2.0 * rhoG * area);
        double weakest = area * area / (4.0 * 3.14159265358979323846);  // a disc of that area, when the moments are not known
        if (h.waterplane.valid) {
            const buoyancy::WaterplaneMoments& wp = h.waterplane;
            const double cx = wp.x / area, cz = wp.z / area;
            const double ixx = wp.xx - area * cx * cx, izz = wp.zz - area * cz * cz, ixz = wp.xz - area * cx * cz;
            const double mean = 0.5 * (ixx + izz), half = 0.5 * (ixx - izz);
            weakest = std::max(mean - std::sqrt(half * half + ixz * ixz), 1e-12 * area * area);
        }
        const Eigen::Vector3d tilt = h.torque - h.torque.dot(up) * up;  // the yaw torque has no spring
        energy += tilt.squaredNorm() / (2.0 * rhoG * weakest);
    }
    return energy;
}

void btBuoyancyAction::debugDraw(btIDebugDraw* debugDrawer) {
    if (!debugDrawer || !m_result.applied) return;
    const btScalar mg = btScalar(m_world->getGravity()) / m_body->getInvMass();
    if (!(mg > 0)) return;
    const btVector3& c = m_result.centreOfBuoyancy;
    debugDrawer->drawLine(c, c + m_result.buoyancyForce / mg, btVector3(0, 0.4, 1));
    const btVector3 com = m_body->getCenterOfMassPosition();
    debugDrawer->drawLine(com, com + m_result.dragForce / mg, btVector3(1, 0.3, 0));
}

// ---- save and restore (btBuoyancyState.h) ----
namespace {

/// Which surface a pointer is, as a number that means the same after a restore: 0 none (or a surface the world no
/// longer has: the warm start would start cold anyway), 1 the world's unbounded water, 2 + k water body k.
std::uint32_t surfaceIndex(const btBuoyancyWorld& world, const btWaterSurface* s) {
    if (!s) return 0;
    if (s == world.getWater()) return 1;
    const std::vector<btWaterBody>& bodies = world.getWaterBodies();
    for (std::size_t k = 0; k < bodies.size(); ++k)
        if (bodies[k].surface == s) return std::uint32_t(2 + k);
    return 0;
}

const btWaterSurface* surfaceOf(const btBuoyancyWorld& world, std::uint32_t index, btBuoyancyStateReader& in,
                                const char* field) {
    if (index == 0) return nullptr;
    if (index == 1) {
        if (!world.getWater()) in.fail(std::string(field) + " names the world's unbounded water, the world has none");
        return world.getWater();
    }
    const std::size_t k = std::size_t(index - 2);
    if (k >= world.getWaterBodies().size())
        in.fail(std::string(field) + " names water body " + std::to_string(k) + ", the world has " +
                std::to_string(world.getWaterBodies().size()));
    return world.getWaterBodies()[k].surface;
}

void writeCache(btBuoyancyStateWriter& out, const btBuoyancyWorld& world, const btWaterQueryCache& c) {
    const std::uint32_t owner = surfaceIndex(world, c.owner);
    out.u32(owner);
    if (owner == 0) return;
    out.u64(c.n);
    out.f64Vector(c.a);
    out.f64Vector(c.b);
}

btWaterQueryCache readCache(btBuoyancyStateReader& in, const btBuoyancyWorld& world, const char* field) {
    btWaterQueryCache c;
    c.owner = surfaceOf(world, in.u32(field), in, field);
    if (!c.owner) return c;
    c.n = std::size_t(in.u64(field));
    c.a = in.f64Vector(field);
    c.b = in.f64Vector(field);
    return c;
}

void writeVector(btBuoyancyStateWriter& out, const btVector3& v) {
    for (int k = 0; k < 3; ++k) out.f64(double(v[k]));
}

btVector3 readVector(btBuoyancyStateReader& in, const char* field) {
    btVector3 v;
    for (int k = 0; k < 3; ++k) v[k] = btScalar(in.f64(field));  // exact: saved from a btScalar of this precision
    return v;
}

void writeEigen(btBuoyancyStateWriter& out, const Eigen::Vector3d& v) { out.f64s(v.data(), 3); }

Eigen::Vector3d readEigen(btBuoyancyStateReader& in, const char* field) {
    Eigen::Vector3d v;
    in.f64s(v.data(), 3, field);
    return v;
}

/// The arrays a blob's drag water must fill: exactly the action's cluster count.
std::vector<double> readSized(btBuoyancyStateReader& in, std::size_t n, const char* field) {
    std::vector<double> v = in.f64Vector(field);
    in.expectCount(v.size(), n, field);
    return v;
}

}  // namespace

std::vector<unsigned char> btBuoyancyAction::saveState() const {
    btBuoyancyStateWriter out(btBuoyancyStateKind::Action);
    // What the blob must be restored into.
    out.u64(m_shape->getSamples().size());
    out.u64(m_shape->getMesh().vertices.size());
    out.u64(m_shape->getMesh().triangles.size());
    out.u64(m_drag->size());
    out.u64(m_drag->probeX.size());
    // Substep bookkeeping.
    out.u64(m_frameVersion);
    out.u64(m_lastSubstep);
    out.u64(m_evaluatedSubstep);
    out.boolean(m_pendingActivate);
    out.boolean(m_pendingSleep);
    out.f64(double(m_pendingLinearSleep));
    out.f64(double(m_pendingAngularSleep));
    out.boolean(m_pendingImpulse);
    writeVector(out, m_pendingJ);
    writeVector(out, m_pendingL);
    out.u64(m_rejected);
    // Water events.
    out.f64(m_submergedFraction);
    out.boolean(m_waterState.inWater);
    out.boolean(m_waterState.submerged);
    out.i32(m_waterState.waterBody);
    // The water chosen.
    out.u32(surfaceIndex(*m_world, m_activeWater));
    out.f64(m_activeDensity);
    out.i32(m_activeWaterBody);
    out.boolean(m_needsPrime);
    // Temporal level of detail.
    m_lod.writeState(out);
    writeEigen(out, m_lastMeanWaterVelocity);
    out.f64(m_linearDamping);
    out.f64(m_linearShare);
    // The drag's water kept for predicted substeps, and the warm starts.
    out.f64Vector(m_dh);
    out.f64Vector(m_ux);
    out.f64Vector(m_uy);
    out.f64Vector(m_uz);
    writeCache(out, *m_world, m_waterCache);
    writeCache(out, *m_world, m_dragCache);
    writeCache(out, *m_world, m_probeCache);
    writeCache(out, *m_world, m_patchCache);
    // Sleeping.
    out.f64(m_baseLinearSleep);
    out.f64(m_baseAngularSleep);
    writeEigen(out, m_lastCom);
    out.boolean(m_hasLastCom);
    // Marine hydrodynamics: the previous substep's end state its added momentum is carried from (design.md 2.10).
    out.u64(m_marineSubstep);
    for (int i = 0; i < 6; ++i) out.f64(m_marineVelocity[i]);
    for (int i = 0; i < 9; ++i) out.f64(m_marineRotation.data()[i]);
    writeEigen(out, m_marineCurrent);
    // The last result.
    const btBuoyancyResult& r = m_result;
    out.f64(r.submergedVolume);
    writeVector(out, r.centreOfBuoyancy);
    writeVector(out, r.buoyancyForce);
    writeVector(out, r.buoyancyTorque);
    writeVector(out, r.dragForce);
    writeVector(out, r.dragTorque);
    out.f64(r.wettedArea);
    out.f64(r.waterlineArea);
    out.f64(r.addedMass);
    out.f64(r.time);
    writeVector(out, r.linearImpulse);
    writeVector(out, r.angularImpulse);
    out.boolean(r.applied);
    out.boolean(r.predicted);
    out.u8(std::uint8_t(r.status));
    return out.bytes();
}

void btBuoyancyAction::restoreState(const unsigned char* data, std::size_t size) {
    if (m_world->isDispatchingEvents())
        throw std::logic_error("btBuoyancyAction::restoreState: called from an event callback; restore between "
                               "stepSimulation calls");
    m_world->finishPrebuilds();  // the heights queried ahead read the warm start about to be replaced
    btBuoyancyStateReader in(data, size, btBuoyancyStateKind::Action, "btBuoyancyAction::restoreState");
    in.expectCount(in.u64("sample count"), m_shape->getSamples().size(), "the shape's sample count");
    in.expectCount(in.u64("mesh vertex count"), m_shape->getMesh().vertices.size(), "the mesh's vertex count");
    in.expectCount(in.u64("mesh triangle count"), m_shape->getMesh().triangles.size(), "the mesh's triangle count");
    in.expectCount(in.u64("drag cluster count"), m_drag->size(), "the drag cluster count");
    in.expectCount(in.u64("velocity probe count"), m_drag->probeX.size(), "the velocity probe count");
    // Everything is read into locals first, then committed (a bad blob leaves the action as it was).
    const std::uint64_t frameVersion = in.u64("frame version");
    const std::uint64_t lastSubstep = in.u64("last substep");
    const std::uint64_t evaluatedSubstep = in.u64("evaluated substep");
    const bool pendingActivate = in.boolean("pending activation");
    const bool pendingSleep = in.boolean("pending sleep");
    const btScalar pendingLinearSleep = btScalar(in.f64("pending linear sleeping threshold"));
    const btScalar pendingAngularSleep = btScalar(in.f64("pending angular sleeping threshold"));
    const bool pendingImpulse = in.boolean("pending impulse");
    const btVector3 pendingJ = readVector(in, "pending linear impulse");
    const btVector3 pendingL = readVector(in, "pending angular impulse");
    const std::uint64_t rejected = in.u64("rejected count");
    const double submergedFraction = in.f64("submerged fraction");
    btBuoyancyWaterState waterState;
    waterState.inWater = in.boolean("in water");
    waterState.submerged = in.boolean("fully submerged");
    waterState.waterBody = in.i32("events' water body");
    const btWaterSurface* activeWater = surfaceOf(*m_world, in.u32("active water"), in, "the active water");
    const double activeDensity = in.f64("active density");
    const int activeWaterBody = in.i32("active water body");
    if (activeWaterBody < -1 || activeWaterBody >= int(m_world->getWaterBodies().size()))
        in.fail("the body was in water body " + std::to_string(activeWaterBody) + ", the world has " +
                std::to_string(m_world->getWaterBodies().size()));
    const bool needsPrime = in.boolean("needs prime");
    btTemporalLevelOfDetail lod = m_lod;  // the body's volume and radius; the rest is read
    lod.readState(in);
    const Eigen::Vector3d lastMeanWaterVelocity = readEigen(in, "last mean water velocity");
    const double linearDamping = in.f64("linear damping");
    const double linearShare = in.f64("linear share");
    const std::size_t k = m_drag->size();
    std::vector<double> dh = readSized(in, k, "the drag's kept water heights");
    std::vector<double> ux = readSized(in, k, "the drag's kept water velocities (x)");
    std::vector<double> uy = readSized(in, k, "the drag's kept water velocities (y)");
    std::vector<double> uz = readSized(in, k, "the drag's kept water velocities (z)");
    btWaterQueryCache waterCache = readCache(in, *m_world, "the hydrostatics' warm start");
    btWaterQueryCache dragCache = readCache(in, *m_world, "the drag's warm start");
    btWaterQueryCache probeCache = readCache(in, *m_world, "the velocity probes' warm start");
    btWaterQueryCache patchCache = readCache(in, *m_world, "the water patch's warm start");
    const double baseLinearSleep = in.f64("base linear sleeping threshold");
    const double baseAngularSleep = in.f64("base angular sleeping threshold");
    const Eigen::Vector3d lastCom = readEigen(in, "last centre of mass");
    const bool hasLastCom = in.boolean("has last centre of mass");
    const std::uint64_t marineSubstep = in.u64("marine substep");
    buoyancy::Vector6d marineVelocity;
    for (int i = 0; i < 6; ++i) marineVelocity[i] = in.f64("marine end-of-step velocity");
    Eigen::Matrix3d marineRotation;
    for (int i = 0; i < 9; ++i) marineRotation.data()[i] = in.f64("marine end-of-step rotation");
    const Eigen::Vector3d marineCurrent = readEigen(in, "marine water velocity");
    btBuoyancyResult r;
    r.submergedVolume = in.f64("result submerged volume");
    r.centreOfBuoyancy = readVector(in, "result centre of buoyancy");
    r.buoyancyForce = readVector(in, "result buoyancy force");
    r.buoyancyTorque = readVector(in, "result buoyancy torque");
    r.dragForce = readVector(in, "result drag force");
    r.dragTorque = readVector(in, "result drag torque");
    r.wettedArea = in.f64("result wetted area");
    r.waterlineArea = in.f64("result waterline area");
    r.addedMass = in.f64("result added mass");
    r.time = in.f64("result time");
    r.linearImpulse = readVector(in, "result linear impulse");
    r.angularImpulse = readVector(in, "result angular impulse");
    r.applied = in.boolean("result applied");
    r.predicted = in.boolean("result predicted");
    const std::uint8_t status = in.u8("result status");
    if (status > std::uint8_t(btBuoyancyStatus::GravityNotAlongWaterUp))
        in.fail("result status " + std::to_string(status) + " is not a btBuoyancyStatus");
    r.status = static_cast<btBuoyancyStatus>(status);
    in.finish();

    // Commit (nothing below throws).
    m_frameVersion = frameVersion;
    m_lastSubstep = lastSubstep;
    m_evaluatedSubstep = evaluatedSubstep;
    m_pendingActivate = pendingActivate;
    m_pendingSleep = pendingSleep;
    m_pendingLinearSleep = pendingLinearSleep;
    m_pendingAngularSleep = pendingAngularSleep;
    m_pendingImpulse = pendingImpulse;
    m_pendingJ = pendingJ;
    m_pendingL = pendingL;
    m_rejected = rejected;
    m_submergedFraction = submergedFraction;
    m_waterState = waterState;
    m_activeWater = activeWater;
    m_activeDensity = activeDensity;
    m_activeWaterBody = activeWaterBody;
    m_needsPrime = needsPrime;
    m_lod = lod;
    m_lastMeanWaterVelocity = lastMeanWaterVelocity;
    m_linearDamping = linearDamping;
    m_linearShare = linearShare;
    m_dh.swap(dh);
    m_ux.swap(ux);
    m_uy.swap(uy);
    m_uz.swap(uz);
    m_waterCache = std::move(waterCache);
    m_dragCache = std::move(dragCache);
    m_probeCache = std::move(probeCache);
    m_patchCache = std::move(patchCache);
    m_prebuild.ready = m_prebuild.wanted = false;
    m_marineSubstep = marineSubstep;
    m_marineVelocity = marineVelocity;
    m_marineRotation = marineRotation;
    m_marineCurrent = marineCurrent;
    m_baseLinearSleep = baseLinearSleep;
    m_baseAngularSleep = baseAngularSleep;
    m_lastCom = lastCom;
    m_hasLastCom = hasLastCom;
    m_result = r;
}
