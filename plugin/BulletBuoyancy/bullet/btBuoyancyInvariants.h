#pragma once
/// @file btBuoyancyInvariants.h
/// Invariants of a rigid body that the buoyancy coupling must never break (design.md 3:
/// "never write NaN/Inf into a body"): finite pose and velocities, an orthonormal basis, and for a dynamic
/// body a mass > 0 and a positive-definite inertia. Used by the tests after every substep and, in debug
/// builds, by btBuoyancyAction after it applies its impulses (BT_BUOYANCY_CHECK_BODY).
#include <LinearMath/btVector3.h>

#include <string>

class btRigidBody;

/// Largest principal moment of inertia a dynamic body may have with single-precision Bullet, kg·m². Bullet's implicit
/// gyroscopic step (on for every body by default) solves a 3×3 system whose cross products grow like I²; above
/// ≈ 1.8e19 kg·m² they overflow float (3.4e38) and the body's state turns NaN in its first step (measured: a 10 km
/// cube of 500 kg/m³, I ≈ 8e21). 1e18 keeps a factor of 300 on I². It is a solid cube of 1000 kg/m³ about 1.4 km
/// across, of 20,000 kg/m³ about 800 m, of 1 kg/m³ about 6 km. Double-precision Bullet has no such limit in the
/// sizes this library accepts (coordinates up to 1e6 m).
constexpr double btBuoyancyMaxSinglePrecisionInertia = 1e18;

/// Empty when a dynamic body with principal moments `localInertia` (kg·m²) can be simulated by this build's Bullet;
/// else the reason and the way out, naming `what` (e.g. "bodies[0]"): beyond btBuoyancyMaxSinglePrecisionInertia in a
/// single-precision build.
std::string btBuoyancyCheckInertiaRange(const btVector3& localInertia, const std::string& what);

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
#define BT_BUOYANCY_CHECK_BODY(body) ((void)sizeof(body))  // unevaluated: the argument counts as used
#endif

/// Used by BT_BUOYANCY_CHECK_BODY: prints the broken invariant with file and line, then aborts.
void btBuoyancyAssertBody(const btRigidBody& body, const char* file, int line);
