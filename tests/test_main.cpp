// Catch2 main shared by every test executable.
//
// Floating-point traps (the CI's FPE run): when built with -DBULLET_BUOYANCY_TRAP_FP=ON, or when
// the environment has BULLET_BUOYANCY_TRAP_FP=1, the exceptions invalid, divide-by-zero and overflow raise
// SIGFPE from the first test on, so a NaN or Inf produced anywhere fails the test at the instruction that
// made it (run the test under gdb to see where). Underflow and inexact stay masked: they are normal in
// physics code. glibc only (feenableexcept).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cfenv>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

bool trapRequested() {
#if defined(BULLET_BUOYANCY_TRAP_FP)
    return true;
#else
    const char* env = std::getenv("BULLET_BUOYANCY_TRAP_FP");
    return env && std::strcmp(env, "1") == 0;
#endif
}

}  // namespace

int main(int argc, char* argv[]) {
    if (trapRequested()) {
#if defined(__GLIBC__)
        std::feclearexcept(FE_ALL_EXCEPT);
        feenableexcept(FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW);
#else
        std::fprintf(stderr, "BULLET_BUOYANCY_TRAP_FP: floating-point traps need glibc's feenableexcept\n");
        return 2;
#endif
    }
    return Catch::Session().run(argc, argv);
}
