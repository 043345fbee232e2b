// Perlin's improved noise (Perlin, "Improving Noise", SIGGRAPH 2002; Green, GPU Gems 2 ch. 26,
// seed 003) in double precision, with its analytic gradient.
//
// The value is Perlin's published reference implementation bit for bit: "JAVA REFERENCE
// IMPLEMENTATION OF IMPROVED NOISE - COPYRIGHT 2002 KEN PERLIN." (ImprovedNoise.java,
// https://mrl.nyu.edu/~perlin/noise/), read from its copies in the GitHub repositories
// Harshit00yadav/PerlinNoise (ImprovedNoise.java, commit 92ca0c1f) and Syritx/improved-noise
// (ImprovedNoise.java, commit dcefdc28): the same 256-entry permutation (doubled), fade
// 6t^5 - 15t^4 + 10t^3, grad() picking 12 directions (16 with 4 repeated) from the low four
// hash bits, and the same nested lerps in the same order. model/testdata/improved_noise_ref.py
// is the independent transliteration the test compares against (and it checks itself against
// a JVM with --java).
//
// Domain: every finite p gives Java's value, including Java's (int) saturation of floor(x)
// beyond +-2^31 (where the noise stops being periodic). A non-finite coordinate gives 0 and
// a zero gradient (Java would give NaN).
#pragma once

#include <array>
#include <cstdint>

#include <glm/vec3.hpp>

namespace pst {

// Perlin's permutation[] (256 entries).
const std::array<uint8_t, 256>& perlin2002Permutation();

// noise(x, y, z) of ImprovedNoise.java; if grad != nullptr also its gradient, exact inside a
// lattice cell (the noise is C2: fade' and fade'' vanish on the lattice planes, so the cell's
// gradient formula is right on them too). |n| <= 2 (each corner term is at most 2 in size, the
// weights sum to 1); 2 million random points stay within [-0.982, 1.001].
double perlin2002(const glm::dvec3& p, glm::dvec3* grad = nullptr);

}  // namespace pst
