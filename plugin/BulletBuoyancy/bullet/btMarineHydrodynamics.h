#pragma once
/// @file btMarineHydrodynamics.h
/// Marine-robotics hydrodynamics of one rigid body in Fossen's form (T. I. Fossen, "Handbook of Marine Craft
/// Hydrodynamics and Motion Control", Wiley 2011, ch. 6–7): a 6×6 added-mass matrix M_A, a linear damping
/// matrix D_l and a diagonal quadratic damping D_q, all in a body-fixed frame, with the added mass's Coriolis and
/// centripetal forces C_A(ν_r)ν_r. Opt-in per body (btBuoyancyAction::setMarineHydrodynamics); how it is integrated
/// with Bullet is design.md 2.10, how to fill it from a vehicle's datasheet docs/integration.md "Marine hydrodynamics".

#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

#include <Eigen/Core>

#include <array>

/// Per-body added mass and damping matrices (Fossen's model), in the generalized velocity ν = [u v w p q r] of the
/// reference frame: the linear velocity of its origin and the angular velocity, both in its axes (m/s, rad/s).
/// Forces and moments are [X Y Z K M N] (N, N·m) about that origin in the same axes. Matrices are row-major 6×6.
///
/// The hydrodynamic force applied is
///   τ = −M_A ν̇_r − C_A(ν_r) ν_r − D_l ν_r − D_q |ν_r| ν_r,   ν_r = ν − [u_water; 0]
/// (Fossen 2011 ch. 6 for M_A, C_A and the damping, ch. 7 for the equations with a current; his sign convention: the
/// matrices are ≥ 0, the hydrodynamic derivatives
/// of a datasheet ≤ 0, M_A = −[X_u̇ …], D_l = −[X_u …], D_q = −diag(X_|u|u, …); fromDerivatives negates them).
/// Every coefficient is the fully submerged body's: a body at the surface gets them scaled by its submerged fraction
/// (scaleBySubmergedFraction).
struct btMarineHydrodynamics {
    /// Off (default): the body's motion is exactly the library's without this model, at no cost.
    bool enabled = false;

    /// M_A, row-major 6×6 in the reference frame about its origin: kg (linear block), kg·m (coupling blocks),
    /// kg·m² (angular block). Symmetric and positive semidefinite (M_RB + M_A is then positive definite). A fully
    /// submerged sphere of volume V: ½ ρ V on the linear diagonal, 0 elsewhere.
    std::array<double, 36> addedMass{};
    /// D_l, row-major 6×6 in the reference frame: N·s/m (linear block), N·s (coupling blocks), N·m·s (angular
    /// block). Need not be symmetric (lift terms such as Y_r, N_v), but its diagonal must be ≥ 0 and its symmetric
    /// part positive semidefinite (it never adds energy).
    std::array<double, 36> linearDamping{};
    /// Diagonal of D_q in the reference frame, each ≥ 0: N·s²/m² (surge, sway, heave), N·m·s² (roll, pitch, yaw);
    /// the force of degree of freedom i is −D_q[i] |ν_r,i| ν_r,i (Fossen's |ν|ν form, no cross terms).
    std::array<double, 6> quadraticDamping{};
    /// The frame the matrices are given in (its origin is the reference point, e.g. the vehicle's centre of origin
    /// CO or its centre of gravity), as a pose in the body's mesh frame (btBuoyancyAction::getMeshInComFrame maps
    /// that to Bullet's centre-of-mass frame; for a body built from its own collision shape both are the body's
    /// frame). Identity (default): the matrices are about the centre of mass in the body's axes. Rotation must be
    /// proper (orthonormal, determinant +1). A datasheet in Fossen's axes (x forward, y starboard, z down) on a body
    /// modelled x forward, y up: basis columns (1,0,0), (0,0,1), (0,−1,0) (docs/integration.md).
    btTransform referenceFrame = btTransform::getIdentity();
    /// Relative velocity ν_r against the water's velocity (btWaterSurface::velocities) at the body's centre of mass,
    /// queried once per substep (currents, orbital velocity of waves); false: against still water.
    bool useWaterVelocity = true;
    /// Scale every coefficient by the body's submerged volume fraction (0 out of the water, 1 fully submerged): a
    /// crude but continuous rule for bodies crossing the surface. false: full coefficients whenever the body is
    /// evaluated in the water (its bounding sphere reaches it). With btBuoyancySettings::buoyancyEnabled false no
    /// volume is computed and the full coefficients apply.
    bool scaleBySubmergedFraction = true;

    /// Check every field. @throws std::invalid_argument whose message names the field (and entry) and the value:
    /// a non-finite entry; an added-mass matrix that is not symmetric (relative 1e-9) or not positive semidefinite;
    /// a negative damping coefficient (linear diagonal or quadratic); a linear damping whose symmetric part is not
    /// positive semidefinite; a reference frame that is not finite or whose rotation is not proper (1e-4)
    void validate() const;

    /// A row-major 6×6 matrix with `diagonal` on its diagonal (units of the diagonal's entries).
    static std::array<double, 36> diagonalMatrix(const std::array<double, 6>& diagonal);

    /// Fill from a datasheet's hydrodynamic derivatives in Fossen's sign convention (each ≤ 0 for a passive body):
    /// M_A = −diag(X_u̇, Y_v̇, Z_ẇ, K_ṗ, M_q̇, N_ṙ), D_l = −diag(X_u, Y_v, Z_w, K_p, M_q, N_r),
    /// D_q = −(X_|u|u, Y_|v|v, Z_|w|w, K_|p|p, M_|q|q, N_|r|r). enabled = true; the other fields are the defaults.
    /// @param addedMassDerivatives      X_u̇, Y_v̇, Z_ẇ (kg), K_ṗ, M_q̇, N_ṙ (kg·m²)
    /// @param linearDerivatives         X_u, Y_v, Z_w (N·s/m), K_p, M_q, N_r (N·m·s)
    /// @param quadraticDerivatives      X_|u|u, Y_|v|v, Z_|w|w (N·s²/m²), K_|p|p, M_|q|q, N_|r|r (N·m·s²)
    static btMarineHydrodynamics fromDerivatives(const std::array<double, 6>& addedMassDerivatives,
                                                 const std::array<double, 6>& linearDerivatives,
                                                 const std::array<double, 6>& quadraticDerivatives);

    /// A 6×6 matrix given in `frame` about its origin (added mass or linear damping), expressed in the parent frame
    /// about the parent's origin: Jᵀ M J with ν_frame = J ν_parent, J = [[Qᵀ, −Qᵀ S(o)], [0, Qᵀ]] (Q the frame's
    /// rotation, o its origin, S the cross-product matrix; Fossen 2011 ch. 3's system transformation H(r)). Kinetic energy
    /// and power are the same in both. E.g. coefficients given about the centre of origin CO, with the centre of
    /// gravity at r_g from CO: toParentFrame(M, btTransform(identity, −r_g)) gives them about the CG.
    /// @param matrix  row-major 6×6 in `frame`
    /// @param frame   the frame's pose in the parent (origin in m)
    static std::array<double, 36> toParentFrame(const std::array<double, 36>& matrix, const btTransform& frame);
};

namespace buoyancy {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// Internal: J with ν_frame = J ν_parent for a frame of rotation Q (columns: its axes in the parent) and origin o
/// (in the parent), m (btMarineHydrodynamics::toParentFrame).
Matrix6d marineFrameJacobian(const Eigen::Matrix3d& Q, const Eigen::Vector3d& o);

/// Internal: one substep of the marine model in the world frame (design.md 2.10). Vectors are [linear; angular]
/// about the body's centre of mass, world axes (m/s, rad/s; impulses N·s, N·m·s).
struct MarineStepInput {
    double dt = 0;                            ///< substep, s
    double mass = 0;                          ///< m, kg
    Eigen::Matrix3d inertia;                  ///< the body's inertia tensor, world axes, kg·m²
    Eigen::Matrix3d rotation;                 ///< body → world now
    Eigen::Matrix3d previousRotation;         ///< body → world at the start of the step (the previous substep's end)
    Matrix6d addedMass;                       ///< M_A about the centre of mass, body axes (already scaled)
    Matrix6d linearDamping;                   ///< D_l in the reference frame (already scaled)
    Vector6d quadraticDamping;                ///< diag D_q in the reference frame (already scaled)
    Matrix6d reference;                       ///< J: ν_reference = J ν_body (marineFrameJacobian)
    Vector6d bulletVelocity;                  ///< ν_B: the velocity Bullet integrated the step with
    Vector6d startVelocity;                   ///< ν_i: the velocity the step started with (before Bullet's kicks)
    Eigen::Vector3d current;                  ///< water velocity now, m/s
    Eigen::Vector3d previousCurrent;          ///< water velocity at the start of the step, m/s
    Vector6d impulse;                         ///< the action's impulses for the next step (buoyancy, drag, weight)
};

/// Internal: the end-of-step velocity ν solving (design.md 2.10)
///   (M_RB + M_A(R)) ν + dt Aᵀ (D_l y + D_q |y| y) = M_RB ν_B + M_A(R_prev)(ν_i − u_prev) + M_A(R) u + K − dt [0; v_r × p]
/// with y = A (ν − u), A = J Tᵀ: implicit in the mass and the damping (Newton on the quadratic term), the added
/// momentum turned with the body (the rotational part of C_A) and the Munk moment −v_r × p at the end-of-step velocity
/// (fixed point).
Vector6d marineStep(const MarineStepInput& in);

}  // namespace buoyancy
