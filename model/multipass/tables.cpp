// Random tables of the SGI multipass noise; see tables.h.
#include "tables.h"

#include <cmath>
#include <cstdlib>

#include "noise.h"

namespace pst::multipass {

Tables makeTables(const Params& params) {
    unsigned short state[3] = {0x330e, static_cast<unsigned short>(params.seed & 0xffff),
                               static_cast<unsigned short>(params.seed >> 16)};  // srand48(seed)
    Tables tables;
    const int cells = 1 << params.format.bi();
    for (int table = 0; table <= Nran; ++table) {
        const int levels = table == Nran ? 256 : 86;
        for (int i = 0; i < 256; ++i)
            tables.t[table][i] = static_cast<uint32_t>(erand48(state) * levels);
        if (table != Nran)
            for (int i = cells; i < 256; ++i) tables.t[table][i] = tables.t[table][i % cells];
    }
    // Section 6.3's proposal (Variant::Xor): Rayshade's 8-bit permutation and value table.
    const NoiseTables& nt = NoiseTables::get();
    const int M = params.format.max();
    tables.t[Perm].resize(size_t(M) + 1);
    tables.t[ValuePerm].resize(size_t(M) + 1);
    for (int i = 0; i <= M; ++i) {
        tables.t[Perm][i] = nt.perm[i & 255];
        tables.t[ValuePerm][i] = static_cast<uint32_t>(std::llround((0.5 * nt.value[nt.perm[i & 255]] + 0.5) * M));
    }
    return tables;
}

}  // namespace pst::multipass
