// The truth suite's figures (docs/truth-suite.md): each suite scene rendered at its full size with
// the photon, localized and frozen methods at default settings, against the project's own
// converged path-traced references in tests/references/ (scripts/make_references.sh).
//   Per still reference frame and method: relative RMSE per pixel and on 4x4 blocks, the ratio of
//   mean luminance (quality/image_error.h; emitters and their border left out), frame time.
//   Per animated scene and method: temporal noise over the four common-random-numbers pairs,
//   over all pixels whose true change is small and "far" (where the light does not change), the
//   mean signed change against the reference's over the far pixels, the method's own mean change
//   there (free of the references' noise), and the references' own noise floor (the middle pair against the same pair
//   with another seed). The still references' own per-pixel noise, where the middle frame's common-random-numbers
//   reference exists with two seeds: RMSE(seed 0 - seed 1) / sqrt(2) is a 1024-sample frame's
//   noise, half that a 4096-sample one's (noise falls as 1 / sqrt(samples)). A method's error
//   against a noisy reference is sqrt(its own error^2 + the reference's noise^2), as the two are
//   independent; "without the reference's noise" prints sqrt(error^2 - noise^2), an estimate of
//   the method's own error against the truth (the middle frame's noise stands for frame 0's too).
// Frames whose reference is missing are skipped and said so. Prints, asserts nothing.
// --save DIR also writes each still frame's image (<scene>_<frame>_<method>.exr, float) and the
// pixels the figures leave out (<scene>_<frame>_left_out.exr, 1 where left out), to look at
// where the error sits.
// Run: build/quality_bench [--scenes table,corridor] [--methods photon,localized,frozen] [--pairs 0] [--save DIR]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>

#include "steadylight/base/freed_memory.h"
#include "steadylight/base/stopwatch.h"
#include "steadylight/methods/method.h"
#include "steadylight/output/image_writer.h"
#include "steadylight/passes/segment_pass.h"
#include "steadylight/photons/distant_photon_share.h"
#include "steadylight/quality/image_error.h"

using namespace steadylight;

namespace {

const std::string source_dir = STEADYLIGHT_SOURCE_DIR;

struct Options {
    std::vector<std::string> scenes{"table",      "corridor",     "mirror_room",    "glass_move",
                                    "flythrough", "ball",         "cornell",        "daylit_room",
                                    "daylit_sun", "outdoor_hdri", "torch_corridor", "daylit_sweep"};
    std::vector<Method> methods{Method::photon, Method::localized, Method::frozen};
    bool pairs = true;
    std::string save_dir;  // empty: nothing written
};

constexpr const char* usage =
    "usage: quality_bench [--scenes a,b] [--methods photon,localized,frozen] [--pairs 0|1] [--save DIR]\n";

std::vector<std::string> split(const char* text) {
    std::vector<std::string> parts;
    std::stringstream list(text);
    for (std::string part; std::getline(list, part, ',');) parts.push_back(part);
    return parts;
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; i += 2) {
        if (i + 1 == argc || argv[i][0] != '-' || !std::strcmp(argv[i], "--help")) {
            std::fputs(usage, std::strcmp(argv[i], "--help") ? stderr : stdout);
            std::exit(std::strcmp(argv[i], "--help") ? 2 : 0);
        }
        if (!std::strcmp(argv[i], "--scenes")) {
            o.scenes = split(argv[i + 1]);
        } else if (!std::strcmp(argv[i], "--pairs")) {
            o.pairs = std::atoi(argv[i + 1]) != 0;
        } else if (!std::strcmp(argv[i], "--save")) {
            o.save_dir = argv[i + 1];
        } else if (!std::strcmp(argv[i], "--methods")) {
            o.methods.clear();
            for (const std::string& name : split(argv[i + 1])) o.methods.push_back(parse_method(name, "--methods"));
        } else {
            std::fprintf(stderr, "quality_bench: unknown option %s\n%s", argv[i], usage);
            std::exit(2);
        }
    }
    return o;
}

/// tests/references/[folder/]<scene>_<frame:04>.exr
std::string reference_file(const std::string& folder, const std::string& scene, int frame) {
    char name[256];
    std::snprintf(name, sizeof name, "%s_%04d.exr", scene.c_str(), frame);
    return (std::filesystem::path(source_dir) / "tests/references" / folder / name).lexically_normal().string();
}

std::optional<Image> read_reference(const std::string& folder, const std::string& scene, int frame) {
    const std::string file = reference_file(folder, scene, frame);
    if (!std::filesystem::exists(file)) return std::nullopt;
    return read_exr(file);
}

/// A scene with its tracer and each method's static solution, rendering frames on demand.
class SceneRenderer {
public:
    explicit SceneRenderer(const std::string& name)
        : m_scene(load_scene_desc(source_dir + "/scenes/" + name + ".json")),
          m_tracer(m_scene, m_scene.evaluate(0)),
          m_bsdfs(make_bsdfs(m_scene)) {
        aim_distant_photons(m_scene);  // as `steadylight render` does for the photon methods
    }

    const Scene& scene() const { return m_scene; }

    /// The frame's beauty by `method` at default settings, and its time (without the static pass).
    std::pair<Image, double> render(Method method, int frame) {
        MethodSettings settings;
        settings.method = method;
        const StaticSolution* solution =
            method_info(method).has_static_pass ? &static_solution(frame, settings) : nullptr;
        const PlacedFrame placed(m_scene, m_tracer, m_bsdfs, frame);
        const Stopwatch time;
        Image beauty =
            method_info(method).render_frame(placed.context(), solution, settings, AnalysisLayers::made).beauty;
        return {std::move(beauty), time.elapsed_s()};
    }

    PixelMask emitters(int frame) {
        const PlacedFrame placed(m_scene, m_tracer, m_bsdfs, frame);
        return emitter_mask(placed.context());
    }

private:
    const StaticSolution& static_solution(int frame, const MethodSettings& settings) {
        const Segment& segment = m_scene.segment_of(frame);
        auto found = m_solutions.find(segment.first);
        if (found == m_solutions.end())
            found = m_solutions
                        .emplace(segment.first,
                                 StaticSolution{run_segment_pass(m_scene, m_tracer, segment, settings.photon)})
                        .first;
        return found->second;
    }

    Scene m_scene;
    RayTracer m_tracer;
    Bsdfs m_bsdfs;
    std::map<int, StaticSolution> m_solutions;  // by the segment's first frame
};

/// The 4096-sample still references' own noise per pixel and on blocks (relative RMSE), estimated
/// from the middle frame's two 1024-sample references with different seeds; nothing where they
/// are missing.
std::optional<ImageError> reference_noise(SceneRenderer& renderer, const std::string& name) {
    const int middle = renderer.scene().frame_count() / 2;
    const std::optional<Image> seed0 = read_reference("crn", name, middle),
                               seed1 = read_reference("crn_seed1", name, middle);
    if (!seed0 || !seed1) return std::nullopt;
    ImageError noise = image_error(*seed1, *seed0, renderer.emitters(middle));
    const double to_one_4096_sample_frame = std::sqrt(0.5) * std::sqrt(1024.0 / 4096.0);
    noise.pixel_rmse *= to_one_4096_sample_frame;
    noise.block_rmse *= to_one_4096_sample_frame;
    return noise;
}

/// sqrt(error^2 - noise^2): an error measured against a reference with independent noise, less it.
double without_noise(double error, double noise) { return std::sqrt(std::max(0.0, error * error - noise * noise)); }

void print_still_figures(SceneRenderer& renderer, const std::string& name, const Options& options) {
    const int frames = renderer.scene().frame_count();
    const std::optional<ImageError> noise = reference_noise(renderer, name);
    if (noise)
        std::printf("%-12s reference's own noise  per pixel %6.2f%%  4x4 %6.2f%%  (two seeds of the middle frame)\n",
                    name.c_str(), 100 * noise->pixel_rmse, 100 * noise->block_rmse);
    for (const int frame : frames > 1 ? std::vector<int>{0, frames / 2} : std::vector<int>{0}) {
        const std::optional<Image> reference = read_reference("", name, frame);
        if (!reference) {
            std::printf("%-12s frame %2d: no reference (%s)\n", name.c_str(), frame,
                        reference_file("", name, frame).c_str());
            continue;
        }
        const PixelMask emitters = renderer.emitters(frame);
        const auto save = [&](const std::string& what, const Image& image) {
            if (options.save_dir.empty()) return;
            std::filesystem::create_directories(options.save_dir);
            char file[256];
            std::snprintf(file, sizeof file, "%s_%04d_%s.exr", name.c_str(), frame, what.c_str());
            write_exr((std::filesystem::path(options.save_dir) / file).string(), image);
        };
        Image left_out(reference->width, reference->height);
        for (size_t i = 0; i < emitters.size(); ++i) left_out.pixels[i] = emitters[i] ? Rgb{1, 1, 1} : Rgb{};
        save("left_out", left_out);
        for (const Method method : options.methods) {
            const auto [image, seconds] = renderer.render(method, frame);
            save(std::string(method_info(method).name), image);
            const ImageError e = image_error(image, *reference, emitters);
            std::printf("%-12s frame %2d %-10s per pixel %6.2f%%  4x4 %6.2f%%  mean ratio %.4f  %6.2f s", name.c_str(),
                        frame, std::string(method_info(method).name).c_str(), 100 * e.pixel_rmse, 100 * e.block_rmse,
                        e.mean_ratio, seconds);
            if (noise)
                std::printf("  without the reference's noise %6.2f%% / %5.2f%%",
                            100 * without_noise(e.pixel_rmse, noise->pixel_rmse),
                            100 * without_noise(e.block_rmse, noise->block_rmse));
            std::printf("\n");
        }
    }
}

/// The common-random-numbers pairs of make_references.sh.
std::vector<int> pair_starts(int frames) { return {0, frames / 4, frames / 2, 3 * frames / 4}; }

void print_temporal_noise(SceneRenderer& renderer, const std::string& name, const Options& options) {
    const int frames = renderer.scene().frame_count();
    if (frames < 2) return;
    std::vector<Image> references;
    for (const int first : pair_starts(frames))
        for (const int frame : {first, first + 1}) {
            std::optional<Image> reference = read_reference("crn", name, frame);
            if (!reference) {
                std::printf("%-12s temporal noise: no reference (%s)\n", name.c_str(),
                            reference_file("crn", name, frame).c_str());
                return;
            }
            references.push_back(std::move(*reference));
        }
    const PixelMask emitters = renderer.emitters(0);
    std::vector<FramePair> reference_pairs;
    for (size_t i = 0; i < references.size(); i += 2) reference_pairs.push_back({references[i], references[i + 1]});
    for (const Method method : options.methods) {
        std::vector<Image> images;
        for (const int first : pair_starts(frames))
            for (const int frame : {first, first + 1}) images.push_back(renderer.render(method, frame).first);
        std::vector<FramePair> pairs;
        for (size_t i = 0; i < images.size(); i += 2) pairs.push_back({images[i], images[i + 1]});
        const TemporalNoise noise = temporal_noise(pairs, reference_pairs, emitters);
        std::printf(
            "%-12s temporal noise %-10s all %.5f  far %.5f  far signed %+.5f  far own %.5f  (%ld / %ld pixels)\n",
            name.c_str(), std::string(method_info(method).name).c_str(), noise.all, noise.far, noise.far_signed,
            noise.far_own, noise.all_pixels, noise.far_pixels);
    }
    const std::optional<Image> a = read_reference("crn_seed1", name, frames / 2),
                               b = read_reference("crn_seed1", name, frames / 2 + 1);
    if (a && b) {
        const TemporalNoise floor = temporal_noise({{*a, *b}}, {reference_pairs[2]}, emitters);
        std::printf(
            "%-12s temporal noise %-10s all %.5f  far %.5f  far signed %+.5f  far own %.5f  (the references' own noise "
            "floor)\n",
            name.c_str(), "reference", floor.all, floor.far, floor.far_signed, floor.far_own);
    }
}

}  // namespace

int main(int argc, char** argv) {
    steadylight::keep_freed_memory_mapped();  // frames reuse their large arrays (freed_memory.h)
    const Options options = parse(argc, argv);
    for (const std::string& name : options.scenes) {
        SceneRenderer renderer(name);
        print_still_figures(renderer, name, options);
        if (options.pairs) print_temporal_noise(renderer, name, options);
    }
    return 0;
}
