// Fuzzes the static irradiance cache file reader (irradiance/cache_file.h). The mutated file gets
// the inputs hash the reader expects and a correct checksum, so that the parser behind those
// checks is reached; a cache it accepts is then interpolated at each record.
#include <cstring>
#include <vector>

#include "fuzz_harness.h"
#include "steadylight/base/hash.h"
#include "steadylight/irradiance/cache_file.h"

namespace {

constexpr uint64_t inputs_hash = 0x5eedf11e;
constexpr size_t inputs_hash_offset = 34;  // after "SLIRRCACHE", version, count, 3 settings
constexpr size_t checksum_size = 8;

void put_u64(unsigned char* at, uint64_t v) {
    for (int k = 0; k < 8; ++k) at[k] = static_cast<unsigned char>(v >> (8 * k));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace steadylight;
    std::vector<unsigned char> bytes(data, data + size);
    if (bytes.size() >= inputs_hash_offset + 8 + checksum_size) {
        put_u64(&bytes[inputs_hash_offset], inputs_hash);
        const size_t checked = bytes.size() - checksum_size;
        put_u64(&bytes[checked], checksum64(bytes.data(), checked));
    }
    const std::string path = fuzz::write_input(bytes.data(), bytes.size(), "scene.irrcache");
    const CacheFileLoad load = read_cache_file(path, inputs_hash);
    if (load.cache.has_value() == !load.rejection.empty()) std::abort();
    if (load.cache)
        for (const IrradianceRecord& record : load.cache->records()) (void)load.cache->interpolate(record.p, record.n);
    return 0;
}
