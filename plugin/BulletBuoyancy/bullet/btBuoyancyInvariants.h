#pragma once
/// @file btBuoyancyInvariants.h
/// Invariants of a rigid body that the buoyancy coupling must never break (design.md 3:
/// "never write NaN/Inf into a body"): finite pose and velocities, an orthonormal basis, and for a dynamic
/// body a mass > 0 and a positive-definite inertia. Used by the tests after every substep and, in debug
/// builds, by btBuoyancyAction after it applies its impulses (BT_BUOYANCY_CHECK_BODY).
#include <string>

class btRigidBody;

/// Check one body. Returns an empty string when every invariant holds, else a message naming the first
/// broken one and its value, e.g. "linear velocity not finite (nan, 0, 0)".
/// Checks: world transform finite with |R Rᵀ − I| ≤ 1e-3 (float) or 1e-9 (double) per entry; linear and
/// angular velocity finite; inverse mass finite and ≥ 0; for a dynamic body (inverse mass > 0) the local
/// inverse inertia diagonal finite and ≥ 0, the world inverse inertia tensor finite and symmetric; with
/// `positiveInertia` (bodies made by btBuoyantBody) also every local inverse moment > 0 and the world
/// inverse inertia positive definite (Sylvester: leading minors > 0, up to btScalar rounding). Without it a
/// zero inverse moment is allowed: Bullet users lock rotation axes that way.
std::string btBuoyancyCheckBody(const btRigidBody& body, bool positiveInertia = true);

/// Debug builds: abort with the message when btBuoyancyCheckBody(body, false) finds a broken invariant.
/// Release builds: nothing. btBuoyancyAction runs it after applying its impulses.
#ifndef NDEBUG
#define BT_BUOYANCY_CHECK_BODY(body) btBuoyancyAssertBody(body, __FILE__, __LINE__)
#else
#define BT_BUOYANCY_CHECK_BODY(body) ((void)0)
#endif

/// Used by BT_BUOYANCY_CHECK_BODY: prints the broken invariant with file and line, then aborts.
void btBuoyancyAssertBody(const btRigidBody& body, const char* file, int line);
