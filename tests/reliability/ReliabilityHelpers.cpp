#include "reliability/ReliabilityHelpers.h"

#include <cfenv>
#include <fstream>
#include <unistd.h>

namespace reliability_test {

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

std::size_t residentBytes() {
    std::ifstream in("/proc/self/statm");
    std::size_t size = 0, resident = 0;
    in >> size >> resident;
    return resident * std::size_t(::sysconf(_SC_PAGESIZE));
}

}  // namespace reliability_test
