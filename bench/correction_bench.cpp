// L_t's correction of the static records (passes/record_correction.h) on its own, in process:
// per scene the segment's static cache once, then at a few frames the frame's dynamic map as the
// localized method makes it, and correct_static_cache run several times over it. Prints the best
// and the median time of the runs (whole runs of the renderer move by a tenth from run to run on
// a shared machine; a phase of 0.03 s inside them tells little), the records, the dynamic
// photons, the points the correction is estimated at, what a point reads (its photons within the
// finest disc that reads them one by one and the cells within the coarsest), how far the
// correction from cells is from the one of every photon one by one (the RMS over the points of
// their difference, over the RMS of the correction), how far the records' change taken from the
// points is from each record's own estimate, and a checksum of the corrected records (the sum of
// their irradiance) to tell a change of the correction that is exact from one that is not.
// Asserts nothing.
// Run: build/correction_bench [--scenes ball,table] [--frames N] [--size WxH] [--runs N]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "scene_bench_options.h"
#include "steadylight/base/stopwatch.h"
#include "steadylight/passes/frame_photons.h"
#include "steadylight/passes/record_correction.h"
#include "steadylight/passes/segment_cache.h"
#include "steadylight/passes/segment_pass.h"

using namespace steadylight;

namespace {

using Options = SceneBenchOptions;

/// Per point, the photons within the finest disc that reads them one by one and the cells within
/// the coarsest: what a point with every level reads (an upper bound: a point with fewer reads
/// less).
double read_per_point(const IrradianceCache& cache, const CorrectionPoints& points, const CorrectionPhotons& photons,
                      const CorrectionSettings& settings) {
    const float coarsest = level_radius(settings, settings.levels - 1);
    const float one_by_one = level_radius(settings, first_summed_level(settings) - 1);
    std::vector<Neighbour> found;
    double sum = 0;
    for (size_t j = 0; j < points.size(); ++j) {
        const IrradianceRecord& record = cache.records()[points.record(j)];
        photons.map().within(record.p, one_by_one, found);
        sum += double(found.size());
        photons.clusters_within(record.p, coarsest, found);
        sum += double(found.size());
    }
    return points.size() == 0 ? 0.0 : sum / double(points.size());
}

/// The RMS over the points of the correction from cells less the one of every photon one by one,
/// over the RMS of the latter (luminance).
double clustering_difference(const IrradianceCache& cache, const CorrectionPoints& points, const PhotonMap& dynamic,
                             const CorrectionSettings& settings) {
    const CorrectionPhotons clustered(dynamic, settings), one_by_one(dynamic, settings, 0);
    double difference2 = 0, correction2 = 0;
    for (size_t j = 0; j < points.size(); ++j) {
        const IrradianceRecord& record = cache.records()[points.record(j)];
        const double c = luminance(correction_at(clustered, record.p, record.n, settings, points.probes(j)));
        const double e = luminance(correction_at(one_by_one, record.p, record.n, settings, points.probes(j)));
        difference2 += (c - e) * (c - e), correction2 += e * e;
    }
    return correction2 > 0 ? std::sqrt(difference2 / correction2) : 0.0;
}

/// The RMS over the records of their change taken from the points less their change estimated at
/// each record (`every_record`: points at every record), over the RMS of the latter (luminance).
double points_difference(const IrradianceCache& cache, const IrradianceCache& from_points,
                         const IrradianceCache& every_record) {
    double difference2 = 0, correction2 = 0;
    for (size_t i = 0; i < cache.records().size(); ++i) {
        const double before = luminance(cache.records()[i].E);
        const double c = luminance(from_points.records()[i].E) - before;
        const double e = luminance(every_record.records()[i].E) - before;
        difference2 += (c - e) * (c - e), correction2 += e * e;
    }
    return correction2 > 0 ? std::sqrt(difference2 / correction2) : 0.0;
}

/// The sum of every record's irradiance, in double.
double checksum(const IrradianceCache& cache) {
    double sum = 0;
    for (const IrradianceRecord& record : cache.records()) sum += double(record.E.r) + record.E.g + record.E.b;
    return sum;
}

void run_scene(const std::string& name, const Options& options) {
    BenchScene opened(name, options);
    auto& [scene, tracer, bsdfs] = opened;
    const PhotonMappingSettings photon;
    const CorrectionSettings settings = LocalizedSettings{}.correction;
    const int runs = std::max(1, options.number("runs", 7));
    const Segment segment{0, scene.frame_count() - 1};
    // As a localized render makes them: the static photon paths, the static cache from their
    // photons, frames composing their maps from the paths.
    std::shared_ptr<const StaticPhotonPaths> traced_paths = trace_segment_photon_paths(scene, tracer, segment, photon);
    const StaticPhotonPaths* paths = traced_paths.get();
    const StaticSolution solution{run_segment_pass(scene, tracer, segment, photon, paths), 0, false, "", traced_paths};

    CorrectionSettings at_every_record = settings;
    at_every_record.point_spacing = 0;
    const CorrectionPoints every_record;
    std::printf("\n%s, %dx%d, %ld static records, %d runs per frame\n", name.c_str(), options.width, options.height,
                solution.records(), runs);
    std::printf("%5s %10s %10s %12s %8s %12s %14s %12s %16s\n", "frame", "best ms", "median ms", "dyn.photons",
                "points", "read/point", "vs one by one", "vs records", "checksum");
    const int frames = std::max(1, std::min(options.frames, scene.frame_count()));
    for (int i = 0; i < frames; ++i) {
        // Frames spread over the animation, the first one left out (nothing has moved yet).
        const int frame = std::min(scene.frame_count() - 1, 1 + i * std::max(1, (scene.frame_count() - 1) / frames));
        const PlacedFrame placed(scene, tracer, bsdfs, frame);
        const FrameContext& context = placed.context();
        FrameStats stats;
        const FramePhotons traced(context, photon, stats, paths, paths ? paths->irradiance.get() : nullptr,
                                  ChangedValues::carried, solution.compose_photons);
        const PhotonMap& dynamic = traced.maps.dynamic;
        const CorrectionPoints& points = *solution.correction_points;
        points.make(context, solution.cache, settings);
        every_record.make(context, solution.cache, at_every_record);
        std::vector<double> seconds;
        double sum = 0;
        for (int run = 0; run < runs; ++run) {
            const Stopwatch time;
            const IrradianceCache corrected = correct_static_cache(solution.cache, dynamic, settings, &points);
            seconds.push_back(time.elapsed_s());
            sum = checksum(corrected);
        }
        std::sort(seconds.begin(), seconds.end());
        const double vs_records =
            points_difference(solution.cache, correct_static_cache(solution.cache, dynamic, settings, &points),
                              correct_static_cache(solution.cache, dynamic, at_every_record, &every_record));
        std::printf("%5d %10.2f %10.2f %12zu %8zu %12.0f %13.2f%% %11.2f%% %16.9e\n", frame, 1e3 * seconds.front(),
                    1e3 * seconds[seconds.size() / 2], dynamic.size(), points.size(),
                    read_per_point(solution.cache, points, CorrectionPhotons(dynamic, settings), settings),
                    100 * clustering_difference(solution.cache, points, dynamic, settings), 100 * vs_records, sum);
    }
}

}  // namespace

int main(int argc, char** argv) {
    const Options options = parse_scene_bench_options(argc, argv, 4);
    for (const std::string& name : options.scenes) run_scene(name, options);
    return 0;
}
