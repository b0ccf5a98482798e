#include "bullet/btBuoyancyAction.h"

#include "bullet/btBulletConvert.h"
#include "bullet/btBuoyancyInvariants.h"
#include "bullet/btBuoyancyWorld.h"
#include "bullet/btBuoyantBodyBuilder.h"
#include "water/btWaterSurface.h"

#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <LinearMath/btIDebugDraw.h>

#include <cmath>
#include <stdexcept>

using buoyancy::toBullet;
using buoyancy::toEigen;

btBuoyancyAction::btBuoyancyAction(btRigidBody* body, std::shared_ptr<const btBuoyancyShape> shape,
                                   btBuoyancyWorld* world, const btBuoyancySettings& settings,
                                   const btTransform& meshInCom)
    : m_body(body), m_shape(std::move(shape)), m_world(world), m_settings(settings), m_meshInCom(meshInCom) {
    if (!m_body) throw std::invalid_argument("body: null");
    if (!m_shape) throw std::invalid_argument("shape: null");
    if (!m_world) throw std::invalid_argument("world: null");
    m_settings.validate();
    const std::size_t n = m_shape->getDragSamples().size();
    m_ws.resize(n);
    m_ux.resize(n);
    m_uy.resize(n);
    m_uz.resize(n);
    m_dragHalfSize.resize(n);
    const buoyancy::SurfaceSamples& drag = m_shape->getDragSamples();
    for (std::size_t i = 0; i < n; ++i) m_dragHalfSize[i] = 0.5 * std::sqrt(std::max(drag.area[i], 0.0));
    m_baseLinearSleep = double(m_body->getLinearSleepingThreshold());
    m_baseAngularSleep = double(m_body->getAngularSleepingThreshold());
    m_world->registerAction(this);
}

btBuoyancyAction::btBuoyancyAction(btBuoyantBody& body, btBuoyancyWorld* world, const btBuoyancySettings& settings)
    : btBuoyancyAction(body.getRigidBody(), body.getShape(), world, settings, body.getMeshInComFrame()) {
    m_owner = &body;
}

btBuoyancyAction::~btBuoyancyAction() { m_world->unregisterAction(this); }

void btBuoyancyAction::setSettings(const btBuoyancySettings& settings) {
    settings.validate();
    m_settings = settings;
}

btTransform btBuoyancyAction::getMeshInComFrame() const {
    return m_owner ? m_owner->getMeshInComFrame() : m_meshInCom;
}

void btBuoyancyAction::computeDrag(const Eigen::Vector3d& com, const Eigen::Vector3d& v, const Eigen::Vector3d& w,
                                   double density, double time, Eigen::Vector3d& force, Eigen::Vector3d& torque,
                                   Eigen::Vector3d& meanWaterVelocity) {
    // DESIGN-NOTES 2.6 (paper eq. 12): per wetted sample, relative velocity v_i = v + ω × (p_i − c) − u(p_i);
    // pressure drag on front-facing samples F_i = −½ ρ C_d (A_i·v̂_i)|v_i|² v̂_i = −½ ρ C_d (A_i·v_i) v_i;
    // skin friction on the tangential part −½ ρ C_f |A_i| |v_t| v_t.
    const buoyancy::SurfaceSamples& s = m_shape->getDragSamples();
    const std::size_t n = s.size();
    const btWaterSurface& water = *m_world->getWater();
    water.velocitiesCached(m_ws.wx.data(), m_ws.wy.data(), m_ws.wz.data(), n, time, m_ux.data(), m_uy.data(),
                           m_uz.data(), m_waterCache);
    const double kd = 0.5 * density * m_settings.dragCoefficient;
    const double kf = 0.5 * density * m_settings.skinFriction;
    const double kl = density * m_settings.linearDamping;
    force.setZero();
    torque.setZero();
    Eigen::Vector3d uSum = Eigen::Vector3d::Zero();
    double areaSum = 0;
    for (std::size_t i = 0; i < n; ++i) {
        // Wet fraction of the sample: a linear ramp over its vertical extent, so a shallow draft still gets drag
        // from the samples it half wets (all-or-nothing by centre left a light box with no sideways drag at all).
        // A horizontal piece has no vertical extent: wet by its centre.
        const double an0 = std::sqrt(m_ws.wax[i] * m_ws.wax[i] + m_ws.way[i] * m_ws.way[i] + m_ws.waz[i] * m_ws.waz[i]);
        const double ny = an0 > 0 ? m_ws.way[i] / an0 : 0.0;
        const double halfV = m_dragHalfSize[i] * std::sqrt(std::max(0.0, 1.0 - ny * ny));
        const double depth = m_ws.waterHeight[i] - m_ws.wy[i];
        const double wet = halfV > 0 ? std::min(1.0, std::max(0.0, 0.5 + 0.5 * depth / halfV)) : (depth > 0 ? 1.0 : 0.0);
        if (!(wet > 0)) continue;
        const Eigen::Vector3d r(m_ws.wx[i] - com.x(), m_ws.wy[i] - com.y(), m_ws.wz[i] - com.z());
        const Eigen::Vector3d u(m_ux[i], m_uy[i], m_uz[i]);
        const Eigen::Vector3d vi = v + w.cross(r) - u;
        const Eigen::Vector3d A = wet * Eigen::Vector3d(m_ws.wax[i], m_ws.way[i], m_ws.waz[i]);
        const double a = wet * s.area[i];
        uSum += a * u;
        areaSum += a;
        Eigen::Vector3d f = Eigen::Vector3d::Zero();
        const double av = A.dot(vi);
        if (kd > 0 && av > 0) f -= kd * av * vi;
        const double an = A.norm();
        if (kl > 0 && an > 0) f -= (kl * av / an) * A;  // linear pressure damping −ρ b (A·v) Â
        if (kf > 0) {
            if (an > 0) {
                const Eigen::Vector3d nrm = A / an;
                const Eigen::Vector3d vt = vi - vi.dot(nrm) * nrm;
                f -= kf * a * vt.norm() * vt;
            }
        }
        force += f;
        torque += r.cross(f);
    }
    meanWaterVelocity = areaSum > 0 ? Eigen::Vector3d(uSum / areaSum) : Eigen::Vector3d::Zero();
}

void btBuoyancyAction::updateAction(btCollisionWorld* collisionWorld, btScalar deltaTimeStep) {
    const double dt = double(deltaTimeStep);
    m_result.applied = false;
    // A zero, negative or non-finite step applies nothing and leaves the water's clock alone (issue 10).
    if (!(dt > 0) || !std::isfinite(dt)) return;
    m_world->beginSubstepIfNew(m_lastSubstep, dt);
#ifndef NDEBUG
    // Misuse check: an action whose body is in another world (a removed body has no broadphase handle and
    // is skipped below).
    if (collisionWorld && m_body->getBroadphaseHandle() &&
        collisionWorld->getCollisionObjectArray().findLinearSearch(m_body) ==
                              collisionWorld->getCollisionObjectArray().size())
        btAssert(!"btBuoyancyAction: its body is not in the world; remove the action before the body");
#else
    (void)collisionWorld;
#endif
    m_result.applied = false;
    // A body removed from its world while this action stays in it: do nothing until it is back (issue 10).
    if (!m_body->getBroadphaseHandle()) return;
    const btWaterSurface* water = m_world->getWater();
    if (!water || m_body->getInvMass() == btScalar(0)) return;
    const bool waves = water->isTimeVarying();
    if (!m_body->isActive() && !waves) {  // calm water: a sleeping body stays asleep
        m_needsPrime = true;
        return;
    }

    const double time = m_world->getTime();
    const double rho = m_world->getFluidDensity();
    const double g = m_world->getGravity();
    const Eigen::Isometry3d pose = toEigen(m_body->getWorldTransform() * getMeshInComFrame());
    const Eigen::Vector3d com = toEigen(m_body->getCenterOfMassPosition());
    // A NaN/Inf pose (set by the user, or a body Bullet already lost) is refused here: nothing below may
    // throw through Bullet's stepSimulation (issue 10: clippedHydrostatics threw invalid_argument).
    if (!pose.matrix().allFinite() || !com.allFinite()) {
        ++m_rejected;
        return;
    }

    // Whole body above the highest water point: nothing to do (DESIGN-NOTES 2.5).
    const Eigen::Vector3d bc = pose * m_shape->getBoundsCentre();
    const double br = m_shape->getBoundsRadius();
    double lo = 0, hi = 0;
    water->heightBounds(bc.x() - br, bc.z() - br, bc.x() + br, bc.z() + br, time, lo, hi);
    if (bc.y() - br >= hi) {
        m_needsPrime = false;  // dry: the missed kick was zero
        m_hasLastCom = false;  // out of the water Bullet's own sleeping test is right again
        m_body->setSleepingThresholds(btScalar(m_baseLinearSleep), btScalar(m_baseAngularSleep));
        m_result = btBuoyancyResult();
        m_result.time = time;
        return;
    }
    if (waves) m_body->activate();

    const btBuoyancyMethod method = m_shape->getMethod();
    buoyancy::HydrostaticsResult h;
    bool wsFilled = false;
    if (m_settings.buoyancyEnabled) {
        try {  // never let an exception escape into Bullet's stepSimulation
            if (method == btBuoyancyMethod::ExactMesh) {
                h = buoyancy::clippedHydrostatics(m_shape->getMesh(), pose, *water, time, rho, g, com);
            } else {
                h = buoyancy::sampledHydrostatics(m_shape->getSamples(), pose, *water, time, rho, g, com, m_ws,
                                                  &m_waterCache);
                wsFilled = true;
            }
        } catch (const std::exception&) {
            ++m_rejected;
            return;
        }
    }

    // Added mass (DESIGN-NOTES 2.7), one scalar on the linear motion: (m + m_a) a = F − m g. Bullet already
    // applies −g·dt, so the impulse is J = m/(m + m_a)·(F + m_a g_up)·dt.
    const double m = 1.0 / double(m_body->getInvMass());
    const double ma = m_settings.addedMass ? m_settings.addedMassCoefficient * rho * std::max(h.submerged_volume, 0.0) : 0.0;
    const double meff = m + ma;
    const Eigen::Vector3d gravityAcc = toEigen(m_body->getGravity());

    // Drag is evaluated at the velocity the next substep will integrate: this substep's hydrostatic kick
    // plus the gravity kick Bullet applies next. At rest in equilibrium that is exactly 0, so drag cannot
    // shift the draft (with the bare body velocity, −g·dt at rest, linear damping would sink it by b·g·dt/g).
    Eigen::Vector3d v = toEigen(m_body->getLinearVelocity());
    Eigen::Vector3d w = toEigen(m_body->getAngularVelocity());
    v += ((h.force - ma * gravityAcc) * dt) / meff + gravityAcc * dt;
    w += toEigen(m_body->getInvInertiaTensorWorld() * toBullet(Eigen::Vector3d(h.torque * dt)));
    Eigen::Vector3d dragF = Eigen::Vector3d::Zero(), dragT = Eigen::Vector3d::Zero(), uMean = Eigen::Vector3d::Zero();
    const bool dragOn =
        m_settings.dragCoefficient > 0 || m_settings.skinFriction > 0 || m_settings.linearDamping > 0;
    if (dragOn) {
        if (!wsFilled) {
            const buoyancy::SurfaceSamples& s = m_shape->getDragSamples();
            buoyancy::transformSamples(s, pose, m_ws);
            water->heightsCached(m_ws.wx.data(), m_ws.wz.data(), s.size(), time, m_ws.waterHeight.data(),
                                 m_waterCache);
        }
        computeDrag(com, v, w, rho, time, dragF, dragT, uMean);
    }

    // Drag stability (DESIGN-NOTES 2.6): scale the drag impulse (J, L) by s so it can never add relative
    // kinetic energy nor reverse the relative motion. In the mass metric ⟨x,y⟩ = m_eff x_v·y_v + x_ω·I y_ω,
    // with a = −⟨Δ,V⟩/|V|² the explicit fraction removed, s = min(1/(1+a), a|V|²/|Δ|²): 1/(1+a) is the exact
    // solution v' = v/(1 + k|v|dt) of quadratic drag along a fixed direction; the second bound keeps
    // |V'|² ≤ |V|²(1 − s a) when Δ is not parallel to V.
    double s = 1.0;
    if (dragOn) {
        const Eigen::Vector3d J = dragF * dt, L = dragT * dt;
        const Eigen::Vector3d vr = v - uMean;
        const btMatrix3x3& basis = m_body->getWorldTransform().getBasis();
        const Eigen::Vector3d invI = toEigen(m_body->getInvInertiaDiagLocal());
        Eigen::Matrix3d R;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) R(i, j) = double(basis[i][j]);
        const Eigen::Vector3d wl = R.transpose() * w, Ll = R.transpose() * L;
        double rotE = 0, rotD = 0;
        for (int k = 0; k < 3; ++k) {
            if (invI[k] > 0) rotE += wl[k] * wl[k] / invI[k];
            rotD += invI[k] * Ll[k] * Ll[k];
        }
        const double V2 = meff * vr.squaredNorm() + rotE;
        const double D2 = J.squaredNorm() / meff + rotD;
        const double a = V2 > 0 ? -(J.dot(vr) + L.dot(w)) / V2 : 0.0;
        if (a > 0 && D2 > 0) s = std::min(1.0 / (1.0 + a), a * V2 / D2);
    }
    dragF *= s;
    dragT *= s;

    // Priming: the body's velocity is meant as the velocity after every kick at its current pose, but in
    // the first substep after creation or wake-up Bullet applied gravity (and integrated) with no buoyancy
    // kick for the starting pose. Give that missed hydrostatic kick once (evaluated at the current pose),
    // else a neutrally buoyant body keeps the −g·dt it got and drifts (DESIGN-NOTES 3, symplectic Euler).
    const double prime = m_needsPrime ? 2.0 : 1.0;
    const Eigen::Vector3d linearImpulse =
        (m / meff) * ((prime * (h.force - ma * gravityAcc) + dragF) * dt);
    const Eigen::Vector3d angularImpulse = (prime * h.torque + dragT) * dt;

    m_result.submergedVolume = h.submerged_volume;
    m_result.centreOfBuoyancy = toBullet(h.centre_of_buoyancy);
    m_result.buoyancyForce = toBullet(h.force);
    m_result.buoyancyTorque = toBullet(h.torque);
    m_result.dragForce = toBullet(dragF);
    m_result.dragTorque = toBullet(dragT);
    m_result.wettedArea = h.wetted_area;
    m_result.waterlineArea = h.waterline_area;
    m_result.addedMass = ma;
    m_result.time = time;
    // Never write NaN/Inf into a body (DESIGN-NOTES 3): checked after rounding to btScalar (a finite double
    // can overflow a float) and on the velocities the impulses would give.
    const btVector3 J = toBullet(linearImpulse), L = toBullet(angularImpulse);
    const btVector3 v1 = m_body->getLinearVelocity() + J * m_body->getInvMass() * m_body->getLinearFactor();
    const btVector3 w1 = m_body->getAngularVelocity() + m_body->getInvInertiaTensorWorld() * L * m_body->getAngularFactor();
    if (!linearImpulse.allFinite() || !angularImpulse.allFinite() || !toEigen(v1).allFinite() ||
        !toEigen(w1).allFinite()) {
        ++m_rejected;
        return;
    }
    // Sleeping (see m_baseLinearSleep): at rest when the COM really moved less than the body's threshold over
    // this substep and it turns slower than its angular threshold; Bullet then counts down to sleep as usual.
    const bool atRest = m_hasLastCom && (com - m_lastCom).norm() < m_baseLinearSleep * dt &&
                        toEigen(m_body->getAngularVelocity()).norm() < m_baseAngularSleep;
    m_lastCom = com;
    m_hasLastCom = true;
    const btScalar open = atRest ? btScalar(1e6) : btScalar(0);
    m_body->setSleepingThresholds(open, open);
    m_body->applyCentralImpulse(J);
    m_body->applyTorqueImpulse(L);
    m_result.applied = true;
    m_needsPrime = false;
    BT_BUOYANCY_CHECK_BODY(*m_body);
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
