// Bit-field access to any verilated port: CData/SData/IData/QData or VlWide<N> (ports wider
// than 64 bits, 32-bit words, word 0 = bits 31:0). Fields up to 64 bits; getSigned
// sign-extends. Shared by the harness and the unit tests.
#pragma once

#include <cstddef>
#include <cstdint>

#include <verilated.h>

#include "fixed.h"

namespace pst {
namespace port {

// Bit-field access for any verilated port type: CData/SData/IData/QData or VlWide<N>.
template <typename T>
void set(T& p, int lsb, int width, uint64_t v) {
    for (int b = 0; b < width; ++b) {
        const T bit = T(1) << (lsb + b);
        p = ((v >> b) & 1) ? (p | bit) : (p & ~bit);
    }
}
template <std::size_t N>
void set(VlWide<N>& p, int lsb, int width, uint64_t v) {
    for (int b = 0; b < width; ++b) {
        const int i = lsb + b;
        const uint32_t bit = 1u << (i % 32);
        p[i / 32] = ((v >> b) & 1) ? (p[i / 32] | bit) : (p[i / 32] & ~bit);
    }
}
template <typename T>
uint64_t get(const T& p, int lsb, int width) {
    return (uint64_t(p) >> lsb) & (width >= 64 ? ~uint64_t(0) : (uint64_t(1) << width) - 1);
}
template <std::size_t N>
uint64_t get(const VlWide<N>& p, int lsb, int width) {
    uint64_t v = 0;
    for (int b = 0; b < width; ++b) {
        const int i = lsb + b;
        v |= uint64_t((p[i / 32] >> (i % 32)) & 1u) << b;
    }
    return v;
}
template <typename T>
int64_t getSigned(const T& p, int lsb, int width) {
    return fx::wrapSigned(fx::i128(get(p, lsb, width)), width);
}

}  // namespace port

}  // namespace pst
