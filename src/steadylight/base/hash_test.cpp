#include "steadylight/base/hash.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <initializer_list>

namespace steadylight {
namespace {

uint64_t hash_floats(std::initializer_list<float> values) {
    Hasher hasher;
    for (const float v : values) hasher.add(v);
    return hasher.value();
}

TEST(Hasher, SameInputsGiveTheSameValue) {
    const auto hash = [] {
        Hasher hasher;
        hasher.add(42);
        hasher.add(uint64_t(7));
        hasher.add(true);
        hasher.add(0.5);
        hasher.add("scene.json");
        hasher.add(Vec3{1, 2, 3});
        hasher.add(Rgb{0.1f, 0.2f, 0.3f});
        hasher.add(Quat{0, 0, 1, 0});
        hasher.add(Transform::translate({1, 2, 3}));
        return hasher.value();
    };
    EXPECT_EQ(hash(), hash());
    // Pinned, so that a change of algorithm (which makes every saved cache stale) is deliberate.
    EXPECT_EQ(checksum64("steadylight", 11), 0x94589b6036bf6cfcull);
}

TEST(Hasher, OrderMatters) {
    EXPECT_NE(hash_floats({1, 2}), hash_floats({2, 1}));
    Hasher ab_c, a_bc;
    ab_c.add("ab");
    ab_c.add("c");
    a_bc.add("a");
    a_bc.add("bc");
    EXPECT_NE(ab_c.value(), a_bc.value());
}

TEST(Hasher, NegativeZeroHashesAsZero) {
    EXPECT_EQ(hash_floats({-0.0f}), hash_floats({0.0f}));
    Hasher negative, positive;
    negative.add(-0.0);
    positive.add(0.0);
    EXPECT_EQ(negative.value(), positive.value());
}

TEST(Hasher, OneFloatBitChangesTheValue) {
    const float v = 0.7853981f;
    for (int bit = 0; bit < 32; ++bit) {
        const float flipped = std::bit_cast<float>(std::bit_cast<uint32_t>(v) ^ (uint32_t(1) << bit));
        EXPECT_NE(hash_floats({1, flipped, 3}), hash_floats({1, v, 3})) << "bit " << bit;
    }
}

}  // namespace
}  // namespace steadylight
