// The floor cosim is measured against (scripts/bench_cosim_ratio.sh): the unit's Verilator
// model evaluated on every (cos_g, n) of the exhaustive sweep, colours varied as cosim varies
// them, with no stimulus stream, no golden model and no checks — only a sum of the outputs so
// the compiler keeps the work. THREADS threads, each its own model on a share of the n.
// Built with: verilator --cc --exe --build -O3 ... -CFLAGS "-O2 -DF=.. -DN=.. -DB=.. -DTHREADS=2"
#include "Vdut.h"
#include "verilated.h"
#include <cstdint>
#include <cstdio>
#include <thread>
#include <vector>

static uint64_t sweep(uint32_t n_lo, uint32_t n_hi) {
    VerilatedContext ctx;
    Vdut top{&ctx};
    const uint32_t bmask = (1u << B) - 1;
    uint64_t acc = 0;
    top.in_valid = 1;
    for (uint32_t n = n_lo; n < n_hi; n++) {
        top.n = n;
        for (uint32_t c = 0; c <= (1u << F); c++) {
            top.cos_g = c;
            top.ks_r = (c + n * 3 + 1) & bmask;
            top.ks_g = (c + n * 5 + 2) & bmask;
            top.ks_b = (c + n * 7 + 3) & bmask;
            top.eval();
            acc += top.intensity + top.spec_r + top.spec_g + top.spec_b + top.done;
        }
    }
    return acc;
}

int main() {
    const uint32_t count = 1u << N;
    std::vector<std::thread> pool;
    std::vector<uint64_t> sums(THREADS);
    for (int t = 0; t < THREADS; t++) {
        pool.emplace_back([&, t] { sums[t] = sweep(count * t / THREADS, count * (t + 1) / THREADS); });
    }
    uint64_t acc = 0;
    for (int t = 0; t < THREADS; t++) {
        pool[t].join();
        acc += sums[t];
    }
    std::printf("%llu\n", (unsigned long long)acc);
    return 0;
}
