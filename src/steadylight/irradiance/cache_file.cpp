// The irradiance cache file of cache_file.h. Every field is encoded byte by byte, little-endian,
// so the layout depends neither on struct padding nor on the host. Reading checks the magic, the
// version, the length the header implies (before allocating for records), the checksum, the
// inputs hash, and then every value, so that a damaged or crafted file is rejected with a reason
// and never reaches the SL_CHECKs of IrradianceCache.
#include "steadylight/irradiance/cache_file.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <vector>

#include "steadylight/base/atomic_file.h"
#include "steadylight/base/hash.h"

namespace steadylight {
namespace {

constexpr std::string_view magic = "SLIRRCACHE";
constexpr uint32_t format_version = 1;
constexpr size_t header_size = magic.size() + 4 + 8 + 3 * 4 + 8;  // 42
constexpr size_t record_size = 28 * 4;                            // 112
constexpr size_t checksum_size = 8;

// Positions, radii and accuracy stay within 2^30 so that the cache's hash grid, whose cells go
// down to 2^-32 units (irradiance_cache.cpp), computes cell coordinates well inside int64.
constexpr float max_magnitude = 0x1p30f;
// Normals are saved unit length; this allows for rounding only.
constexpr float normal_tolerance = 1e-3f;

using Bytes = std::vector<unsigned char>;

/// Appends little-endian fields.
class ByteWriter {
public:
    explicit ByteWriter(size_t size) { m_bytes.reserve(size); }
    void u32(uint32_t v) { put(v, 4); }
    void u64(uint64_t v) { put(v, 8); }
    void f32(float v) { u32(std::bit_cast<uint32_t>(v)); }
    void vec3(Vec3 v) {
        f32(v.x);
        f32(v.y);
        f32(v.z);
    }
    void text(std::string_view s) {
        for (const char c : s) m_bytes.push_back(static_cast<unsigned char>(c));
    }
    const Bytes& bytes() const { return m_bytes; }

private:
    void put(uint64_t v, int size) {
        for (int k = 0; k < size; ++k) m_bytes.push_back(static_cast<unsigned char>(v >> (8 * k)));
    }
    Bytes m_bytes;
};

/// Reads little-endian fields in order; the caller has checked that the bytes are there.
class ByteReader {
public:
    explicit ByteReader(const unsigned char* at) : m_at(at) {}
    uint32_t u32() { return uint32_t(get(4)); }
    uint64_t u64() { return get(8); }
    float f32() { return std::bit_cast<float>(u32()); }
    Vec3 vec3() { return {f32(), f32(), f32()}; }  // braced lists evaluate left to right

private:
    uint64_t get(int size) {
        uint64_t v = 0;
        for (int k = 0; k < size; ++k) v |= uint64_t(m_at[k]) << (8 * k);
        m_at += size;
        return v;
    }
    const unsigned char* m_at;
};

struct Header {
    uint64_t record_count = 0;
    CacheSettings settings;
    uint64_t inputs_hash = 0;
};

void write_header(ByteWriter& out, const IrradianceCache& cache, uint64_t inputs_hash) {
    out.text(magic);
    out.u32(format_version);
    out.u64(cache.records().size());
    out.f32(cache.settings().accuracy);
    out.f32(cache.settings().min_spacing_px);
    out.f32(cache.settings().max_spacing_px);
    out.u64(inputs_hash);
}

/// The header fields after the magic and version, which header_problem() has checked.
Header read_header(const Bytes& bytes) {
    ByteReader in(bytes.data() + magic.size() + 4);
    Header header;
    header.record_count = in.u64();
    header.settings = {in.f32(), in.f32(), in.f32()};
    header.inputs_hash = in.u64();
    return header;
}

void write_record(ByteWriter& out, const IrradianceRecord& record) {
    out.vec3(record.p);
    out.vec3(record.n);
    out.f32(record.E.r);
    out.f32(record.E.g);
    out.f32(record.E.b);
    out.f32(record.radius);
    for (const Vec3& g : record.rotational_gradient) out.vec3(g);
    for (const Vec3& g : record.translational_gradient) out.vec3(g);
}

IrradianceRecord read_record(ByteReader& in) {
    IrradianceRecord record;
    record.p = in.vec3();
    record.n = in.vec3();
    record.E = {in.f32(), in.f32(), in.f32()};
    record.radius = in.f32();
    for (Vec3& g : record.rotational_gradient) g = in.vec3();
    for (Vec3& g : record.translational_gradient) g = in.vec3();
    return record;
}

/// Why a file starting with `prefix` (its first header_size bytes, or all of a shorter file)
/// is not a cache file of this version; empty when it may be one.
std::string header_problem(const Bytes& prefix) {
    const size_t known = std::min(prefix.size(), magic.size());
    if (!std::equal(prefix.begin(), prefix.begin() + std::ptrdiff_t(known), magic.begin()))
        return "corrupt: wrong magic (not a steadylight irradiance cache)";
    if (prefix.size() < magic.size() + 4) return "truncated (inside the header)";
    const uint32_t version = ByteReader(prefix.data() + magic.size()).u32();
    if (version != format_version) return "other format version " + std::to_string(version);
    if (prefix.size() < header_size) return "truncated (inside the header)";
    return "";
}

/// Why a file of `size` bytes does not hold exactly `count` records; empty when it does. Runs
/// before anything is allocated for them, so an absurd count costs nothing.
std::string length_problem(uintmax_t size, uint64_t count) {
    if (size < header_size + checksum_size) return "truncated (no room for the checksum)";
    if (count > (size - header_size - checksum_size) / record_size)
        return "truncated (" + std::to_string(size) + " bytes cannot hold the " + std::to_string(count) +
               " records its header promises)";
    const uintmax_t expected = header_size + count * record_size + checksum_size;
    if (size > expected) return "corrupt: " + std::to_string(size - expected) + " bytes after the checksum";
    return "";
}

bool within(float v, float limit) { return std::abs(v) <= limit; }  // false for NaN
bool within(Vec3 v, float limit) { return within(v.x, limit) && within(v.y, limit) && within(v.z, limit); }

std::string settings_problem(const CacheSettings& s) {
    if (!(s.accuracy > 0 && s.accuracy <= max_magnitude)) return "accuracy not in (0, 2^30]";
    if (!(s.min_spacing_px >= 0 && std::isfinite(s.min_spacing_px) && s.max_spacing_px >= 0 &&
          std::isfinite(s.max_spacing_px)))
        return "record spacing negative or not finite";
    return "";
}

/// Why `record` must not be inserted (IrradianceCache::insert would abort, or interpolation
/// misbehave); empty when it may.
std::string record_problem(const IrradianceRecord& record) {
    if (!within(record.p, max_magnitude)) return "position not finite or beyond 2^30";
    if (!(std::abs(length(record.n) - 1) <= normal_tolerance)) return "normal not of unit length";
    if (!is_finite(record.E) || !(std::min({record.E.r, record.E.g, record.E.b}) >= 0))
        return "irradiance negative or not finite";
    if (!(record.radius > 0 && record.radius <= max_magnitude)) return "radius not in (0, 2^30]";
    for (const Vec3& g : record.rotational_gradient)
        if (!is_finite(g)) return "rotational gradient not finite";
    for (const Vec3& g : record.translational_gradient)
        if (!is_finite(g)) return "translational gradient not finite";
    return "";
}

CacheFileLoad rejected(std::string why) { return {std::nullopt, std::move(why)}; }

/// The cache rebuilt from the records at `at`, each validated before it is inserted.
CacheFileLoad load_records(const unsigned char* at, const Header& header) {
    if (const std::string why = settings_problem(header.settings); !why.empty()) return rejected("corrupt: " + why);
    IrradianceCache cache(header.settings);
    ByteReader in(at);
    for (uint64_t i = 0; i < header.record_count; ++i) {
        const IrradianceRecord record = read_record(in);
        if (const std::string why = record_problem(record); !why.empty())
            return rejected("corrupt: record " + std::to_string(i) + ": " + why);
        cache.insert(record);
    }
    return {std::move(cache), ""};
}

std::string os_reason() { return std::generic_category().message(errno); }

struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

/// Reads `count` bytes into `to`; why not, or empty when all arrived.
std::string read_into(std::FILE* file, unsigned char* to, size_t count) {
    if (std::fread(to, 1, count, file) == count) return "";
    return std::ferror(file) ? "cannot read: " + os_reason() : "truncated (the file shrank while being read)";
}

void write_bytes(const std::string& path, const Bytes& bytes) {
    File file(std::fopen(path.c_str(), "wb"));
    if (!file) throw std::runtime_error(os_reason());
    if (std::fwrite(bytes.data(), 1, bytes.size(), file.get()) != bytes.size()) throw std::runtime_error(os_reason());
    // Closing flushes, which is where a full disk shows.
    if (std::fclose(file.release()) != 0) throw std::runtime_error(os_reason());
}

}  // namespace

void write_cache_file(const std::string& path, const IrradianceCache& cache, uint64_t inputs_hash) {
    ByteWriter out(header_size + cache.records().size() * record_size + checksum_size);
    write_header(out, cache, inputs_hash);
    for (const IrradianceRecord& record : cache.records()) write_record(out, record);
    out.u64(checksum64(out.bytes().data(), out.bytes().size()));
    write_file_atomically(path, [&](const std::string& file) { write_bytes(file, out.bytes()); });
}

CacheFileLoad read_cache_file(const std::string& path, uint64_t inputs_hash) {
    // Learn the size first: no file is the usual first run, and a directory has no size.
    std::error_code error;
    const uintmax_t size = std::filesystem::file_size(path, error);
    if (error == std::errc::no_such_file_or_directory) return rejected("missing");
    if (error) return rejected("cannot read: " + error.message());
    const File file(std::fopen(path.c_str(), "rb"));
    if (!file) return rejected("cannot read: " + os_reason());

    // Check the header and the length it implies before reading, and allocating for, the records.
    Bytes bytes(std::min<uintmax_t>(size, header_size));
    if (std::string why = read_into(file.get(), bytes.data(), bytes.size()); !why.empty()) return rejected(why);
    if (std::string why = header_problem(bytes); !why.empty()) return rejected(why);
    const Header header = read_header(bytes);
    if (std::string why = length_problem(size, header.record_count); !why.empty()) return rejected(why);

    // Read the rest, and check that nothing changed since it was written and by what it was made.
    bytes.resize(size);
    if (std::string why = read_into(file.get(), bytes.data() + header_size, size - header_size); !why.empty())
        return rejected(why);
    const size_t checked = size - checksum_size;
    if (checksum64(bytes.data(), checked) != ByteReader(bytes.data() + checked).u64())
        return rejected("corrupt: checksum mismatch");
    if (header.inputs_hash != inputs_hash) return rejected("stale (made from other inputs)");
    return load_records(bytes.data() + header_size, header);
}

}  // namespace steadylight
