// Random tables of the SGI multipass noise; see tables.h.
#include "tables.h"

#include <cstdlib>

namespace pst::multipass {

Tables makeTables(const Params& params) {
    unsigned short state[3] = {0x330e, static_cast<unsigned short>(params.seed & 0xffff),
                               static_cast<unsigned short>(params.seed >> 16)};  // srand48(seed)
    Tables tables;
    const int cells = 1 << params.format.bi();
    for (int table = 0; table < kTableCount; ++table) {
        const int levels = table == Nran ? 256 : 86;
        for (int i = 0; i < 256; ++i)
            tables.t[table][i] = static_cast<uint8_t>(static_cast<int>(erand48(state) * levels));
        if (table != Nran)
            for (int i = cells; i < 256; ++i) tables.t[table][i] = tables.t[table][i % cells];
    }
    return tables;
}

}  // namespace pst::multipass
