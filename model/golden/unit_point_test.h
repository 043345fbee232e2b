// The point a noise unit sees, for the unit tests of the golden noise units (worley_fx_test,
// subband_fx_test): a scene point through the hardware's octave transform with the identity
// matrix, as lattice cell, fraction and the double point they stand for.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/vec3.hpp>

#include "noise_fx.h"
#include "fixed.h"
#include "profile.h"

namespace pst {

struct UnitPoint {
    int lat[3];
    int64_t frac[3];
    glm::dvec3 pq;  // the point the unit sees
};

// The unit's input for a point p (identity transform, as the hardware's octave transform).
inline UnitPoint unitPoint(const Profile& prof, const glm::dvec3& p) {
    UnitPoint pt;
    int64_t s[3], M[9] = {}, o[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) s[k] = fx::quantize(p[k], prof.coord.intBits, prof.coord.fracBits);
    for (int k = 0; k < 3; ++k) M[4 * k] = fx::quantize(1.0, prof.matrix.intBits, prof.matrix.fracBits);
    octaveTransformFx(prof, s, M, o, pt.lat, pt.frac);
    for (int k = 0; k < 3; ++k)
        pt.pq[k] = double(fx::floorShift(s[k], prof.coord.fracBits)) + std::ldexp(double(pt.frac[k]), -prof.noiseLatticeFrac);
    return pt;
}

}  // namespace pst
