#pragma once
/// @file FuzzContract.h
/// What every libFuzzer target of fuzz/ shares: how a broken contract is reported, so that
/// scripts/fuzz-run.sh can tell it from a crash ("contract violated: ..." then abort, libFuzzer keeps the
/// input in its artifacts).

#include <cstdio>
#include <cstdlib>

namespace buoyancy::fuzz {

/// Report a broken contract of our code on stderr and abort (the fuzzer saves the input).
[[noreturn]] inline void violated(const char* what) {
    std::fprintf(stderr, "contract violated: %s\n", what);
    std::abort();
}

}  // namespace buoyancy::fuzz
