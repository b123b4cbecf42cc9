// Loading a segment's static cache, or computing and saving it (segment_cache.h).
#include "steadylight/passes/segment_cache.h"

#include <filesystem>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "steadylight/base/stopwatch.h"
#include "steadylight/irradiance/cache_file.h"

namespace steadylight {

std::string static_cache_file(const std::string& cache_file, const std::string& out_dir, const Scene& scene,
                              const Segment& segment) {
    namespace fs = std::filesystem;
    fs::path file = cache_file.empty() ? fs::path(out_dir) / (scene.name() + ".irrcache") : fs::path(cache_file);
    if (scene.segments().size() > 1)
        file.replace_filename(fmt::format("{}_{:04d}-{:04d}{}", file.stem().string(), segment.first, segment.last,
                                          file.extension().string()));
    return file.string();
}

StaticSolution load_or_run_segment_pass(const Scene& scene, RayTracer& tracer, const Segment& segment,
                                        const PhotonMappingSettings& settings, const std::string& file) {
    const Stopwatch time;
    const uint64_t inputs = static_inputs_hash(scene, segment, settings);
    CacheFileLoad load = read_cache_file(file, inputs);
    if (load.cache) {
        StaticSolution solution{std::move(*load.cache), time.elapsed_s(), true, ""};
        spdlog::info("static cache: {} records loaded from {}", solution.records(), file);
        return solution;
    }
    StaticSolution solution{run_segment_pass(scene, tracer, segment, settings), 0, false, load.rejection};
    write_cache_file(file, solution.cache, inputs);
    solution.seconds = time.elapsed_s();
    spdlog::info("static cache: {} records computed in {:.2f} s ({}), saved to {}", solution.records(), solution.seconds,
                 solution.file_note, file);
    return solution;
}

}  // namespace steadylight
