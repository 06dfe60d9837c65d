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
// With $SPECGEN_SWEEP set, stdin is not read: the harness makes the exhaustive sweep itself
// (cosim/stimulus.rs `Exhaustive`, cycle for cycle: the same formula here), and after each
// batch of output records writes a 64-bit digest of the inputs it applied, which specgen
// compares with its own (a sweep out of step with the checker's is an error, never a pass).
// With $SPECGEN_DIGEST set (0: a combinational unit, 1: a pipelined one), a batch returns no
// records, only a 64-bit digest of what was sampled (cosim/checking.rs `sample_hash`, the same
// steps): out_valid, and the outputs and tag of every cycle (0) or of the valid ones after the
// first reset (1). specgen digests what the golden model expects the same way; a batch that
// differs is run again with records, to find and describe the first mismatch.
// With -DTAGGED=0 (no tag) an output record is 12 bytes: no out_tag.
// With -DCLOCKED=0 (a combinational unit: no register, clk read by nothing) the rising edge
// is not evaluated: Verilator would run the whole datapath again for a clk nobody reads.
#include "Vdut.h"
#include "verilated.h"
#if TRACE
#include "verilated_vcd_c.h"
#endif
#include <cstdint>
#include <cstdio>
#ifndef CLOCKED
#define CLOCKED 1
#endif
#include <cstdlib>

struct InRecord {            // 24 bytes
    uint32_t cos_g;
    uint16_t n, ks_r, ks_g, ks_b;
    uint8_t flags;           // bit 0: in_valid, 1: rst, 2: out_ready, 3: ks_load, 4: clk_en low
    uint8_t pad[3];
    uint64_t tag;
};
#ifndef TAGGED
#define TAGGED 1
#endif
#if TAGGED
struct OutRecord {           // 24 bytes
    uint32_t intensity;
    uint16_t spec_r, spec_g, spec_b;
    uint8_t flags;           // bit 0: out_valid, 1: done, 2: in_ready, 3: idle
    uint8_t pad[5];
    uint64_t tag;
};
static_assert(sizeof(OutRecord) == 24, "output record layout");
#else
struct OutRecord {           // 12 bytes
    uint32_t intensity;
    uint16_t spec_r, spec_g, spec_b;
    uint8_t flags;
    uint8_t pad[1];
};
static_assert(sizeof(OutRecord) == 12, "output record layout");
#endif
static_assert(sizeof(InRecord) == 24, "input record layout");

static const size_t BATCH = 1 << 14;
static InRecord in_buf[BATCH];
static OutRecord out_buf[BATCH];

static uint64_t splitmix(uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

// The digest of one applied cycle folded into h (cosim/backend.rs `applied`, the same steps).
static inline uint64_t applied(uint64_t h, const InRecord& in) {
    uint64_t a = (uint64_t)in.cos_g | (uint64_t)in.n << 32 | (uint64_t)in.flags << 48;
    uint64_t b = (uint64_t)in.ks_r | (uint64_t)in.ks_g << 16 | (uint64_t)in.ks_b << 32;
    return ((h << 7 | h >> 57) ^ a) + (b ^ in.tag);
}

static inline uint64_t mix(uint64_t x) {
    x *= 0x9E3779B97F4A7C15ull;
    return x ^ (x >> 29);
}

// The hash of sampled cycle t (cosim/checking.rs `sample_hash`); a batch's digest is the sum.
static inline uint64_t sample_hash(uint64_t t, const OutRecord& o, uint64_t tag, bool compared) {
    const uint64_t valid = o.flags & 1, done = (o.flags >> 1) & 1;
    uint64_t w0 = valid, w1 = 0;
    if (compared) {
        w0 = valid | 2 | done << 2 | (uint64_t)o.intensity << 32;
        w1 = ((uint64_t)o.spec_r | (uint64_t)o.spec_g << 16 | (uint64_t)o.spec_b << 32) ^ (tag << 17 | tag >> 47);
    }
    return mix(mix(t ^ (w0 << 8 | w0 >> 56)) ^ w1);
}

// The exhaustive sweep (cosim/stimulus.rs `Exhaustive::cycle`).
struct Sweep {
    uint64_t f, b, n_bits, n_lo, n_hi, clocked, static_colour, settle, tag_bits, tail, drain;
    uint64_t row() const { return (1ull << f) + 1; }
    uint64_t lead() const { return clocked + static_colour + settle; }
    uint64_t sweep() const { return (n_hi - n_lo) * row(); }
    uint64_t tail_len() const { return tail ? 1ull << b : 0; }
    uint64_t len() const { return sweep() + lead() + tail_len() + drain; }
    uint64_t tag(uint64_t i) const {
        if (tag_bits == 0) return 0;
        return splitmix(i) & (tag_bits >= 64 ? ~0ull : (1ull << tag_bits) - 1);
    }
    InRecord cycle(uint64_t i) const {
        InRecord c = {};
        c.flags = 4;  // out_ready: the sweep never stalls
        const uint32_t bm = (1u << b) - 1;
        if (clocked && i == 0) { c.flags |= 2; return c; }
        if (static_colour && i == clocked) {
            c.ks_r = bm; c.ks_g = bm / 2 + 1; c.ks_b = bm < 1 ? bm : 1;
            c.flags |= 8;
            return c;
        }
        if (i < lead()) return c;
        uint64_t j = i - lead();
        if (j >= sweep() + tail_len()) return c;
        c.flags |= 1;
        c.tag = tag(i);
        if (j >= sweep()) {
            uint32_t code = (uint32_t)(j - sweep());
            c.n = (code * 7u) & ((1u << n_bits) - 1);
            c.cos_g = 1u << f;
            c.ks_r = code; c.ks_g = (code + 1) & bm; c.ks_b = (code + 2) & bm;
            return c;
        }
        at(c, i, (uint32_t)(j % row()), (uint32_t)(n_lo + j / row()));
        return c;
    }
    // cycle i, which is in the sweep at (cos_g, n), written field by field into c (a record
    // built aside and copied whole stalls on store forwarding)
    void at(InRecord& c, uint64_t i, uint32_t cos_g, uint32_t n) const {
        const uint32_t bm = (1u << b) - 1;
        c.cos_g = cos_g;
        c.n = (uint16_t)n;
        c.ks_r = (uint16_t)((cos_g + n) & bm);
        c.ks_g = (uint16_t)((cos_g + n * 3u + 85u) & bm);
        c.ks_b = (uint16_t)((cos_g + n * 7u + 170u) & bm);
        c.flags = 5;  // in_valid, out_ready
        c.pad[0] = c.pad[1] = c.pad[2] = 0;
        c.tag = tag(i);
    }
    // cycles from, from + 1, ... into out (at most max); returns how many: steps through the
    // sweep without a division a cycle
    size_t fill(uint64_t from, size_t max, InRecord* out) const {
        size_t k = 0;
        const uint64_t end = from + max < len() ? from + max : len();
        for (uint64_t i = from; i < end;) {
            if (i < lead() || i - lead() >= sweep()) {
                out[k++] = cycle(i++);
                continue;
            }
            uint64_t j = i - lead();
            uint32_t cos_g = (uint32_t)(j % row()), n = (uint32_t)(n_lo + j / row());
            const uint64_t stop = end < lead() + sweep() ? end : lead() + sweep();
            for (; i < stop; i++) {
                at(out[k++], i, cos_g, n);
                if (++cos_g == row()) cos_g = 0, n++;
            }
        }
        return k;
    }
};

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
    Sweep sweep = {};
    const char* spec = std::getenv("SPECGEN_SWEEP");
    const bool sweeping = spec != nullptr;
    if (sweeping) {
        unsigned long long v[11];
        if (std::sscanf(spec, "%llu %llu %llu %llu %llu %llu %llu %llu %llu %llu %llu", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5],
                        &v[6], &v[7], &v[8], &v[9], &v[10]) != 11) {
            std::fprintf(stderr, "SPECGEN_SWEEP is malformed: %s\n", spec);
            return 6;
        }
        sweep = Sweep{v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10]};
    }
    const char* digest_mode = std::getenv("SPECGEN_DIGEST");
    const bool digesting = digest_mode != nullptr;
    const bool pipelined = digesting && digest_mode[0] == '1';
    bool reset_seen = false;  // a pipelined unit's outputs mean nothing before its first reset
    uint64_t next = 0;   // the sweep's next cycle
    uint64_t cycle = 0;  // the batch's first cycle
    size_t count;
    for (;;) {
        if (sweeping) {
            count = sweep.fill(next, BATCH, in_buf);
            next += count;
        } else {
            count = std::fread(in_buf, sizeof(InRecord), BATCH, stdin);
        }
        if (count == 0) break;
        uint64_t h = 0, sampled = 0;
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
            OutRecord out;  // the sample: a record, or hashed (never stored and read back)
            out.intensity = dut.intensity;
            out.spec_r = dut.spec_r;
            out.spec_g = dut.spec_g;
            out.spec_b = dut.spec_b;
            out.flags = (dut.out_valid & 1) | ((dut.done & 1) << 1) | ((dut.in_ready & 1) << 2) | ((dut.idle & 1) << 3);
            for (size_t k = 0; k < sizeof(out.pad); k++) out.pad[k] = 0;
#if TAGGED
            out.tag = dut.out_tag;
            const uint64_t tag = out.tag;
#else
            const uint64_t tag = 0;
#endif
            if (digesting) {
                if (!pipelined || reset_seen) sampled += sample_hash(cycle + i, out, tag, !pipelined || (out.flags & 1));
                reset_seen |= (in.flags >> 1) & 1;
            } else {
                out_buf[i] = out;
                if (sweeping) h = applied(h, in);
            }
#if CLOCKED
            dut.clk = 1;
            dut.eval();
#endif
#if TRACE
            vcd.dump(time++);
#endif
        }
        cycle += count;
        if (digesting) {
            if (std::fwrite(&sampled, sizeof sampled, 1, data) != 1) return 3;
        } else {
            if (std::fwrite(out_buf, sizeof(OutRecord), count, data) != count) return 3;
            if (sweeping && std::fwrite(&h, sizeof h, 1, data) != 1) return 3;
        }
        std::fflush(data);
    }
#if TRACE
    vcd.close();
#endif
    dut.final();
    return 0;
}
