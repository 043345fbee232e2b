// pst_roms OUTDIR: writes the noise unit's ROM images for $readmemh, from the reference
// model's tables (model/noise.cpp holds their one definition):
//   OUTDIR/hash4096.memh  4096 lines, 3 hex digits: Rayshade's hash table T
//   OUTDIR/perm256.memh    256 lines, 2 hex digits: the 256-entry permutation P
//   OUTDIR/perlin256.memh  256 lines, 2 hex digits: Perlin's 2002 permutation (perlin2002.h)
//   OUTDIR/value16.memh    267 lines, 4 hex digits: R[i] * 32768 as a 16-bit two's-complement
//                          number (exact: R = (crc - 32768) / 32768). The RTL and the golden
//                          model bring it to NoiseValueFrac bits with value16 >>> (15 - frac).
// and the banks rtl/noise/pst_noise.sv reads (the same entries, split by address):
//   OUTDIR/hash4096_even.memh, hash4096_odd.memh   T[2a], T[2a + 1] (2048 lines each)
//   OUTDIR/perm256_even.memh, perm256_odd.memh     P[2a], P[2a + 1] (128 lines each)
//   OUTDIR/value16_b<b>.memh, b = 0..3             value16[4j + b], j = 0..66 (67 lines; the
//                                                  entry past value16[266] is 0, never read)
// and the worley unit's feature-point ROMs (rtl/noise/pst_worley.sv, model/worley.h worleyRomCube):
//   OUTDIR/worley256_p<M>.memh, M = 1..9   256 words of 4 + 24 M bits: [3:0] the cube's count
//                                          (Poisson, clamped to 1..M), point j's x, y, z bytes
//                                          at [4 + 24 j + 8 a +: 8] (1 + 6 M hex digits)
// and the subband unit's tile (rtl/noise/pst_subband.sv, model/golden/subband_fx.h):
//   OUTDIR/subband.memh                    4^SubbandTileLog2 words of SubbandValueBits (two's
//                                          complement), word y 2^SubbandTileLog2 + x the tile at
//                                          pixel (x, y)
//   OUTDIR/subband_k<K>.memh, K = 4, 8     4^SubbandTileLog2 words of K SubbandValueBits: oriented
//                                          tile t at [t SubbandValueBits +: SubbandValueBits]
//   OUTDIR/subband_k<K>_b<B>.memh, B = 0..3  the same tiles in four banks by the pixel's row and
//                                          column parity, B = 2 (y mod 2) + (x mod 2): word
//                                          (y / 2) 2^(SubbandTileLog2 - 1) + x / 2 (the subband
//                                          unit reading its four corners in one step)
// Each file is written to a temporary name and renamed, so a reader never sees half a file.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "noise.h"
#include "perlin2002.h"
#include "subband_fx.h"
#include "worley.h"

namespace {

bool writeMemh(const std::string& dir, const std::string& name, int count, int digits,
               const std::function<uint32_t(int)>& entry) {
    const std::string path = dir + "/" + name;
    const std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp, std::ios::trunc);
        if (!out) {
            std::fprintf(stderr, "pst_roms: cannot write %s\n", tmp.c_str());
            return false;
        }
        char line[16];
        for (int i = 0; i < count; ++i) {
            std::snprintf(line, sizeof line, "%0*x\n", digits, static_cast<unsigned>(entry(i)));
            out << line;
        }
        if (!out.flush()) {
            std::fprintf(stderr, "pst_roms: write error on %s\n", tmp.c_str());
            return false;
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::fprintf(stderr, "pst_roms: cannot rename %s: %s\n", tmp.c_str(), ec.message().c_str());
        return false;
    }
    return true;
}

// The last step of a file written line by line to PATH.tmp: flushed, closed and renamed to PATH
// (renamed even after an earlier failure). Returns ok and whether this file was written whole;
// says so on stderr when not.
bool closeAndRename(std::ofstream& out, const std::string& path, bool ok) {
    ok = bool(out.flush()) && ok;
    out.close();
    std::error_code ec;
    std::filesystem::rename(path + ".tmp", path, ec);
    ok = ok && !ec;
    if (!ok) std::fprintf(stderr, "pst_roms: cannot write %s\n", path.c_str());
    return ok;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: pst_roms OUTDIR\n");
        return 2;
    }
    const std::string dir = argv[1];
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) {
        std::fprintf(stderr, "pst_roms: cannot create %s: %s\n", dir.c_str(), ec.message().c_str());
        return 1;
    }
    const pst::NoiseTables& t = pst::NoiseTables::get();

    // R[i] * 32768 must be an integer in [-32768, 32767]: check every entry before writing.
    for (int i = 0; i < pst::NoiseTables::kValueSize; ++i) {
        const double v = t.value[i] * 32768.0;
        if (!(v == std::floor(v) && v >= -32768.0 && v <= 32767.0)) {
            std::fprintf(stderr, "pst_roms: R[%d] = %.17g is not a signed 1.15 number\n", i, t.value[i]);
            return 1;
        }
    }
    bool ok = writeMemh(dir, "hash4096.memh", pst::NoiseTables::kHashSize, 3,
                        [&](int i) { return uint32_t(t.hash[i]) & 0xfffu; });
    ok = ok && writeMemh(dir, "perm256.memh", pst::NoiseTables::kPermSize, 2,
                         [&](int i) { return uint32_t(t.perm[i]) & 0xffu; });
    const auto value16 = [&](int i) {
        return i < pst::NoiseTables::kValueSize ? uint32_t(uint16_t(int16_t(std::lround(t.value[i] * 32768.0))))
                                                : 0u;
    };
    ok = ok && writeMemh(dir, "perlin256.memh", 256, 2,
                         [&](int i) { return uint32_t(pst::perlin2002Permutation()[size_t(i)]); });
    ok = ok && writeMemh(dir, "perlin256_even.memh", 128, 2,
                         [&](int a) { return uint32_t(pst::perlin2002Permutation()[size_t(2 * a)]); });
    ok = ok && writeMemh(dir, "perlin256_odd.memh", 128, 2,
                         [&](int a) { return uint32_t(pst::perlin2002Permutation()[size_t(2 * a + 1)]); });
    ok = ok && writeMemh(dir, "value16.memh", pst::NoiseTables::kValueSize, 4, value16);
    ok = ok && writeMemh(dir, "hash4096_even.memh", pst::NoiseTables::kHashSize / 2, 3,
                         [&](int a) { return uint32_t(t.hash[2 * a]) & 0xfffu; });
    ok = ok && writeMemh(dir, "hash4096_odd.memh", pst::NoiseTables::kHashSize / 2, 3,
                         [&](int a) { return uint32_t(t.hash[2 * a + 1]) & 0xfffu; });
    ok = ok && writeMemh(dir, "perm256_even.memh", pst::NoiseTables::kPermSize / 2, 2,
                         [&](int a) { return uint32_t(t.perm[2 * a]) & 0xffu; });
    ok = ok && writeMemh(dir, "perm256_odd.memh", pst::NoiseTables::kPermSize / 2, 2,
                         [&](int a) { return uint32_t(t.perm[2 * a + 1]) & 0xffu; });
    const int banks = 4, depth = (pst::NoiseTables::kValueSize + banks - 1) / banks;
    for (int b = 0; b < banks; ++b)
        ok = ok && writeMemh(dir, "value16_b" + std::to_string(b) + ".memh", depth, 4,
                             [&](int j) { return value16(banks * j + b); });
    for (int m = 1; m <= pst::kWorleyMaxPoints; ++m) {
        const std::string path = dir + "/worley256_p" + std::to_string(m) + ".memh";
        std::ofstream out(path + ".tmp", std::ios::trunc);
        for (int e = 0; e < 256; ++e) {
            const pst::WorleyCube c = pst::worleyRomCube(e, m);
            const auto b = pst::worleyRomBytes(e);
            char hex[8];
            std::string line;
            for (int j = m - 1; j >= 0; --j)
                for (int a = 2; a >= 0; --a) {
                    std::snprintf(hex, sizeof hex, "%02x", unsigned(b[size_t(3 * j + a)]));
                    line += hex;
                }
            std::snprintf(hex, sizeof hex, "%x", unsigned(c.count));
            out << line << hex << "\n";
        }
        ok = closeAndRename(out, path, ok);
    }
    // The subband unit's tile (rtl/noise/pst_subband.sv): SubbandValueBits-bit two's complement
    // words, y 2^SubbandTileLog2 + x (model/golden/subband_fx.h subbandRomWord).
    // subband_k4.memh, subband_k8.memh: the K oriented tiles, tile t at [t vb +: vb] (writeMemh
    // writes up to 32 bits: the words are written here, most significant tile first).
    {
        const int vb = pst::contract::kSubbandValueBits;
        ok = ok && writeMemh(dir, "subband.memh", pst::kSubbandRomWords, (vb + 3) / 4, [&](int i) {
            return uint32_t(pst::subbandRomWord(0, 0, i)) & uint32_t((uint64_t(1) << vb) - 1);
        });
        auto line = [&](int K, int a) {
            std::string l;
            for (int t = K - 1; t >= 0; --t) {
                char hex[8];
                std::snprintf(hex, sizeof hex, "%0*x", (vb + 3) / 4,
                              unsigned(pst::subbandRomWord(K, t, a) & ((int64_t(1) << vb) - 1)));
                l += hex;
            }
            return l;
        };
        const int tl = pst::contract::kSubbandTileLog2;
        for (int K : {4, 8}) {
            const std::string path = dir + "/subband_k" + std::to_string(K) + ".memh";
            std::ofstream out(path + ".tmp", std::ios::trunc);
            for (int a = 0; a < pst::kSubbandRomWords; ++a) out << line(K, a) << "\n";
            ok = closeAndRename(out, path, ok);
            for (int b = 0; b < 4; ++b) {
                const std::string bpath = dir + "/subband_k" + std::to_string(K) + "_b" + std::to_string(b) + ".memh";
                std::ofstream bout(bpath + ".tmp", std::ios::trunc);
                for (int a = 0; a < pst::kSubbandRomWords / 4; ++a) {
                    const int y = 2 * (a >> (tl - 1)) + (b >> 1), x = 2 * (a & ((1 << (tl - 1)) - 1)) + (b & 1);
                    bout << line(K, (y << tl) + x) << "\n";
                }
                ok = closeAndRename(bout, bpath, ok);
            }
        }
    }
    return ok ? 0 : 1;
}
