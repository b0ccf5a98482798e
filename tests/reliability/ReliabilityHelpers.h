#pragma once
/// @file ReliabilityHelpers.h
/// What the reliability tests add to the shared fixture tests/oracles/BulletTestWorld.h: a world
/// that checks every body's invariants after every substep, floating-point traps masked on purpose, and
/// the process's resident memory.

#include <BulletBuoyancy/bullet/btBuoyancyInvariants.h>
#include "oracles/BulletTestWorld.h"
#include "oracles/FloatingPointTraps.h"

#include <cstddef>

namespace reliability_test {

using buoyancy_test::makePose;

/// The shared fixture with btBuoyancyCheckBody run on every body after every substep (firstViolation()).
class CheckedWorld : public buoyancy_test::BulletTestWorld {
public:
    /// Flat water at y = 0.
    CheckedWorld() { checkInvariants(); }
    /// Water given by `surface` (not owned).
    explicit CheckedWorld(const btWaterSurface* surface) : BulletTestWorld(surface) { checkInvariants(); }
};

/// Floating-point traps masked on purpose (shared with the other tests: tests/oracles/FloatingPointTraps.h).
using buoyancy_test::ScopedFpTrapsOff;

/// Resident set size of this process, bytes (/proc/self/statm, field 2 × page size).
std::size_t residentBytes();

}  // namespace reliability_test
