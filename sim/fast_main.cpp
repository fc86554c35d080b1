// phongfx fast check: drive the Verilated top `Vtop` (see fast_backend.wrapper) from a
// binary stream and compare its outputs with the expected ones, cycle by cycle.
//
// usage: phongfx_sim STREAM RESULT
// STREAM: 8 little-endian uint64 (magic, cycles, in_words, out_words, max_report, mode, 0, 0),
//   then cycles x in_words uint32 input words {i.payload, i.valid} (least significant first),
//   then, in mode 0 (compare), cycles x out_words uint32 expected words {o.payload, o.valid}.
// RESULT, mode 0: uint64 (cycles, mismatch count, recorded), then per recorded mismatch
//   uint64 cycle, out_words uint32 got, out_words uint32 expected.
// RESULT, mode 1 (dump): cycles x out_words uint32 output words.
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

static const uint64_t MAGIC = 0x3174736166786670ULL;  // "pfxfast1"

static int fail(const char* what) {
    std::fprintf(stderr, "phongfx_sim: %s\n", what);
    return 2;
}

int main(int argc, char** argv) {
    if (argc != 3) return fail("usage: phongfx_sim STREAM RESULT");
    int fd = open(argv[1], O_RDONLY);
    if (fd < 0) return fail("cannot open the stream");
    struct stat st;
    if (fstat(fd, &st) != 0 || st.st_size < 64) return fail("stream shorter than its header");
    const size_t size = static_cast<size_t>(st.st_size);
    void* base = mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    if (base == MAP_FAILED) return fail("cannot map the stream");
    const uint64_t* head = static_cast<const uint64_t*>(base);
    const uint64_t cycles = head[1], ni = head[2], no = head[3], limit = head[4], mode = head[5];
    if (head[0] != MAGIC) return fail("stream has a wrong magic number");
    if (mode > 1) return fail("stream has an unknown mode");

    VerilatedContext context;
    Vtop top{&context};
    if (ni != sizeof(top.i_word) / 4 || no != sizeof(top.o_word) / 4)
        return fail("stream word counts differ from the compiled top's ports");
    if (size != 64 + 4 * cycles * (ni + (mode == 0 ? no : 0)))
        return fail("stream size does not match its header");
    madvise(base, size, MADV_SEQUENTIAL);
    const uint32_t* in = reinterpret_cast<const uint32_t*>(static_cast<const char*>(base) + 64);
    const uint32_t* expected = in + cycles * ni;

    std::vector<uint32_t> dump(mode == 1 ? cycles * no : 0);
    std::vector<uint64_t> at;
    std::vector<uint32_t> words;
    uint64_t count = 0;
    top.clk = 0;
    top.eval();
    for (uint64_t cycle = 0; cycle < cycles; ++cycle) {
        std::memcpy(top.i_word.data(), in + cycle * ni, 4 * ni);
        top.eval();
        const uint32_t* got = top.o_word.data();
        if (mode == 1) {
            std::memcpy(&dump[cycle * no], got, 4 * no);
        } else {
            const uint32_t* want = expected + cycle * no;
            // a payload only counts when the output is expected valid
            bool bad = ((got[0] ^ want[0]) & 1) != 0;
            if (!bad && (want[0] & 1)) bad = std::memcmp(got, want, 4 * no) != 0;
            if (bad) {
                if (at.size() < limit) {
                    at.push_back(cycle);
                    words.insert(words.end(), got, got + no);
                    words.insert(words.end(), want, want + no);
                }
                ++count;
            }
        }
        top.clk = 1;
        top.eval();
        top.clk = 0;
    }
    top.final();

    std::FILE* out = std::fopen(argv[2], "wb");
    if (!out) return fail("cannot write the result");
    bool ok = true;
    if (mode == 1) {
        ok = std::fwrite(dump.data(), 4, dump.size(), out) == dump.size();
    } else {
        const uint64_t summary[3] = {cycles, count, at.size()};
        ok = std::fwrite(summary, 8, 3, out) == 3;
        for (size_t k = 0; ok && k < at.size(); ++k) {
            ok = std::fwrite(&at[k], 8, 1, out) == 1 &&
                 std::fwrite(&words[k * 2 * no], 4, 2 * no, out) == 2 * no;
        }
    }
    if (std::fclose(out) != 0 || !ok) return fail("result write failed");
    munmap(base, size);
    close(fd);
    return 0;
}
