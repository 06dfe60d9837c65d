#include <unistd.h>
// specgen co-simulation harness for Verilator: generic over every generated configuration.
//
// Built with --prefix Vdut --top-module specgen_cosim_top: the adapter specgen writes for each
// unit, one set of port names for every interface mode (a combinational unit ignores clk).
// Protocol (little-endian, binary, batched): stdin carries 24-byte input records, one per
// clock cycle; stdout returns one 24-byte output record per input record. Per cycle:
// apply the inputs (clk low), settle, sample the outputs, then raise clk (posedge), so an
// input applied in cycle t shows at the outputs in cycle t + latency.
// With -DTRACE=1 a VCD of the whole run is written to the file named by $SPECGEN_VCD.
#include "Vdut.h"
#include "verilated.h"
#if TRACE
#include "verilated_vcd_c.h"
#endif
#include <cstdint>
#include <cstdio>
#include <cstdlib>

struct InRecord {            // 24 bytes
    uint32_t cos_g;
    uint16_t n, ks_r, ks_g, ks_b;
    uint8_t flags;           // bit 0: in_valid, 1: rst, 2: out_ready, 3: ks_load, 4: clk_en low
    uint8_t pad[3];
    uint64_t tag;
};
struct OutRecord {           // 24 bytes
    uint32_t intensity;
    uint16_t spec_r, spec_g, spec_b;
    uint8_t flags;           // bit 0: out_valid, 1: done, 2: in_ready, 3: idle
    uint8_t pad[5];
    uint64_t tag;
};
static_assert(sizeof(InRecord) == 24, "input record layout");
static_assert(sizeof(OutRecord) == 24, "output record layout");

static const size_t BATCH = 1 << 14;
static InRecord in_buf[BATCH];
static OutRecord out_buf[BATCH];

int main(int argc, char** argv) {
    VerilatedContext ctx;
    ctx.commandArgs(argc, argv);
    Vdut dut{&ctx};
#if TRACE
    ctx.traceEverOn(true);
    VerilatedVcdC vcd;
    dut.trace(&vcd, 99);
    const char* vcd_path = std::getenv("SPECGEN_VCD");
    vcd.open(vcd_path ? vcd_path : "specgen_trace.vcd");
    uint64_t time = 0;
#endif
    // results go to the original stdout; the design's own $display text to stderr
    FILE* data = fdopen(dup(1), "wb");
    if (!data || dup2(2, 1) < 0) return 5;
    dut.eval();  // runs the initial blocks: a missing or short table file stops here
    if (ctx.gotFinish()) {
        std::fprintf(stderr, "the design stopped the simulation with $finish before the first vector (its message is above)\n");
        return 4;
    }
    size_t count;
    while ((count = std::fread(in_buf, sizeof(InRecord), BATCH, stdin)) > 0) {
        for (size_t i = 0; i < count; i++) {
            const InRecord& in = in_buf[i];
            dut.in_valid = in.flags & 1;
            dut.cos_g = in.cos_g;
            dut.n = in.n;
            dut.ks_r = in.ks_r;
            dut.ks_g = in.ks_g;
            dut.ks_b = in.ks_b;
            dut.in_tag = in.tag;
            dut.rst = (in.flags >> 1) & 1;
            dut.out_ready = (in.flags >> 2) & 1;
            dut.ks_load = (in.flags >> 3) & 1;
            dut.clk_en = !((in.flags >> 4) & 1);
            dut.clk = 0;
            dut.eval();
#if TRACE
            vcd.dump(time++);
#endif
            OutRecord& out = out_buf[i];
            out.intensity = dut.intensity;
            out.spec_r = dut.spec_r;
            out.spec_g = dut.spec_g;
            out.spec_b = dut.spec_b;
            out.flags = (dut.out_valid & 1) | ((dut.done & 1) << 1) | ((dut.in_ready & 1) << 2) | ((dut.idle & 1) << 3);
            for (int k = 0; k < 5; k++) out.pad[k] = 0;
            out.tag = dut.out_tag;
            dut.clk = 1;
            dut.eval();
#if TRACE
            vcd.dump(time++);
#endif
        }
        if (std::fwrite(out_buf, sizeof(OutRecord), count, data) != count) return 3;
        std::fflush(data);
    }
#if TRACE
    vcd.close();
#endif
    dut.final();
    return 0;
}
