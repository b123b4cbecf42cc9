#include "steadylight/irradiance/cache_file.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "steadylight/base/hash.h"
#include "steadylight/base/rng.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

// The layout of cache_file.h, spelled out so that a change of format fails here on purpose.
constexpr size_t version_offset = 10;
constexpr size_t count_offset = 14;
constexpr size_t accuracy_offset = 22;
constexpr size_t header_size = 42;
constexpr size_t record_size = 112;
constexpr size_t radius_in_record = 36;
constexpr uint64_t inputs = 0x5eed'cafe'f00d'1234ull;

using Bytes = std::vector<unsigned char>;

void put_le(Bytes& bytes, size_t at, uint64_t v, int size) {
    for (int k = 0; k < size; ++k) bytes[at + size_t(k)] = static_cast<unsigned char>(v >> (8 * k));
}
void put_float(Bytes& bytes, size_t at, float v) { put_le(bytes, at, std::bit_cast<uint32_t>(v), 4); }

/// Recomputes the trailing checksum, as a crafted file would.
void reseal(Bytes& bytes) { put_le(bytes, bytes.size() - 8, checksum64(bytes.data(), bytes.size() - 8), 8); }

Vec3 random_in_cube(Pcg32& rng, float half) {
    return {(2 * rng.next_float() - 1) * half, (2 * rng.next_float() - 1) * half, (2 * rng.next_float() - 1) * half};
}

Vec3 random_unit(Pcg32& rng) {
    for (;;) {
        const Vec3 v = random_in_cube(rng, 1);
        if (length2(v) > 0.01f && length2(v) <= 1) return normalize(v);
    }
}

/// `count` random records with gradients, inserted without clamping, with non-default settings.
IrradianceCache random_cache(int count, uint64_t seed = 7) {
    Pcg32 rng(seed);
    IrradianceCache cache(CacheSettings{0.2f, 1.5f, 24.0f});
    for (int i = 0; i < count; ++i) {
        IrradianceRecord record;
        record.p = random_in_cube(rng, 2);
        record.n = random_unit(rng);
        record.E = {5 * rng.next_float(), 5 * rng.next_float(), 5 * rng.next_float()};
        record.radius = 0.05f + rng.next_float();
        for (Vec3& g : record.rotational_gradient) g = random_in_cube(rng, 1);
        for (Vec3& g : record.translational_gradient) g = random_in_cube(rng, 1);
        cache.insert(record);
    }
    return cache;
}

/// The settings and every record of `cache` as 32-bit patterns, in order.
std::vector<uint32_t> bits_of(const IrradianceCache& cache) {
    std::vector<uint32_t> bits;
    const auto add = [&](float v) { bits.push_back(std::bit_cast<uint32_t>(v)); };
    const auto add3 = [&](Vec3 v) {
        add(v.x);
        add(v.y);
        add(v.z);
    };
    add(cache.settings().accuracy);
    add(cache.settings().min_spacing_px);
    add(cache.settings().max_spacing_px);
    for (const IrradianceRecord& r : cache.records()) {
        add3(r.p);
        add3(r.n);
        add3({r.E.r, r.E.g, r.E.b});
        add(r.radius);
        for (const Vec3& g : r.rotational_gradient) add3(g);
        for (const Vec3& g : r.translational_gradient) add3(g);
    }
    return bits;
}

/// Each test gets its own file under the temporary directory, removed (with any .partial) after.
class CacheFile : public ::testing::Test {
protected:
    void SetUp() override {
        const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
        m_path = (fs::temp_directory_path() /
                  ("steadylight_" + test + "_" + std::to_string(std::random_device{}()) + ".slirr"))
                     .string();
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(m_path, ignored);
        fs::remove(m_path + ".partial", ignored);
    }

    Bytes read_bytes() const {
        std::ifstream in(m_path, std::ios::binary);
        return Bytes(std::istreambuf_iterator<char>(in), {});
    }
    void write_bytes(const Bytes& bytes) const {
        std::ofstream out(m_path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    }
    /// Writes `bytes` and reads them back as a cache file made from `inputs`.
    CacheFileLoad load(const Bytes& bytes) const {
        write_bytes(bytes);
        return read_cache_file(m_path, inputs);
    }

    std::string m_path;
};

TEST_F(CacheFile, RoundTripGivesBitIdenticalRecordsInOrder) {
    const IrradianceCache cache = random_cache(500);
    write_cache_file(m_path, cache, inputs);
    const CacheFileLoad loaded = read_cache_file(m_path, inputs);
    ASSERT_TRUE(loaded.cache) << loaded.rejection;
    EXPECT_EQ(loaded.rejection, "");
    EXPECT_EQ(fs::file_size(m_path), header_size + 500 * record_size + 8);
    EXPECT_EQ(bits_of(*loaded.cache), bits_of(cache));
}

TEST_F(CacheFile, LoadedCacheInterpolatesIdentically) {
    const IrradianceCache cache = random_cache(500);
    write_cache_file(m_path, cache, inputs);
    const CacheFileLoad loaded = read_cache_file(m_path, inputs);
    ASSERT_TRUE(loaded.cache) << loaded.rejection;
    // Probe near records, with tilted normals, so that most probes interpolate.
    Pcg32 rng(11);
    int interpolated = 0;
    for (int i = 0; i < 2000; ++i) {
        const IrradianceRecord& near = cache.records()[rng.next_u32() % 500];
        const Vec3 p = near.p + random_in_cube(rng, 0.03f), n = normalize(near.n + random_in_cube(rng, 0.05f));
        const std::optional<Rgb> want = cache.interpolate(p, n), got = loaded.cache->interpolate(p, n);
        ASSERT_EQ(got.has_value(), want.has_value());
        if (!want) continue;
        EXPECT_EQ(*got, *want);
        ++interpolated;
    }
    EXPECT_GT(interpolated, 1000);
}

TEST_F(CacheFile, EmptyCacheRoundTrips) {
    write_cache_file(m_path, IrradianceCache(CacheSettings{0.3f, 2, 16}), inputs);
    const CacheFileLoad loaded = read_cache_file(m_path, inputs);
    ASSERT_TRUE(loaded.cache) << loaded.rejection;
    EXPECT_TRUE(loaded.cache->records().empty());
    EXPECT_EQ(loaded.cache->settings().accuracy, 0.3f);
    EXPECT_EQ(fs::file_size(m_path), header_size + 8);
}

TEST_F(CacheFile, OtherInputsAreStale) {
    write_cache_file(m_path, random_cache(10), inputs);
    const CacheFileLoad loaded = read_cache_file(m_path, inputs + 1);
    EXPECT_FALSE(loaded.cache);
    EXPECT_EQ(loaded.rejection, "stale (made from other inputs)");
}

TEST_F(CacheFile, MissingFileIsMissing) {
    const CacheFileLoad loaded = read_cache_file(m_path, inputs);
    EXPECT_FALSE(loaded.cache);
    EXPECT_EQ(loaded.rejection, "missing");
}

TEST_F(CacheFile, DirectoryIsRejectedWithTheOsReason) {
    fs::create_directory(m_path);
    const CacheFileLoad loaded = read_cache_file(m_path, inputs);
    EXPECT_FALSE(loaded.cache);
    EXPECT_EQ(loaded.rejection.rfind("cannot read: ", 0), 0u) << loaded.rejection;
    EXPECT_GT(loaded.rejection.size(), std::string("cannot read: ").size());
}

TEST_F(CacheFile, TruncatedFilesAreRejected) {
    write_cache_file(m_path, random_cache(200), inputs);
    const Bytes whole = read_bytes();
    for (const size_t cut : {size_t(0), size_t(4), size_t(10), size_t(20), header_size - 1, header_size,
                             header_size + 100 * record_size + 7, whole.size() - 8, whole.size() - 1}) {
        const CacheFileLoad loaded = load(Bytes(whole.begin(), whole.begin() + std::ptrdiff_t(cut)));
        EXPECT_FALSE(loaded.cache) << "cut at " << cut;
        EXPECT_EQ(loaded.rejection.rfind("truncated", 0), 0u) << "cut at " << cut << ": " << loaded.rejection;
    }
}

TEST_F(CacheFile, AnyFlippedByteIsRejectedAndInRecordsByTheChecksum) {
    write_cache_file(m_path, random_cache(20), inputs);
    const Bytes whole = read_bytes();
    for (size_t i = 0; i < whole.size(); ++i) {
        Bytes damaged = whole;
        damaged[i] ^= 0x20;
        const CacheFileLoad loaded = load(damaged);
        ASSERT_FALSE(loaded.cache) << "byte " << i;
        if (i >= header_size && i < whole.size() - 8) {
            ASSERT_EQ(loaded.rejection, "corrupt: checksum mismatch") << "byte " << i;
        }
    }
}

TEST_F(CacheFile, WrongMagicIsRejectedNamingIt) {
    write_cache_file(m_path, random_cache(3), inputs);
    Bytes bytes = read_bytes();
    bytes[2] = 'X';
    reseal(bytes);
    const CacheFileLoad loaded = load(bytes);
    EXPECT_FALSE(loaded.cache);
    EXPECT_NE(loaded.rejection.find("magic"), std::string::npos) << loaded.rejection;
}

TEST_F(CacheFile, OtherVersionIsRejectedNamingIt) {
    write_cache_file(m_path, random_cache(3), inputs);
    Bytes bytes = read_bytes();
    put_le(bytes, version_offset, 2, 4);
    reseal(bytes);
    EXPECT_EQ(load(bytes).rejection, "other format version 2");
}

TEST_F(CacheFile, CraftedValuesWithCorrectChecksumAreCorruptNotAnAbort) {
    write_cache_file(m_path, random_cache(5), inputs);
    const Bytes whole = read_bytes();
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    struct Patch {
        size_t offset_in_record;
        float value;
    };
    // p.x, n.y, E.g, radius, a rotational and a translational gradient component.
    for (const Patch patch :
         {Patch{36, nan}, Patch{36, 0}, Patch{36, -1}, Patch{36, inf}, Patch{0, nan}, Patch{0, 1e30f}, Patch{16, 5},
          Patch{28, -1}, Patch{28, inf}, Patch{40, nan}, Patch{76, inf}}) {
        Bytes bytes = whole;
        put_float(bytes, header_size + 3 * record_size + patch.offset_in_record, patch.value);
        reseal(bytes);
        const CacheFileLoad loaded = load(bytes);
        EXPECT_FALSE(loaded.cache);
        EXPECT_EQ(loaded.rejection.rfind("corrupt: record 3: ", 0), 0u) << loaded.rejection;
    }
    Bytes bad_settings = whole;
    put_float(bad_settings, accuracy_offset, nan);
    reseal(bad_settings);
    EXPECT_EQ(load(bad_settings).rejection.rfind("corrupt: accuracy", 0), 0u);
}

TEST_F(CacheFile, NanRadiusNamesTheRadius) {
    write_cache_file(m_path, random_cache(5), inputs);
    Bytes bytes = read_bytes();
    put_float(bytes, header_size + 2 * record_size + radius_in_record, std::numeric_limits<float>::quiet_NaN());
    reseal(bytes);
    EXPECT_EQ(load(bytes).rejection, "corrupt: record 2: radius not in (0, 2^30]");
}

TEST_F(CacheFile, AbsurdRecordCountIsRejectedBeforeAllocating) {
    write_cache_file(m_path, random_cache(5), inputs);
    Bytes bytes = read_bytes();
    put_le(bytes, count_offset, uint64_t(1) << 60, 8);
    reseal(bytes);
    EXPECT_EQ(load(bytes).rejection.rfind("truncated", 0), 0u);
    put_le(bytes, count_offset, 4, 8);  // one record fewer: the last one's bytes are left over
    reseal(bytes);
    EXPECT_EQ(load(bytes).rejection, "corrupt: 112 bytes after the checksum");
}

TEST_F(CacheFile, WritingLeavesNoPartialFileAndReplacesAnOldOne) {
    write_cache_file(m_path, random_cache(50, 1), inputs);
    const IrradianceCache second = random_cache(30, 2);
    write_cache_file(m_path, second, inputs);
    EXPECT_FALSE(fs::exists(m_path + ".partial"));
    const CacheFileLoad loaded = read_cache_file(m_path, inputs);
    ASSERT_TRUE(loaded.cache) << loaded.rejection;
    EXPECT_EQ(bits_of(*loaded.cache), bits_of(second));
}

TEST_F(CacheFile, WritingIntoAMissingFolderThrowsAndLeavesNothing) {
    const std::string path = m_path + "/cache.slirr";
    EXPECT_THROW(write_cache_file(path, random_cache(3), inputs), std::runtime_error);
    EXPECT_FALSE(fs::exists(m_path));
}

}  // namespace
}  // namespace steadylight
