// The steadylight command line: parses flags into RenderSettings and calls the library.
// Errors are caught once, here: the message goes to stderr and the exit code is 1.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <memory>
#include <regex>

#include "steadylight/base/error.h"
#include "steadylight/render.h"

using namespace steadylight;

namespace {

void parse_size(const std::string& text, RenderSettings& settings) {
    static const std::regex pattern(R"((\d{1,5})x(\d{1,5}))");
    std::smatch match;
    if (!std::regex_match(text, match, pattern) || std::stoi(match[1]) < 1 || std::stoi(match[2]) < 1)
        throw InputError("--size", "expected WIDTHxHEIGHT, for example 320x240, got \"" + text + "\"");
    settings.width = std::stoi(match[1]);
    settings.height = std::stoi(match[2]);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"steadylight: global-illumination animations with localized final gathering"};
    app.set_version_flag("--version", std::string("steadylight ") + STEADYLIGHT_VERSION);
    app.require_subcommand(1);

    RenderSettings settings;
    std::string frames, size;
    int threads = 0;
    CLI::App* render = app.add_subcommand("render", "Render the frames of a scene");
    render->add_option("scene", settings.scene_file, "Scene file (JSON)")->required();
    render->add_option("--frames", frames, "Frame N or inclusive range A-B (default: all)");
    std::optional<int> spp;
    render->add_option("--spp", spp, "Samples per pixel (default: 64 for path, 16 for photon)")
        ->check(CLI::Range(1, 1 << 20));
    render->add_option("--size", size, "Image size WIDTHxHEIGHT (default: the scene's)");
    render->add_option("--threads", threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 1024));
    render->add_option("--out", settings.out_dir, "Output folder")->capture_default_str();
    render->add_option("--method,--integrator", settings.method,
                       "path: path-traced ground truth; photon: photon mapping with final gathering")
        ->capture_default_str()->check(CLI::IsMember({"path", "photon"}));
    PhotonMappingSettings& photon = settings.photon;
    render->add_option("--photons", photon.photons.global_photons, "photon: paths emitted for the global map")
        ->capture_default_str()->check(CLI::Range(0L, 1L << 34));
    render->add_option("--caustic-photons", photon.photons.caustic_photons, "photon: paths emitted for the caustic map")
        ->capture_default_str()->check(CLI::Range(0L, 1L << 34));
    int gather_samples = photon.gather.theta_strata * photon.gather.phi_strata;
    render->add_option("--gather-samples", gather_samples,
                       "photon: final-gather rays per record, as M x 2M strata (rounded)")
        ->capture_default_str()->check(CLI::Range(8, 1 << 16));
    render->add_option("--cache-accuracy", photon.cache.accuracy, "photon: Ward's a; smaller = more records")
        ->capture_default_str()->check(CLI::Range(0.01f, 2.0f));
    render->add_option("--cache-spacing", photon.cache.min_spacing_px, "photon: smallest record spacing in pixels")
        ->capture_default_str()->check(CLI::Range(0.5f, 1000.0f));
    render->add_option("--cache-max-spacing", photon.cache.max_spacing_px, "photon: largest record spacing in pixels")
        ->capture_default_str()->check(CLI::Range(1.0f, 10000.0f));
    render->add_option("--direct-samples", photon.shading.direct_samples, "photon: shadow rays per diffuse hit and camera ray")
        ->capture_default_str()->check(CLI::Range(1, 4096));
    render->add_flag("!--jittered-gather", photon.gather.fixed_directions,
                     "photon: new gather directions per record instead of one fixed set");
    render->add_option("--max-depth", settings.path.max_depth, "Maximum path length in bounces")
        ->capture_default_str()->check(CLI::Range(0, 10000));
    render->add_flag("!--no-progress", settings.show_progress, "No progress output");

    std::string info_scene;
    CLI::App* info = app.add_subcommand("info", "Describe a scene: objects, lights, frames, static/dynamic");
    info->add_option("scene", info_scene, "Scene file (JSON)")->required();

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help and --version exit 0; usage errors exit 2, as most command-line tools do.
        return app.exit(e) == 0 ? 0 : 2;
    }

    try {
        if (*info) {
            std::fputs(describe_scene(info_scene).c_str(), stdout);
            return 0;
        }
        if (!frames.empty()) settings.frames = parse_frame_range(frames);
        if (!size.empty()) parse_size(size, settings);
        if (spp) settings.path.samples_per_pixel = settings.photon.shading.samples_per_pixel = *spp;
        settings.photon.gather.theta_strata = std::max(2, int(std::lround(std::sqrt(gather_samples / 2.0))));
        settings.photon.gather.phi_strata = 2 * settings.photon.gather.theta_strata;
        if (settings.photon.cache.max_spacing_px < settings.photon.cache.min_spacing_px)
            throw InputError("--cache-max-spacing", "must not be smaller than --cache-spacing");
        std::unique_ptr<tbb::global_control> thread_limit;
        if (threads > 0)
            thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(threads));
        const RenderSummary summary = render_animation(settings);
        spdlog::info("{} frame(s) written to {} in {:.1f} s", summary.frames_written, settings.out_dir, summary.seconds);
        return 0;
    } catch (const InputError& e) {
        std::fprintf(stderr, "steadylight: error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "steadylight: internal error: %s\n", e.what());
        return 1;
    }
}
