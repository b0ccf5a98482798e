#pragma once
/// @file OpenClTestSupport.h
/// Shared helpers of tests/opencl: a backend for a world (or a clean skip when there is no device), and the
/// per-substep CPU-vs-device comparison of one world's actions at identical states.

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btOpenClBuoyancyBackend.h>

#include <btBulletDynamicsCommon.h>

#include <cstdint>
#include <string>
#include <vector>

namespace buoyancy_test {

/// True (after a WARN) in builds where device tests must not run (AddressSanitizer: the driver is not leak-clean).
bool deviceTestsDisabled();

/// Install an OpenCL backend of the given precision on `world` (the world owns it) and return it, or return
/// nullptr after a WARN naming why (the caller returns: a clean skip on machines without OpenCL, or whose
/// device lacks cl_khr_fp64 for Double). Kernels are built once per process (the backend caches them).
btOpenClBuoyancyBackend* installTestBackend(btBuoyancyWorld& world, btOpenClOptions::Precision precision);

/// Evaluate one substep of dt at the bodies' current states twice, restoring every body's velocities and the
/// water clock in between so both see identical states: on the CPU (backend paused), then on the device.
/// @param[out] answered  hydrostatic answers the device gave in its run
void evaluateBoth(btDynamicsWorld& dynamics, btBuoyancyWorld& world, btOpenClBuoyancyBackend& backend, double dt,
                  std::vector<btBuoyancyResult>& cpu, std::vector<btBuoyancyResult>& device, std::uint64_t& answered);

/// Largest difference between two results: submerged volume relative to V, pressure and drag forces relative
/// to the weight scale W = ρ g V (N), pressure and drag torques relative to W·L (L: the body's size, m).
double resultDifference(const btBuoyancyResult& a, const btBuoyancyResult& b, double weight, double length, double volume);

}  // namespace buoyancy_test
