#pragma once
// The procedural scenes' random numbers (builtin:forest, builtin:terrain): a stateless hash
// of an object's index and a stream number, so that placement depends on the index alone
// and is the same on every platform (std:: distributions are not portable).
#include <cstdint>

namespace penumbra {

// SplitMix64 (Steele et al. 2014), in [0, 1) with 24 bits.
inline float procedural_random01(uint64_t index, uint64_t stream) {
    uint64_t z = index * 0x9E3779B97F4A7C15ull + stream * 0xBF58476D1CE4E5B9ull + 0x94D049BB133111EBull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<float>(z >> 40) / static_cast<float>(1ull << 24);
}

inline float procedural_lerp(float a, float b, float t) { return a + (b - a) * t; }

}  // namespace penumbra
