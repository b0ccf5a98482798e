#include "oracles/FloatingPointTraps.h"

#include <cfenv>

namespace buoyancy_test {

ScopedFpTrapsOff::ScopedFpTrapsOff() {
#if defined(__GLIBC__)
    m_saved = fegetexcept();
    fedisableexcept(FE_ALL_EXCEPT);
#endif
}

ScopedFpTrapsOff::~ScopedFpTrapsOff() {
#if defined(__GLIBC__)
    std::feclearexcept(FE_ALL_EXCEPT);
    feenableexcept(m_saved);
#endif
}

}  // namespace buoyancy_test
