// Saving and loading the static irradiance cache of an animation segment. The static cache is
// computed once per segment and reused by every frame (Tawara et al. 2002, "Exploiting temporal
// coherence in global illumination"); saved to a file, it is also reused by later runs and other
// machines, and loaded instead of recomputed when it was made from the same inputs.
//
// The file is little-endian binary, written field by field (floats as their 32-bit patterns):
//   "SLIRRCACHE" | u32 format version | u64 record count | f32 accuracy, min_spacing_px,
//   max_spacing_px | u64 inputs hash | records (28 f32 each: p, n, E, radius, rotational
//   gradient r g b, translational gradient r g b) | u64 checksum64 of all bytes before it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "steadylight/irradiance/irradiance_cache.h"

namespace steadylight {

/// \brief Writes `cache` to `path` atomically: a versioned header (magic, format version, record
/// count, the CacheSettings, `inputs_hash`: a hash of everything the cache depends on), the
/// records in insertion order, and a checksum of everything before it.
/// Throws std::runtime_error naming `path` when the file cannot be written.
void write_cache_file(const std::string& path, const IrradianceCache& cache, uint64_t inputs_hash);

struct CacheFileLoad {
    std::optional<IrradianceCache> cache;  // set when the file is usable
    /// Why not, when it is not: "missing", "stale (made from other inputs)", "corrupt: ...",
    /// "truncated (...)", "other format version N", "cannot read: <OS reason>".
    std::string rejection;
};

/// \brief Reads `path` when it exists, is intact, of this format version, and was made from
/// `inputs_hash`. A missing, stale or damaged file is not an error: the caller recomputes and
/// overwrites it. Records are inserted as stored (their radii were clamped before saving), and
/// every one is validated first, so a crafted file is rejected rather than aborting the program.
CacheFileLoad read_cache_file(const std::string& path, uint64_t inputs_hash);

}  // namespace steadylight
