// Fragment files: the text form of the fragment stream (rasterizer -> fragments -> models).
// One fragment per line, nine numbers separated by blanks:
//   s t r  ds/dx dt/dx dr/dx  ds/dy dt/dy dr/dy
// '#' starts a comment; blank lines are skipped. NaN and infinities are rejected.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace pst {

struct FragmentRecord {
    glm::dvec3 s{0.0};
    glm::dvec3 dsdx{0.0};
    glm::dvec3 dsdy{0.0};
};

// Throws InputError ("file:line: field: what") on malformed input.
std::vector<FragmentRecord> readFragments(std::istream& in, const std::string& path);
std::vector<FragmentRecord> loadFragments(const std::string& path);
// Full double precision (%.17g), so a written file reads back bit for bit.
void writeFragments(std::ostream& out, const std::vector<FragmentRecord>& frags);

}  // namespace pst
