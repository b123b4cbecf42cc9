// Loading a segment's static cache, or computing and saving it (segment_cache.h).
#include "steadylight/passes/segment_cache.h"

#include <algorithm>
#include <filesystem>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "steadylight/base/error.h"
#include "steadylight/base/lock_file.h"
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

namespace {

/// `<dir>/.<name>.lock` for the cache file `<dir>/<name>`: hidden, as the folder's own lock.
std::string cache_lock_file(const std::string& file) {
    const std::filesystem::path path(file);
    std::string name = path.filename().string();
    name.insert(0, 1, '.');
    name += ".lock";
    return (path.parent_path() / name).string();
}

int segment_index(const Scene& scene, const Segment& segment) {
    const std::vector<Segment>& segments = scene.segments();
    const auto found =
        std::find_if(segments.begin(), segments.end(), [&](const Segment& s) { return s.first == segment.first; });
    return int(found - segments.begin());
}

StaticSolution loaded_solution(CacheFileLoad& load, const Stopwatch& time, const std::string& file,
                               std::shared_ptr<const StaticPhotonPaths> paths) {
    StaticSolution solution{std::move(*load.cache), time.elapsed_s(), true, "", std::move(paths)};
    spdlog::info("static cache: {} records loaded from {} in {:.3f} s", solution.records(), file, solution.seconds);
    return solution;
}

}  // namespace

StaticSolution load_or_run_segment_pass(const Scene& scene, RayTracer& tracer, const Segment& segment,
                                        const PhotonMappingSettings& settings, const std::string& file, CacheUse use,
                                        std::shared_ptr<const StaticPhotonPaths> paths) {
    const Stopwatch time;
    const uint64_t inputs = static_inputs_hash(scene, segment, settings);
    CacheFileLoad load = read_cache_file(file, inputs);
    if (load.cache) return loaded_solution(load, time, file, paths);
    if (use == CacheUse::require)
        throw InputError(file, fmt::format("the static cache of frames {}-{} is not usable ({}), and --require-cache "
                                           "does not compute it; bake it first with the same settings (steadylight "
                                           "bake SCENE --segment {}), or render without --require-cache",
                                           segment.first, segment.last, load.rejection, segment_index(scene, segment)));
    // Another process may be computing it: wait for its lock, then look again.
    const std::unique_ptr<LockFile> lock = LockFile::lock(cache_lock_file(file), "the static cache " + file);
    load = read_cache_file(file, inputs);
    if (load.cache) return loaded_solution(load, time, file, paths);
    StaticSolution solution{run_segment_pass(scene, tracer, segment, settings, paths.get()), 0, false, load.rejection,
                            paths};
    write_cache_file(file, solution.cache, inputs);
    solution.seconds = time.elapsed_s();
    spdlog::info("static cache: {} records computed in {:.2f} s ({}), saved to {}", solution.records(),
                 solution.seconds, solution.file_note, file);
    return solution;
}

}  // namespace steadylight
