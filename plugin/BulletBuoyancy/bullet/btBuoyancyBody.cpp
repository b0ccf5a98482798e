#include <BulletBuoyancy/bullet/btBuoyancyBody.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>

const btTransform& btBuoyancyRigidBody::getWorldTransform() const { return m_body->getWorldTransform(); }
const btVector3& btBuoyancyRigidBody::getLinearVelocity() const { return m_body->getLinearVelocity(); }
const btVector3& btBuoyancyRigidBody::getAngularVelocity() const { return m_body->getAngularVelocity(); }
btScalar btBuoyancyRigidBody::getInvMass() const { return m_body->getInvMass(); }
const btVector3& btBuoyancyRigidBody::getInvInertiaDiagLocal() const { return m_body->getInvInertiaDiagLocal(); }
const btMatrix3x3& btBuoyancyRigidBody::getInvInertiaTensorWorld() const { return m_body->getInvInertiaTensorWorld(); }
const btVector3& btBuoyancyRigidBody::getGravity() const { return m_body->getGravity(); }
const btVector3& btBuoyancyRigidBody::getLinearFactor() const { return m_body->getLinearFactor(); }
const btVector3& btBuoyancyRigidBody::getAngularFactor() const { return m_body->getAngularFactor(); }
const btVector3& btBuoyancyRigidBody::getTotalForce() const { return m_body->getTotalForce(); }
const btVector3& btBuoyancyRigidBody::getTotalTorque() const { return m_body->getTotalTorque(); }
bool btBuoyancyRigidBody::isInWorld() const { return m_body->getBroadphaseHandle() != nullptr; }
bool btBuoyancyRigidBody::isActive() const { return m_body->isActive(); }
btScalar btBuoyancyRigidBody::getLinearSleepingThreshold() const { return m_body->getLinearSleepingThreshold(); }
btScalar btBuoyancyRigidBody::getAngularSleepingThreshold() const { return m_body->getAngularSleepingThreshold(); }

void btBuoyancyRigidBody::applyCentralImpulses(const btVector3& linearImpulse, const btVector3& angularImpulse) {
    m_body->applyCentralImpulse(linearImpulse);
    m_body->applyTorqueImpulse(angularImpulse);
}

void btBuoyancyRigidBody::activate(bool forceActivation) { m_body->activate(forceActivation); }

void btBuoyancyRigidBody::setSleepingThresholds(btScalar linear, btScalar angular) {
    m_body->setSleepingThresholds(linear, angular);
}

void btBuoyancyRigidBody::setMassProps(btScalar mass, const btVector3& localInertia) {
    m_body->setMassProps(mass, localInertia);
    m_body->updateInertiaTensor();
}

const btCollisionObject* btBuoyancyRigidBody::getCollisionObject() const { return m_body; }
