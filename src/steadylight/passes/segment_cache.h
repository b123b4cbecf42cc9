// The segment pass's result kept on disk: a segment's static irradiance cache is loaded from its
// file when the file was made from the same inputs (static_inputs_hash), and otherwise computed
// by the segment pass and saved there, for later runs, `steadylight bake`, and other machines
// (irradiance/cache_file.h holds the format). Many processes may share one file: the one that
// finds it missing computes it under a lock (`.<file name>.lock` beside it) while the others wait
// and then load it; a farm worker may instead require it (`render --require-cache`), so that a
// missing or stale file is an error rather than a second computation.
#pragma once

#include <memory>
#include <string>

#include "steadylight/passes/centre_rays.h"
#include "steadylight/passes/pixel_reuse.h"
#include "steadylight/passes/record_correction.h"
#include "steadylight/passes/segment_pass.h"
#include "steadylight/photons/photon_paths.h"

namespace steadylight {

/// What the segment pass leaves for every frame of its segment: the static irradiance cache,
/// and the static photon paths when frames reuse them.
struct StaticSolution {
    IrradianceCache cache;
    double seconds = 0;                                     // to compute or to load it
    bool loaded = false;                                    // read from the cache file instead of computed
    std::string file_note;                                  // why the file was not used, when it was not
    std::shared_ptr<const StaticPhotonPaths> photon_paths;  // null: frames trace all their photons
    bool compose_photons = true;  // false: frames trace all their photons and only tell photon_paths' from them
    std::shared_ptr<const StaticFrame> static_frame;  // null: frames shade every pixel
    /// Where L_t is estimated, made by the first frame that needs them.
    std::shared_ptr<const CorrectionPoints> correction_points = std::make_shared<CorrectionPoints>();
    /// What the pixel centres see, made by the first frame that needs it (a still view only).
    std::shared_ptr<const KeptCentreRays> centre_rays = std::make_shared<KeptCentreRays>();
    /// The direct light of pixels whose shadow rays alone may change, kept by the frames as they
    /// shade it (a still view only).
    std::shared_ptr<KeptDirectLight> kept_direct_light = std::make_shared<KeptDirectLight>();

    long records() const { return long(cache.records().size()); }
};

/// The cache file of `segment`: `cache_file`, or `<out_dir>/<scene>.irrcache` when it is empty;
/// with several segments each gets its frames added: `<scene>_0000-0029.irrcache`.
std::string static_cache_file(const std::string& cache_file, const std::string& out_dir, const Scene& scene,
                              const Segment& segment);

/// What a run does when a segment's cache file is missing or stale.
enum class CacheUse {
    load_or_compute,  // compute it (once: under the file's lock) and save it
    require,          // an InputError naming the file (`render --require-cache`)
};

/// The static solution of `segment`: from `file` when that matches its inputs, else computed
/// (run_segment_pass) and saved to `file`, holding `.<file name>.lock` meanwhile so that other
/// processes wait and load it rather than compute it again; with CacheUse::require an
/// InputError instead. Logs which, with the record count. `paths`, when given, are the
/// segment's static photon paths: the solution keeps them, and a computed cache starts from
/// their photons rather than tracing its own.
StaticSolution load_or_run_segment_pass(const Scene& scene, RayTracer& tracer, const Segment& segment,
                                        const PhotonMappingSettings& settings, const std::string& file,
                                        CacheUse use = CacheUse::load_or_compute,
                                        std::shared_ptr<const StaticPhotonPaths> paths = nullptr);

}  // namespace steadylight
