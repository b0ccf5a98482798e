#pragma once
/// @file ReliabilityHelpers.h
/// What the reliability tests (issue 10) add to the shared fixture tests/oracles/BulletTestWorld.h: a world
/// that checks every body's invariants after every substep, floating-point traps masked on purpose, and
/// the process's resident memory.

#include "bullet/btBuoyancyInvariants.h"
#include "oracles/BulletTestWorld.h"

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

/// Masks the floating-point traps of test_main.cpp (FPE build) for a test that feeds NaN or overflowing
/// values on purpose: comparing a NaN raises FE_INVALID even where the code handles it. Restores on exit.
class ScopedFpTrapsOff {
public:
    ScopedFpTrapsOff();
    ~ScopedFpTrapsOff();
    ScopedFpTrapsOff(const ScopedFpTrapsOff&) = delete;
    ScopedFpTrapsOff& operator=(const ScopedFpTrapsOff&) = delete;

private:
    int m_saved = 0;
};

/// Resident set size of this process, bytes (/proc/self/statm, field 2 × page size).
std::size_t residentBytes();

}  // namespace reliability_test
