#include <BulletBuoyancy/bullet/btBuoyancyInvariants.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace {

bool finite(const btVector3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

std::string str(const btVector3& v) {
    std::ostringstream os;
    os << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
    return os.str();
}

}  // namespace

std::string btBuoyancyCheckBody(const btRigidBody& body, bool positiveInertia) {
    const btTransform& t = body.getWorldTransform();
    if (!finite(t.getOrigin())) return "position not finite " + str(t.getOrigin());
    const btMatrix3x3& R = t.getBasis();
    for (int i = 0; i < 3; ++i)
        if (!finite(R[i])) return "rotation not finite, row " + std::to_string(i) + " " + str(R[i]);
    // Orthonormality: R Rᵀ = I within btScalar rounding (Bullet renormalises through its quaternion).
    const double tol = sizeof(btScalar) == sizeof(float) ? 1e-3 : 1e-9;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const double d = double(R[i].dot(R[j])) - (i == j ? 1.0 : 0.0);
            if (std::abs(d) > tol) return "rotation not orthonormal: (R R^T - I)[" + std::to_string(i) + "][" +
                                          std::to_string(j) + "] = " + std::to_string(d);
        }
    if (!finite(body.getLinearVelocity())) return "linear velocity not finite " + str(body.getLinearVelocity());
    if (!finite(body.getAngularVelocity())) return "angular velocity not finite " + str(body.getAngularVelocity());
    const double invMass = double(body.getInvMass());
    if (!std::isfinite(invMass) || invMass < 0) return "inverse mass not finite and >= 0: " + std::to_string(invMass);
    if (invMass == 0) return {};  // static or kinematic: no mass or inertia to check
    const btVector3 invI = body.getInvInertiaDiagLocal();
    if (!finite(invI) || invI.x() < 0 || invI.y() < 0 || invI.z() < 0)
        return "local inverse inertia not finite and >= 0 " + str(invI);
    if (positiveInertia && !(invI.x() > 0 && invI.y() > 0 && invI.z() > 0))
        return "local inverse inertia not > 0 " + str(invI);
    const btMatrix3x3& W = body.getInvInertiaTensorWorld();
    for (int i = 0; i < 3; ++i) {
        if (!finite(W[i])) return "world inverse inertia not finite, row " + std::to_string(i) + " " + str(W[i]);
    }
    const double scale = std::max({double(invI.x()), double(invI.y()), double(invI.z())});
    if (scale == 0) return {};  // rotation locked on every axis
    for (int i = 0; i < 3; ++i)
        for (int j = i + 1; j < 3; ++j)
            if (std::abs(double(W[i][j]) - double(W[j][i])) > 1e-3 * scale)
                return "world inverse inertia not symmetric at (" + std::to_string(i) + "," + std::to_string(j) + ")";
    if (!positiveInertia) return {};
    // Sylvester's criterion on the (symmetric part of the) world inverse inertia.
    // Normalised by the largest local entry so the minors neither underflow nor overflow.
    const double a = W[0][0] / scale, b = 0.5 * (W[0][1] + W[1][0]) / scale, c = 0.5 * (W[0][2] + W[2][0]) / scale;
    const double d = W[1][1] / scale, e = 0.5 * (W[1][2] + W[2][1]) / scale, f = W[2][2] / scale;
    const double m1 = a, m2 = a * d - b * b, m3 = a * (d * f - e * e) - b * (b * f - e * c) + c * (b * e - d * c);
    // The local moments are already known > 0, so W = R diag(invI) Rᵀ is positive definite in exact
    // arithmetic; the minors only have to be clearly not negative (btScalar rounding of an ill-conditioned W).
    const double eps = sizeof(btScalar) == sizeof(float) ? 1e-5 : 1e-12;
    if (!(m1 > 0) || !(m2 > -eps) || !(m3 > -eps))
        return "world inverse inertia not positive definite (minors " + std::to_string(m1) + ", " + std::to_string(m2) +
               ", " + std::to_string(m3) + ")";
    return {};
}

void btBuoyancyAssertBody(const btRigidBody& body, const char* file, int line) {
    const std::string problem = btBuoyancyCheckBody(body, false);
    if (problem.empty()) return;
    std::fprintf(stderr, "%s:%d: rigid body invariant broken: %s\n", file, line, problem.c_str());
    std::abort();
}

std::string btBuoyancyCheckInertiaRange(const btVector3& localInertia, const std::string& what) {
    if (sizeof(btScalar) > sizeof(float)) return "";
    const double largest = std::max({double(localInertia.x()), double(localInertia.y()), double(localInertia.z())});
    if (!(largest > btBuoyancyMaxSinglePrecisionInertia)) return "";
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "%s: moment of inertia %.3g kg m^2 is beyond single-precision Bullet's range (at most %.0e kg m^2: a "
                  "solid cube of 1000 kg/m^3 about 1.4 km across; Bullet's gyroscopic step overflows float beyond "
                  "it): use a double-precision build (-DBULLET_BUOYANCY_DOUBLE_PRECISION=ON with Bullet's float64 "
                  "libraries) or a smaller or lighter body",
                  what.c_str(), largest, btBuoyancyMaxSinglePrecisionInertia);
    return buf;
}
