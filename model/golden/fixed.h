// Fixed-point helpers shared by the golden model and the driver: every rounding and
// saturation the hardware does, as one function each. Values are held in int64_t (or
// __int128 for exact intermediate products); a format's value is integer / 2^frac.
#pragma once

#include <cmath>
#include <cstdint>

namespace pst::fx {

using i128 = __int128;

// Largest and smallest integer of a signed `bits`-wide two's-complement number.
constexpr int64_t maxSigned(int bits) { return (int64_t(1) << (bits - 1)) - 1; }
constexpr int64_t minSigned(int bits) { return -(int64_t(1) << (bits - 1)); }
constexpr int64_t maxUnsigned(int bits) { return (int64_t(1) << bits) - 1; }

// Signed saturation to `bits` bits (a hardware saturating clamp).
constexpr int64_t satSigned(i128 v, int bits) {
    return v > maxSigned(bits) ? maxSigned(bits) : v < minSigned(bits) ? minSigned(bits) : int64_t(v);
}
// Unsigned saturation to [0, 2^bits - 1].
constexpr int64_t satUnsigned(i128 v, int bits) {
    return v > maxUnsigned(bits) ? maxUnsigned(bits) : v < 0 ? 0 : int64_t(v);
}
// Two's-complement wrap to `bits` bits, sign-extended (dropping the high bits of a register).
constexpr int64_t wrapSigned(i128 v, int bits) {
    const uint64_t m = bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1;
    uint64_t u = uint64_t(v) & m;
    if (bits < 64 && (u >> (bits - 1)) & 1) u |= ~m;
    return int64_t(u);
}
constexpr uint64_t wrapUnsigned(i128 v, int bits) {
    return uint64_t(v) & (bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1);
}
// Arithmetic shift right: floor(v / 2^sh) (SystemVerilog >>> on a signed value). sh < 0
// shifts left (exact).
constexpr i128 floorShift(i128 v, int sh) { return sh >= 0 ? (v >> sh) : v * (i128(1) << -sh); }
// Round half up: floor(v / 2^sh + 1/2).
constexpr i128 roundShift(i128 v, int sh) {
    return sh > 0 ? ((v + (i128(1) << (sh - 1))) >> sh) : floorShift(v, sh);
}

// The driver's conversion from double: round to nearest (ties away from zero), saturate to a
// signed (intBits + fracBits)-bit number. NaN maps to 0 (inputs are checked before this).
inline int64_t quantize(double v, int intBits, int fracBits) {
    if (std::isnan(v)) return 0;
    const int bits = intBits + fracBits;
    const double scaled = std::ldexp(v, fracBits);
    if (scaled >= double(maxSigned(bits))) return maxSigned(bits);
    if (scaled <= double(minSigned(bits))) return minSigned(bits);
    return int64_t(std::llround(scaled));
}
inline double toDouble(int64_t v, int fracBits) { return std::ldexp(double(v), -fracBits); }

}  // namespace pst::fx
