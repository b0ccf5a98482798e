#include <BulletBuoyancy/bullet/btMarineHydrodynamics.h>

#include <BulletBuoyancy/bullet/btBulletConvert.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace {

const char* const kDof[6] = {"surge", "sway", "heave", "roll", "pitch", "yaw"};

std::string num(double x) {
    std::ostringstream s;
    s.precision(9);
    s << x;
    return s.str();
}

buoyancy::Matrix6d toMatrix(const std::array<double, 36>& a) {
    buoyancy::Matrix6d m;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) m(i, j) = a[std::size_t(6 * i + j)];
    return m;
}

std::array<double, 36> toArray(const buoyancy::Matrix6d& m) {
    std::array<double, 36> a{};
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) a[std::size_t(6 * i + j)] = m(i, j);
    return a;
}

Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
    Eigen::Matrix3d s;
    s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
    return s;
}

void checkFinite(const double* a, int n, int cols, const char* field) {
    for (int k = 0; k < n; ++k)
        if (!std::isfinite(a[k]))
            throw std::invalid_argument(std::string("btMarineHydrodynamics.") + field + "[" + std::to_string(k / cols) +
                                        (cols > 1 ? "][" + std::to_string(k % cols) : std::string()) +
                                        "]: not finite (" + num(a[k]) + ")");
}

/// Smallest eigenvalue of the symmetric part of m, and the scale (largest |entry|) it is compared with.
double smallestEigenvalue(const buoyancy::Matrix6d& m, double& scale) {
    scale = m.cwiseAbs().maxCoeff();
    if (!(scale > 0)) return 0.0;
    const buoyancy::Matrix6d s = 0.5 * (m / scale + (m / scale).transpose());  // normalised: no overflow
    Eigen::SelfAdjointEigenSolver<buoyancy::Matrix6d> eig(s, Eigen::EigenvaluesOnly);
    return eig.eigenvalues().minCoeff() * scale;
}

}  // namespace

void btMarineHydrodynamics::validate() const {
    checkFinite(addedMass.data(), 36, 6, "addedMass");
    checkFinite(linearDamping.data(), 36, 6, "linearDamping");
    checkFinite(quadraticDamping.data(), 6, 1, "quadraticDamping");
    const buoyancy::Matrix6d ma = toMatrix(addedMass), dl = toMatrix(linearDamping);
    const double maScale = ma.cwiseAbs().maxCoeff();
    for (int i = 0; i < 6; ++i)
        for (int j = i + 1; j < 6; ++j)
            if (!(std::abs(ma(i, j) - ma(j, i)) <= 1e-9 * maScale))
                throw std::invalid_argument("btMarineHydrodynamics.addedMass: not symmetric ([" + std::to_string(i) +
                                            "][" + std::to_string(j) + "] = " + num(ma(i, j)) + ", [" +
                                            std::to_string(j) + "][" + std::to_string(i) + "] = " + num(ma(j, i)) + ")");
    double scale = 0;
    if (const double e = smallestEigenvalue(ma, scale); !(e >= -1e-9 * scale))
        throw std::invalid_argument("btMarineHydrodynamics.addedMass: not positive semidefinite (smallest eigenvalue " +
                                    num(e) + "); entries are −X_u̇ etc., ≥ 0 on the diagonal");
    for (int i = 0; i < 6; ++i)
        if (!(dl(i, i) >= 0))
            throw std::invalid_argument("btMarineHydrodynamics.linearDamping[" + std::to_string(i) + "][" +
                                        std::to_string(i) + "] (" + kDof[i] + "): negative (" + num(dl(i, i)) +
                                        "); damping coefficients are ≥ 0 (Fossen's derivatives X_u etc. are ≤ 0: "
                                        "negate them)");
    if (const double e = smallestEigenvalue(dl, scale); !(e >= -1e-9 * scale))
        throw std::invalid_argument("btMarineHydrodynamics.linearDamping: not dissipative (its symmetric part has the "
                                    "eigenvalue " + num(e) + " < 0)");
    for (int i = 0; i < 6; ++i)
        if (!(quadraticDamping[std::size_t(i)] >= 0))
            throw std::invalid_argument("btMarineHydrodynamics.quadraticDamping[" + std::to_string(i) + "] (" + kDof[i] +
                                        "): negative (" + num(quadraticDamping[std::size_t(i)]) +
                                        "); damping coefficients are ≥ 0 (Fossen's X_|u|u etc. are ≤ 0: negate them)");
    const Eigen::Isometry3d frame = buoyancy::toEigen(referenceFrame);
    const Eigen::Matrix3d Q = frame.linear();
    const Eigen::Vector3d o = frame.translation();
    if (!Q.allFinite() || !o.allFinite())
        throw std::invalid_argument("btMarineHydrodynamics.referenceFrame: not finite");
    const double orthogonality = (Q.transpose() * Q - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (!(orthogonality <= 1e-4) || !(Q.determinant() > 0))
        throw std::invalid_argument("btMarineHydrodynamics.referenceFrame: rotation not proper (|QᵀQ − I| = " +
                                    num(orthogonality) + ", det = " + num(Q.determinant()) + ")");
}

std::array<double, 36> btMarineHydrodynamics::diagonalMatrix(const std::array<double, 6>& diagonal) {
    std::array<double, 36> a{};
    for (std::size_t i = 0; i < 6; ++i) a[7 * i] = diagonal[i];
    return a;
}

btMarineHydrodynamics btMarineHydrodynamics::fromDerivatives(const std::array<double, 6>& addedMassDerivatives,
                                                             const std::array<double, 6>& linearDerivatives,
                                                             const std::array<double, 6>& quadraticDerivatives) {
    // Fossen's sign convention: the derivatives of a passive body are ≤ 0, the matrices their negatives.
    btMarineHydrodynamics h;
    h.enabled = true;
    std::array<double, 6> ma{}, dl{};
    for (std::size_t i = 0; i < 6; ++i) {
        ma[i] = -addedMassDerivatives[i];
        dl[i] = -linearDerivatives[i];
        h.quadraticDamping[i] = -quadraticDerivatives[i];
    }
    h.addedMass = diagonalMatrix(ma);
    h.linearDamping = diagonalMatrix(dl);
    return h;
}

std::array<double, 36> btMarineHydrodynamics::toParentFrame(const std::array<double, 36>& matrix,
                                                            const btTransform& frame) {
    const Eigen::Isometry3d f = buoyancy::toEigen(frame);
    const buoyancy::Matrix6d J = buoyancy::marineFrameJacobian(f.linear(), f.translation());
    return toArray(J.transpose() * toMatrix(matrix) * J);
}

namespace buoyancy {

Matrix6d marineFrameJacobian(const Eigen::Matrix3d& Q, const Eigen::Vector3d& o) {
    // The frame's origin moves at v_o = v + ω × o = v − S(o) ω; both parts are then read in the frame's axes.
    Matrix6d J = Matrix6d::Zero();
    J.topLeftCorner<3, 3>() = Q.transpose();
    J.topRightCorner<3, 3>() = -Q.transpose() * skew(o);
    J.bottomRightCorner<3, 3>() = Q.transpose();
    return J;
}

Vector6d marineStep(const MarineStepInput& in) {
    // design.md 2.10. World frame, [linear; angular] about the centre of mass.
    const double dt = in.dt;
    Matrix6d T = Matrix6d::Zero(), Tp = Matrix6d::Zero();
    T.topLeftCorner<3, 3>() = T.bottomRightCorner<3, 3>() = in.rotation;
    Tp.topLeftCorner<3, 3>() = Tp.bottomRightCorner<3, 3>() = in.previousRotation;
    const Matrix6d maNow = T * in.addedMass * T.transpose();
    const Matrix6d maPrev = Tp * in.addedMass * Tp.transpose();
    Matrix6d mrb = Matrix6d::Zero();
    mrb.topLeftCorner<3, 3>() = in.mass * Eigen::Matrix3d::Identity();
    mrb.bottomRightCorner<3, 3>() = in.inertia;
    Vector6d u = Vector6d::Zero(), up = Vector6d::Zero();
    u.head<3>() = in.current;
    up.head<3>() = in.previousCurrent;

    // The added momentum at the start of the step, in the body's axes of then (Fossen's C_A: turning it with the body
    // is the ω × p and ω × h part).
    const Vector6d pOld = maPrev * (in.startVelocity - up);
    const Vector6d base = mrb * in.bulletVelocity + pOld + maNow * u + in.impulse;
    const Matrix6d M = mrb + maNow;

    // Damping in the reference frame, y = A (ν − u): implicit. Linear only: one factorisation for every pass below.
    // With the quadratic term: Newton on f(ν) = M ν + dt Aᵀ (D_l y + D_q |y| y) − rhs, whose Jacobian
    // M + dt Aᵀ (D_l + 2 D_q |y|) A is positive definite (f is the gradient of a strictly convex function when D_l's
    // symmetric part is ≥ 0), started from the step with |y| lagged at ν_B or from the previous pass's solution.
    const Matrix6d A = in.reference * T.transpose();
    const bool quadratic = in.quadraticDamping.cwiseAbs().maxCoeff() > 0;
    const Matrix6d AtDlA = dt * A.transpose() * in.linearDamping * A;
    Eigen::PartialPivLU<Matrix6d> linearLu;
    if (!quadratic) linearLu.compute(M + AtDlA);
    auto solve = [&](const Vector6d& rhs, const Vector6d* warm) -> Vector6d {
        if (!quadratic) return linearLu.solve(rhs + AtDlA * u);
        Vector6d nu;
        if (warm) {
            nu = *warm;
        } else {
            const Vector6d lag = A * (in.bulletVelocity - u);
            const Matrix6d D = in.linearDamping + Matrix6d(in.quadraticDamping.cwiseProduct(lag.cwiseAbs()).asDiagonal());
            const Matrix6d AtDA = dt * A.transpose() * D * A;
            nu = (M + AtDA).partialPivLu().solve(rhs + AtDA * u);
        }
        for (int it = 0; it < 8 && nu.allFinite(); ++it) {
            const Vector6d y = A * (nu - u);
            const Vector6d f = M * nu +
                               dt * A.transpose() *
                                   (in.linearDamping * y + in.quadraticDamping.cwiseProduct(y.cwiseAbs().cwiseProduct(y))) -
                               rhs;
            const Matrix6d Jf =
                M + AtDlA + dt * A.transpose() * Matrix6d((2.0 * in.quadraticDamping.cwiseProduct(y.cwiseAbs())).asDiagonal()) * A;
            const Vector6d step = Jf.partialPivLu().solve(f);
            if (!step.allFinite()) break;
            nu -= step;
            if (step.norm() <= 1e-10 * (nu.norm() + 1e-30)) break;  // far below the step's O(dt) error
        }
        return nu;
    };
    // The Munk moment −v_r × p at the end of the step (design.md 2.10), by fixed point: a first solve with the start's
    // v and p, then again with the end's until they agree. The linear rows do not depend on ω without coupling blocks
    // (and without damping at an offset point): then the second solve is the answer; at most three more otherwise.
    auto withMunk = [&](const Eigen::Vector3d& munk, const Vector6d* warm) {
        Vector6d rhs = base;
        rhs.tail<3>() += dt * munk;
        return solve(rhs, warm);
    };
    auto munkAt = [&](const Vector6d& nu) -> Eigen::Vector3d {
        const Vector6d p = maNow * (nu - u);
        return -(nu.head<3>() - in.current).cross(Eigen::Vector3d(p.head<3>()));
    };
    Eigen::Vector3d munk = -(in.startVelocity.head<3>() - in.previousCurrent).cross(Eigen::Vector3d(pOld.head<3>()));
    Vector6d nu = withMunk(munk, nullptr);
    for (int pass = 0; pass < 4 && nu.allFinite(); ++pass) {
        const Eigen::Vector3d next = munkAt(nu);
        if (!((next - munk).norm() > 1e-12 * (next.norm() + munk.norm()))) break;  // consistent (or not finite)
        munk = next;
        nu = withMunk(munk, &nu);
    }
    return nu;
}

}  // namespace buoyancy
