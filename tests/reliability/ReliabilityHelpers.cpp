#include "reliability/ReliabilityHelpers.h"

#include <fstream>
#include <unistd.h>

namespace reliability_test {

std::size_t residentBytes() {
    std::ifstream in("/proc/self/statm");
    std::size_t size = 0, resident = 0;
    in >> size >> resident;
    return resident * std::size_t(::sysconf(_SC_PAGESIZE));
}

}  // namespace reliability_test
