// The photon-mapping method (--method photon) on BALL frame 0 at 320x240: time per phase,
// irradiance records, and relative RMSE against a converged path-traced frame; then the path
// tracer at growing sample counts, to see how long it needs for the same error. Prints, asserts
// nothing. The reference (path tracer, 2048 spp, independent seed) is cached in the working
// folder as ball_0000_reference.exr, since it takes minutes.
// Run: build/photon_frame_bench [reference.exr]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "steadylight/base/freed_memory.h"
#include "steadylight/base/stopwatch.h"
#include "steadylight/methods/path_tracer.h"
#include "steadylight/methods/photon_mapping.h"
#include "steadylight/output/image_writer.h"

using namespace steadylight;

namespace {

/// Relative RMSE of luminance clamped at 1 (display-referred, as the PNG shows it; unclamped,
/// the light's anti-aliased edge pixels dominate).
double relative_rmse(const Image& image, const Image& reference) {
    double sum2 = 0, sum_ref = 0;
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        const double y = std::min(1.0f, luminance(image.pixels[i])),
                     y_ref = std::min(1.0f, luminance(reference.pixels[i]));
        sum2 += (y - y_ref) * (y - y_ref);
        sum_ref += y_ref;
    }
    const double n = double(image.pixels.size());
    return std::sqrt(sum2 / n) / (sum_ref / n);
}

Image reference_image(const PreparedFrame& ball, const std::string& path) {
    if (std::filesystem::exists(path)) return read_exr(path);
    std::printf("rendering the reference (path tracer, 2048 spp) into %s ...\n", path.c_str());
    const Stopwatch time;
    const Image reference = render_path_traced(ball.context(), {.samples_per_pixel = 2048, .seed = 0x7e7e}).beauty;
    std::printf("  %.1f s\n", time.elapsed_s());
    write_exr(path, reference);
    return reference;
}

}  // namespace

int main(int argc, char** argv) {
    steadylight::keep_freed_memory_mapped();  // frames reuse their large arrays (freed_memory.h)
    const Scene scene(load_scene_desc(std::string(STEADYLIGHT_SOURCE_DIR) + "/scenes/ball.json"));
    const PreparedFrame ball(scene, 0);
    const Image reference = reference_image(ball, argc > 1 ? argv[1] : "ball_0000_reference.exr");

    // The photon method, defaults as the command line has them.
    const PhotonFrame frame = render_photon_mapped(ball.context(), PhotonMappingSettings{});
    const FrameStats& s = frame.stats;
    const double photon_rmse = relative_rmse(frame.beauty, reference);
    std::printf("\nphoton mapping, BALL frame 0, 320x240, default settings\n");
    std::printf("  photon tracing                              %7.3f s  (%ld global, %ld caustic photons stored)\n",
                s.photon_tracing_s, s.global_photons_stored, s.caustic_photons_stored);
    std::printf("  irradiance at photons + cache (gathering)   %7.3f s  (%ld records, %.2fM gather rays)\n", s.cache_s,
                s.irradiance_records, double(s.gather_rays) / 1e6);
    std::printf("  shading (direct, look-ups, specular)        %7.3f s  (caustics %.3f s cpu)\n", s.shading_s,
                s.caustics_s);
    std::printf("  total                                       %7.3f s\n", s.total_s);
    std::printf("  relative RMSE vs reference                  %7.4f\n", photon_rmse);

    // The path tracer at growing sample counts: how long until it matches that error?
    std::printf("\npath tracer, same frame\n%8s %10s %10s\n", "spp", "seconds", "rel. RMSE");
    double path_time_at_photon_error = -1;
    for (int spp = 4; spp <= 1024; spp *= 2) {
        const Stopwatch time;
        const Image image = render_path_traced(ball.context(), {.samples_per_pixel = spp}).beauty;
        const double seconds = time.elapsed_s(), rmse = relative_rmse(image, reference);
        std::printf("%8d %10.3f %10.4f\n", spp, seconds, rmse);
        if (rmse <= photon_rmse) {
            path_time_at_photon_error = seconds;
            break;
        }
    }
    if (path_time_at_photon_error > 0)
        std::printf("\npath tracer time to reach the photon method's error / photon time: %.1fx\n",
                    path_time_at_photon_error / s.total_s);
    else
        std::printf("\nthe path tracer did not reach the photon method's error by 1024 spp\n");
    return 0;
}
