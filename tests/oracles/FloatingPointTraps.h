#pragma once
/// @file FloatingPointTraps.h
/// Shared by the tests: mask the floating-point traps that tests/test_main.cpp turns on in the CI's FPE run.

namespace buoyancy_test {

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

}  // namespace buoyancy_test
