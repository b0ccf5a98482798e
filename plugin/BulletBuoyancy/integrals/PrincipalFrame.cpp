/// @file PrincipalFrame.cpp
/// Principal axes of an inertia tensor for Bullet's COM frame (declared in MassProperties.h;
/// design.md 2.1, last item).

#include <BulletBuoyancy/integrals/MassProperties.h>

#include <Eigen/Eigenvalues>
#include <stdexcept>

namespace buoyancy {

PrincipalFrame principalFrame(const Eigen::Matrix3d& inertia) {
    if (!inertia.allFinite()) throw std::invalid_argument("principalFrame: inertia tensor has non-finite entries");
    const double scale = inertia.cwiseAbs().maxCoeff();
    if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
        throw std::invalid_argument("principalFrame: inertia tensor is not symmetric");
    // Symmetrise exactly, then eigen-decompose (eigenvalues ascending, orthonormal eigenvectors).
    const Eigen::Matrix3d sym = 0.5 * (inertia + inertia.transpose());
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(sym);
    if (solver.info() != Eigen::Success) throw std::runtime_error("principalFrame: eigen-decomposition failed");
    PrincipalFrame f;
    f.rotation = solver.eigenvectors();
    f.moments = solver.eigenvalues();
    if (f.rotation.determinant() < 0) f.rotation.col(2) = -f.rotation.col(2);  // proper rotation, det +1
    return f;
}

}  // namespace buoyancy
