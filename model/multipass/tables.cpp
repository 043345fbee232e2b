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
            tables.t[table][i] = static_cast<uint8_t>(static_cast<int>(erand48(state) * levels));
        if (table != Nran)
            for (int i = cells; i < 256; ++i) tables.t[table][i] = tables.t[table][i % cells];
    }
    // Section 6.3's proposal (Variant::Xor): Rayshade's 8-bit permutation and value table.
    const NoiseTables& nt = NoiseTables::get();
    for (int i = 0; i < 256; ++i) {
        tables.t[Perm][i] = nt.perm[i];
        tables.t[ValuePerm][i] = static_cast<uint8_t>(std::lround((0.5 * nt.value[nt.perm[i]] + 0.5) * 255.0));
    }
    return tables;
}

}  // namespace pst::multipass
