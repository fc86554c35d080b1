// phongfx fast check: drive the Verilated top `Vtop` (see fast_backend.wrapper) from a
// binary stream and compare its outputs with the expected ones, cycle by cycle.
//
// usage: phongfx_sim STREAM RESULT [VCD]   (VCD: a build with --trace only)
// STREAM: 16 little-endian uint64 (magic, cycles, in_words, out_words, max_report, mode, count,
//   junk_rows, latency, quiet_from, drain, 0 ...), then, in modes 0 (compare) and 1 (dump),
//   cycles x in_words uint32 input words {i.payload, i.valid} (least significant first),
//   then, in mode 0, cycles x out_words uint32 expected words {o.payload, o.valid}.
// RESULT, mode 0: uint64 (cycles, mismatch count, recorded), then per recorded mismatch
//   uint64 cycle, out_words uint32 got, out_words uint32 expected.
// RESULT, mode 1: cycles x out_words uint32 output words.
// Mode 2 (stream, phongfx.sim.harness.StreamChecker's twin: a Handshake top with
//   back-pressure and reset): `cycles` is the most cycles the run may take; after the header
//   count x in_words vector words, count x out_words expected words, junk_rows x in_words
//   idle payloads, count uint32 resume points (the vector to re-send from after a reset, per
//   first vector not delivered), then one control byte per cycle (READY, IDLE, RESET bits),
//   padded to 4.
//   RESULT: uint64 (cycles run, mismatch count, recorded, delivered, stall cycles, resets,
//   re-sent, 0), then per recorded mismatch uint64 cycle, kind, index (int64), out_words
//   uint32 got, out_words uint32 expected.
// Outputs of a cycle are read after its inputs settle and before its rising edge.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

#include "Vtop.h"
#include "verilated.h"
#if VM_TRACE
#include "verilated_vcd_c.h"
#endif

static const uint64_t MAGIC = 0x3274736166786670ULL;  // "pfxfast2"
static const uint64_t HEADER = 16;
// as phongfx.sim.harness READY, IDLE, RESET and VALID ... LOST
enum : uint8_t { READY = 1, IDLE = 2, RESET = 4 };
enum : uint64_t { VALID, PAYLOAD, HELD, EXTRA, LOST };

static int fail(const char* what) {
    std::fprintf(stderr, "phongfx_sim: %s\n", what);
    return 2;
}

// Waveform of a --trace build; without one, its calls compile to nothing.
struct Trace {
#if VM_TRACE
    VerilatedVcdC* vcd = nullptr;
    void open(Vtop& top, const char* path) {
        vcd = new VerilatedVcdC;
        top.trace(vcd, 99);
        vcd->open(path);
    }
    void dump(uint64_t time) {
        if (vcd) vcd->dump(time);
    }
    void close() {
        if (vcd) vcd->close();
    }
#else
    void open(Vtop&, const char*) {}
    void dump(uint64_t) {}
    void close() {}
#endif
};

// Mismatches of a run: their count, and the first `limit` of them in detail.
struct Report {
    uint64_t limit, no, count = 0;
    std::vector<uint64_t> meta;  // cycle (and, in mode 2, kind and index) per record
    std::vector<uint32_t> words;  // got, then expected, per record
    size_t recorded() const { return words.size() / (2 * no); }
    void add(std::initializer_list<uint64_t> head, const uint32_t* got, const uint32_t* want) {
        if (recorded() < limit) {
            meta.insert(meta.end(), head);
            words.insert(words.end(), got, got + no);
            words.insert(words.end(), want, want + no);
        }
        ++count;
    }
    bool write(std::FILE* out, size_t per_record) const {
        bool ok = true;
        for (size_t k = 0; ok && k < recorded(); ++k) {
            ok = std::fwrite(&meta[k * per_record], 8, per_record, out) == per_record &&
                 std::fwrite(&words[k * 2 * no], 4, 2 * no, out) == 2 * no;
        }
        return ok;
    }
};

// One clock edge after the outputs of `cycle` were read.
static void edge(Vtop& top, Trace& trace, uint64_t cycle) {
    top.clk = 1;
    top.eval();
    trace.dump(10 * cycle + 5);
    top.clk = 0;
}

struct Stats {
    uint64_t cycles, delivered, stalls, resets, resent;
};

// Mode 2: the driver and checks of harness.StreamChecker, line for line.
static Stats stream(Vtop& top, Trace& trace, Report& report, const uint64_t* head, const uint32_t* data) {
    const uint64_t limit = head[1], ni = head[2], no = head[3], count = head[6], nj = head[7];
    const uint64_t latency = head[8], quiet_from = head[9], drain0 = head[10];
    const uint64_t interval = head[11] ? head[11] : 1;
    const uint32_t* vectors = data;
    const uint32_t* expected = vectors + count * ni;
    const uint32_t* junk = expected + count * no;
    const uint32_t* resume = junk + nj * ni;
    const uint8_t* control = reinterpret_cast<const uint8_t*>(resume + count);
    std::vector<int64_t> ring(latency + 1, -1);
    std::vector<uint32_t> held(no), zero(no, 0), want(no, 0);
    bool holding = false, offering = false, in_reset = false;
    uint64_t next = 0, delivered = 0, moves = 0, stalls = 0, resets = 0, resent = 0, cycle = 0, busy = 0;
    int64_t drain = -1;
    while (cycle < limit) {
        const uint8_t ctl = control[cycle];
        const bool rst = ctl & RESET, ready = ctl & READY;
        const uint32_t* word = junk + (cycle % nj) * ni;
        if (rst) {
            offering = false;
        } else {
            if (!offering && next < count && !(ctl & IDLE)) offering = true;
            if (offering) word = vectors + next * ni;
        }
        std::memcpy(top.i_word.data(), word, 4 * ni);
        top.ctl = (rst ? 2 : 0) | (ready ? 1 : 0);
        top.eval();
        trace.dump(10 * cycle);
        const uint32_t* got = top.o_word.data();
        const bool o_valid = got[0] & 1, i_ready = top.i_ready & 1;
        const int64_t source = moves >= latency ? ring[(moves - latency) % ring.size()] : -1;
        const bool want_valid = source >= 0, transfer = o_valid && ready && !rst;
        if (o_valid != want_valid) {
            want[0] = want_valid;
            report.add({cycle, VALID, static_cast<uint64_t>(source)}, got, want.data());
        } else if (holding && (!o_valid || std::memcmp(got, held.data(), 4 * no) != 0)) {
            report.add({cycle, HELD, delivered}, got, held.data());
        } else if (transfer && delivered >= count) {
            report.add({cycle, EXTRA, static_cast<uint64_t>(-1)}, got, zero.data());
        } else if (transfer && std::memcmp(got, expected + delivered * no, 4 * no) != 0) {
            report.add({cycle, PAYLOAD, delivered}, got, expected + delivered * no);
        }

        if (rst) {
            // what was in flight is lost: offer it again, from a scanline's start if need be
            const uint64_t from = delivered < count ? resume[delivered] : delivered;
            if (!in_reset) {
                ++resets;
                resent += next > from ? next - from : 0;
            }
            in_reset = true;
            next = delivered = from;
            moves = 0;
            busy = 0;
            holding = false;
        } else {
            in_reset = false;
            const bool taken = offering && i_ready;
            // the pipeline moves where the design is ready, or busy with a vector's turns
            const bool moving = i_ready || (busy > 0 && (ready || !o_valid));
            if (moving) ring[moves++ % ring.size()] = taken ? static_cast<int64_t>(next) : -1;
            if (taken) {
                busy = interval - 1;
            } else if (moving && busy > 0) {
                --busy;
            }
            if (taken) {
                ++next;
                offering = false;
            }
            delivered += transfer;
            holding = o_valid && !ready;
            stalls += holding;
            if (holding) std::memcpy(held.data(), got, 4 * no);
        }
        edge(top, trace, cycle);

        ++cycle;
        if (drain >= 0) {
            --drain;
        } else if (delivered >= count && cycle >= quiet_from) {
            drain = static_cast<int64_t>(drain0);
        }
        if (drain == 0) break;
    }
    if (delivered < count) report.add({cycle - 1, LOST, delivered}, zero.data(), zero.data());
    return {cycle, delivered, stalls, resets, resent};
}

int main(int argc, char** argv) {
    if (argc != 3 && argc != 4) return fail("usage: phongfx_sim STREAM RESULT [VCD]");
#if !VM_TRACE
    if (argc == 4) return fail("a VCD needs a build with --trace");
#endif
    int fd = open(argv[1], O_RDONLY);
    if (fd < 0) return fail("cannot open the stream");
    struct stat st;
    if (fstat(fd, &st) != 0 || st.st_size < static_cast<off_t>(8 * HEADER))
        return fail("stream shorter than its header");
    const size_t size = static_cast<size_t>(st.st_size);
    void* base = mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    if (base == MAP_FAILED) return fail("cannot map the stream");
    const uint64_t* head = static_cast<const uint64_t*>(base);
    const uint64_t cycles = head[1], ni = head[2], no = head[3], limit = head[4], mode = head[5];
    if (head[0] != MAGIC) return fail("stream has a wrong magic number");
    if (mode > 2) return fail("stream has an unknown mode");

    VerilatedContext context;
    if (argc == 4) context.traceEverOn(true);
    Vtop top{&context};
    Trace trace;
    if (argc == 4) trace.open(top, argv[3]);
    if (ni != sizeof(top.i_word) / 4 || no != sizeof(top.o_word) / 4)
        return fail("stream word counts differ from the compiled top's ports");
    size_t body = 4 * cycles * (ni + (mode == 0 ? no : 0));
    if (mode == 2) {
        if (head[7] == 0) return fail("stream has no junk rows");
        body = 4 * (head[6] * (ni + no + 1) + head[7] * ni) + (cycles + 3) / 4 * 4;
    }
    if (size != 8 * HEADER + body) return fail("stream size does not match its header");
    madvise(base, size, MADV_SEQUENTIAL);
    const uint32_t* in = reinterpret_cast<const uint32_t*>(static_cast<const char*>(base) + 8 * HEADER);
    const uint32_t* expected = in + cycles * ni;

    std::vector<uint32_t> dump(mode == 1 ? cycles * no : 0);
    Report report{mode == 1 ? 0 : limit, no};
    Stats stats{cycles, 0, 0, 0, 0};
    top.clk = 0;
    top.ctl = 0;
    top.eval();
    if (mode == 2) {
        stats = stream(top, trace, report, head, in);
    } else {
        for (uint64_t cycle = 0; cycle < cycles; ++cycle) {
            std::memcpy(top.i_word.data(), in + cycle * ni, 4 * ni);
            top.eval();
            trace.dump(10 * cycle);
            const uint32_t* got = top.o_word.data();
            if (mode == 1) {
                std::memcpy(&dump[cycle * no], got, 4 * no);
            } else {
                const uint32_t* want = expected + cycle * no;
                // a payload only counts when the output is expected valid
                bool bad = ((got[0] ^ want[0]) & 1) != 0;
                if (!bad && (want[0] & 1)) bad = std::memcmp(got, want, 4 * no) != 0;
                if (bad) report.add({cycle}, got, want);
            }
            edge(top, trace, cycle);
        }
    }
    top.final();
    trace.close();

    std::FILE* out = std::fopen(argv[2], "wb");
    if (!out) return fail("cannot write the result");
    bool ok = true;
    if (mode == 1) {
        ok = std::fwrite(dump.data(), 4, dump.size(), out) == dump.size();
    } else if (mode == 0) {
        const uint64_t summary[3] = {cycles, report.count, report.recorded()};
        ok = std::fwrite(summary, 8, 3, out) == 3 && report.write(out, 1);
    } else {
        const uint64_t summary[8] = {stats.cycles, report.count, report.recorded(), stats.delivered,
                                     stats.stalls, stats.resets, stats.resent, 0};
        ok = std::fwrite(summary, 8, 8, out) == 8 && report.write(out, 3);
    }
    if (std::fclose(out) != 0 || !ok) return fail("result write failed");
    munmap(base, size);
    close(fd);
    return 0;
}
