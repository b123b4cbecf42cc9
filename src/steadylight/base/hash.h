// Deterministic 64-bit hashing: keys that say what a saved result was made from (the static
// irradiance cache's inputs, Tawara et al. 2002) and checksums of the files that hold it. Values
// are the same on every run and machine: input is read as little-endian 8-byte words, each folded
// in as state = mix_bits(state ^ (word + golden)) with the SplitMix64 finaliser of base/rng.h, and
// nothing depends on pointers, std::hash or the host's byte order. mix_bits is a bijection, so a
// change confined to one word of a fixed-length input always changes the value. Not
// cryptographic: it detects damage, not tampering.
#pragma once

#include <bit>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "steadylight/base/color.h"
#include "steadylight/base/rng.h"
#include "steadylight/base/transform.h"
#include "steadylight/base/vec.h"

namespace steadylight {

class Hasher {
public:
    /// Adds `size` bytes as one field: their length is folded in after them, so that splitting
    /// the same bytes differently between calls gives a different value.
    void add(const void* data, size_t size) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        size_t i = 0;
        for (; i + 8 <= size; i += 8) add_word(load_word(bytes + i, 8));
        if (i < size) add_word(load_word(bytes + i, size - i));
        add_word(uint64_t(size));
    }

    /// Integers hash by value: a negative one as its 64-bit two's complement.
    template <std::integral T>
    void add(T v) {
        add_word(uint64_t(v));
    }
    void add(bool v) { add_word(v ? 1 : 0); }
    /// Floats hash by bit pattern, except that -0 counts as 0 (they compare equal).
    void add(float v) { add_word(std::bit_cast<uint32_t>(v == 0 ? 0.0f : v)); }
    void add(double v) { add_word(std::bit_cast<uint64_t>(v == 0 ? 0.0 : v)); }
    void add(std::string_view s) { add(s.data(), s.size()); }
    // Without this a string literal would convert to bool, not to std::string_view.
    void add(const char* s) { add(std::string_view(s)); }

    void add(Vec3 v) { add_floats(v.x, v.y, v.z); }
    void add(Rgb c) { add_floats(c.r, c.g, c.b); }
    void add(Quat q) { add_floats(q.x, q.y, q.z, q.w); }
    void add(const Transform& t) {
        for (const auto& row : t.m) add_floats(row[0], row[1], row[2], row[3]);
    }

    uint64_t value() const { return m_state; }

private:
    static constexpr uint64_t golden = 0x9e3779b97f4a7c15ull;

    // Adding `golden` keeps 0 (a fixed point of mix_bits) from passing through unchanged.
    void add_word(uint64_t word) { m_state = mix_bits(m_state ^ (word + golden)); }

    template <class... F>
    void add_floats(F... v) {
        (add(v), ...);
    }

    /// `count` (1 to 8) bytes as a little-endian word, zero-padded.
    static uint64_t load_word(const unsigned char* bytes, size_t count) {
        uint64_t word = 0;
        for (size_t k = 0; k < count; ++k) word |= uint64_t(bytes[k]) << (8 * k);
        return word;
    }

    uint64_t m_state = 0x243f6a8885a308d3ull;  // digits of pi: any fixed non-zero start
};

/// A checksum of `size` bytes for file integrity: every single-word change is detected.
inline uint64_t checksum64(const void* data, size_t size) {
    Hasher hasher;
    hasher.add(data, size);
    return hasher.value();
}

}  // namespace steadylight
