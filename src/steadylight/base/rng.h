// Deterministic random numbers. Streams are seeded from the work item's identity (frame, pixel,
// sample), never from the thread, so images do not depend on the thread count (docs/design.md).
#pragma once

#include <bit>
#include <cstdint>

#include "steadylight/base/vec.h"

namespace steadylight {

/// 64-bit mixing of several integers into one seed (SplitMix64 finaliser per word).
constexpr uint64_t mix_bits(uint64_t v) {
    v ^= v >> 31;
    v *= 0x7fb5d329728ea185ull;
    v ^= v >> 27;
    v *= 0x81dadef4bc2dd44dull;
    v ^= v >> 33;
    return v;
}

/// A hash `h` of words so far, with the word `word` mixed in: hash_ids's step, for callers that
/// share the hash of their first words among many last ones.
constexpr uint64_t hash_more(uint64_t h, uint64_t word) { return mix_bits(h ^ (word + 0x9e3779b97f4a7c15ull)); }

constexpr uint64_t hash_ids(uint64_t a, uint64_t b = 0, uint64_t c = 0, uint64_t d = 0) {
    return hash_more(hash_more(hash_more(hash_more(0, a), b), c), d);
}

/// A hash of two vectors, bit for bit (a ray's origin and direction, a photon's position and
/// direction): the same bits give the same hash wherever they are.
inline uint64_t hash_bits(Vec3 a, Vec3 b) {
    const auto bits = [](float x) { return uint64_t(std::bit_cast<uint32_t>(x)); };
    return hash_ids(bits(a.x) << 32 | bits(a.y), bits(a.z) << 32 | bits(b.x), bits(b.y) << 32 | bits(b.z));
}

/// PCG32 (O'Neill 2014): small state, good statistical quality, cheap to seed per pixel.
class Pcg32 {
public:
    explicit Pcg32(uint64_t seed, uint64_t stream = 0x5851f42d4c957f2dull) : m_state(0), m_inc((stream << 1u) | 1u) {
        next_u32();
        m_state += seed;
        next_u32();
    }

    uint32_t next_u32() {
        const uint64_t old = m_state;
        m_state = old * 6364136223846793005ull + m_inc;
        const uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
        const uint32_t rot = uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
    }

    /// A float uniformly in [0, 1).
    float next_float() { return float(next_u32() >> 8) * 0x1p-24f; }

    /// Two floats in [0, 1), drawn in order x then y.
    Vec2 next_vec2() {
        const float x = next_float();
        return {x, next_float()};
    }

private:
    uint64_t m_state;
    uint64_t m_inc;
};

}  // namespace steadylight
