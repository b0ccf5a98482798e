#include "benchmark/BenchSeas.h"

#include "benchmark/Scaling.h"

namespace buoyancy::bench {

std::vector<btGerstnerWave> chopSea() {
    std::vector<btGerstnerWave> w(4);
    //       A     λ     d_x   d_z    Q     φ
    w[0] = {0.30, 10.0, 1.0, 0.0, 0.60, 0.3};
    w[1] = {0.22, 7.0, 0.6, 0.8, 0.65, 1.7};
    w[2] = {0.16, 5.5, -0.5, 0.866, 0.70, 4.0};
    w[3] = {0.12, 4.0, 0.8, -0.6, 0.70, 2.6};
    return w;
}

std::vector<BenchSea> benchSeas() { return {{"swell", p3Sea()}, {"chop", chopSea()}}; }

}  // namespace buoyancy::bench
