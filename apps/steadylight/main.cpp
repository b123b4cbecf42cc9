// The steadylight command line: parses flags into RenderSettings and calls the library.
// Errors are caught once, here: the message goes to stderr and the exit code is 1; Ctrl-C ends
// a render cleanly with exit code 130 (run/interrupt.h).
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <regex>
#include <set>

#include "steadylight/base/checkpoint.h"
#include "steadylight/base/error.h"
#include "steadylight/base/freed_memory.h"
#include "steadylight/farm/submit.h"
#include "steadylight/render.h"
#include "steadylight/report/report.h"
#include "steadylight/run/console.h"
#include "steadylight/run/interrupt.h"

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

/// Command-line values that need checking or converting after parsing.
struct RawOptions {
    std::optional<std::string> frames;
    std::string size;
    std::optional<int> spp;
    int threads = 0;
    int gather_samples = 0;
    std::string method = std::string(method_info(MethodSettings{}.method).name);  // the default
    std::string exr_type = "half", view_transform = "standard", layers = "all";
};

/// The options that shape the written files: EXR pixel type and layers, PNG view transform,
/// transparent background, video.
void add_output_options(CLI::App* command, RenderSettings& settings, RawOptions& raw) {
    command->add_option("--exr-type", raw.exr_type, "EXR channels: half (16-bit) or float (32-bit)")
        ->capture_default_str()
        ->check(CLI::IsMember({"half", "float"}));
    command->add_flag_callback(
        "--exr-float", [&raw] { raw.exr_type = "float"; }, "Same as --exr-type float");
    command
        ->add_option("--layers", raw.layers,
                     "AOV layers after the beauty: all (the method's every layer, its analysis layers too), "
                     "terms (direct, indirect, caustic, specular) or beauty (none)")
        ->capture_default_str()
        ->check(CLI::IsMember({"all", "terms", "beauty"}));
    command->add_option("--exposure", settings.output.view.exposure_ev, "PNG: exposure in stops (linear x 2^EV)")
        ->capture_default_str()
        ->check(CLI::Range(-64.0f, 64.0f));
    command->add_option("--view-transform", raw.view_transform, "PNG: standard (clamp) or filmic (Hable curve)")
        ->capture_default_str()
        ->check(CLI::IsMember({"standard", "filmic"}));
    command->add_flag("!--no-dither", settings.output.view.dither, "PNG: round without the fixed dither");
    command->add_flag("--transparent-background", settings.output.transparent_background,
                      "Leave the world out of what the camera sees directly: EXR and PNG with alpha (the share of "
                      "camera rays that meet a surface; the world seen through glass and mirrors stays)");
    command->add_option("--blender-view-layer", settings.output.blender_view_layer,
                        "EXR channels named as Blender's render result names them for view layer NAME: "
                        "NAME.Combined.R, G, B, A and NAME.<layer>.R, G, B or NAME.<layer>.X (what "
                        "RenderResult.load_from_file reads; the Blender add-on uses it)");
    command->add_option("--video", settings.output.video_file,
                        "Encode the frames' PNGs as an H.264 MP4 with ffmpeg after rendering");
}

/// The options `render` and `bake` share: the scene, output, and every setting of the methods.
void add_method_options(CLI::App* command, RenderSettings& settings, RawOptions& raw) {
    command->add_option("scene", settings.scene_file, "Scene file (JSON)")->required();
    command->add_option("--size", raw.size, "Image size WIDTHxHEIGHT (default: the scene's)");
    command->add_option("--threads", raw.threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 1024));
    command->add_option("--out", settings.out_dir, "Output folder")->capture_default_str();
    PhotonMappingSettings& photon = settings.photon;
    command->add_option("--photons", photon.photons.global_photons, "photon paths emitted per frame for the global map")
        ->capture_default_str()
        ->check(CLI::Range(0L, 1L << 34));
    command
        ->add_option("--caustic-photons", photon.photons.caustic_photons,
                     "photon paths emitted per frame for the caustic map")
        ->capture_default_str()
        ->check(CLI::Range(0L, 1L << 34));
    raw.gather_samples = photon.gather.theta_strata * photon.gather.phi_strata;
    command
        ->add_option("--gather-samples", raw.gather_samples, "final-gather rays per record, as M x 2M strata (rounded)")
        ->capture_default_str()
        ->check(CLI::Range(8, 1 << 16));
    command->add_option("--cache-accuracy", photon.cache.accuracy, "Ward's a; smaller = more records")
        ->capture_default_str()
        ->check(CLI::Range(0.01f, 2.0f));
    command->add_option("--cache-spacing", photon.cache.min_spacing_px, "smallest reach of a record in pixels")
        ->capture_default_str()
        ->check(CLI::Range(0.5f, 1000.0f));
    command->add_option("--cache-max-spacing", photon.cache.max_spacing_px, "largest reach of a record in pixels")
        ->capture_default_str()
        ->check(CLI::Range(1.0f, 10000.0f));
    command->add_flag("!--jittered-gather", photon.gather.fixed_directions,
                      "new gather directions per record instead of one fixed set");
    command->add_option("--cache-file", settings.cache_file, "static cache file (default: OUT/SCENE.irrcache)");
}

/// "localized: the paper's method; photon: ..." from the method table.
std::string method_help() {
    std::string help;
    for (const MethodInfo& info : methods())
        help += fmt::format("{}{}: {}", help.empty() ? "" : "; ", info.name, info.description);
    return help;
}

std::vector<std::string> method_name_list() {
    std::vector<std::string> names;
    for (const MethodInfo& info : methods()) names.emplace_back(info.name);
    return names;
}

/// The options of `render` beyond add_method_options (`submit` takes them too and passes them on).
void add_render_options(CLI::App* command, RenderSettings& settings, RawOptions& raw) {
    command->add_option("--frames", raw.frames, "Frames: N, A-B, A-B:STEP or a comma list of them (default: all)");
    command->add_option("--spp", raw.spp, "Camera rays per pixel (default: 64 for path, 16 otherwise)")
        ->check(CLI::Range(1, 1 << 20));
    command->add_option("--method,--integrator", raw.method, method_help())
        ->capture_default_str()
        ->check(CLI::IsMember(method_name_list()));
    command
        ->add_option("--direct-samples", settings.photon.shading.direct_samples,
                     "shadow rays per diffuse hit and camera ray")
        ->capture_default_str()
        ->check(CLI::Range(1, 4096));
    command
        ->add_option("--influence-photons", settings.localized.influence_photons,
                     "localized: dynamic photons in the influence estimate")
        ->capture_default_str()
        ->check(CLI::Range(1, 100000));
    command
        ->add_option("--tau-lower", settings.localized.tau_lower,
                     "localized: influence (relative to static indirect irradiance) below which L_t alone is used")
        ->capture_default_str()
        ->check(CLI::Range(0.0f, 1e6f));
    command
        ->add_option("--tau-upper", settings.localized.tau_upper, "localized: influence above which L_y alone is used")
        ->capture_default_str()
        ->check(CLI::Range(0.0f, 1e6f));
    command->add_option("--max-depth", settings.path.max_depth, "path: maximum path length in bounces")
        ->capture_default_str()
        ->check(CLI::Range(0, 10000));
    command->add_flag("--fixed-seed", settings.path.fixed_seed,
                      "path: the same random numbers per pixel and camera sample in every frame, so frames "
                      "differ only where paths meet what moved");
    command
        ->add_option("--seed", settings.path.seed,
                     "path: another seed gives independent noise (references' noise floor)")
        ->capture_default_str();
    command->add_flag("!--no-progress", settings.show_progress, "No progress output");
    command->add_flag("--aov", settings.aov_pngs, "Also write every EXR layer as a PNG");
    command->add_flag("!--no-reuse", settings.reuse,
                      "photon, localized, frozen: trace every photon path in every frame instead of retracing only "
                      "the static paths that dynamic objects meet, and (localized, still camera) shade every pixel "
                      "instead of those the dynamic objects can change (the same images, slower; for comparison)");
}

/// What a scene may read: --confine-inputs (render, bake, submit, info).
void add_input_options(CLI::App* command, bool& confine_inputs) {
    command->add_flag("--confine-inputs", confine_inputs,
                      "Read only files inside the scene file's folder (symbolic links resolved): for farms that "
                      "render scene files from others");
}

/// The console and resume options of `render` and `bake`.
void add_console_options(CLI::App* command, LogOptions& log) {
    command->add_flag("--quiet,-q", log.quiet, "Print errors only (no progress, no log lines)");
    command->add_option("--log-level", log.level, "Console and log file detail")
        ->capture_default_str()
        ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}));
    command->add_option("--log", log.file, "Also append the log to FILE");
}

/// What a render that stopped early says: what is finished and how to go on.
void print_interrupted(const RenderSummary& summary, bool overwrite) {
    std::fprintf(stderr,
                 "steadylight: interrupted; %zu frame(s) finished in this run%s%s, %zu left (%s).\n"
                 "Run the same command again%s to resume: finished frames are skipped.\n",
                 summary.frames_written.size(), summary.frames_written.empty() ? "" : ": ",
                 format_frame_list(summary.frames_written).c_str(), summary.frames_left.size(),
                 format_frame_list(summary.frames_left).c_str(), overwrite ? " without --overwrite" : "");
}

/// Checks and converts what add_method_options and the render options read.
void finish_settings(const RawOptions& raw, RenderSettings& settings) {
    if (raw.frames) settings.frames = parse_frame_selection(*raw.frames);
    if (!raw.size.empty()) parse_size(raw.size, settings);
    settings.output.exr_type = parse_exr_pixel_type(raw.exr_type);
    settings.output.layers = parse_layer_set(raw.layers);
    settings.output.view.curve = parse_view_curve(raw.view_transform);
    if (raw.spp) settings.path.samples_per_pixel = settings.photon.shading.samples_per_pixel = *raw.spp;
    settings.photon.gather.theta_strata = std::max(2, int(std::lround(std::sqrt(raw.gather_samples / 2.0))));
    settings.photon.gather.phi_strata = 2 * settings.photon.gather.theta_strata;
    settings.method = parse_method(raw.method, "--method");
}

/// The options given to `submit` that its jobs pass on: for `render` all but those the job
/// scripts set themselves or that are submit's own, for `bake` those of them it takes.
struct ForwardedOptions {
    std::vector<std::string> render, bake;
};

ForwardedOptions forwarded_options(const CLI::App& submit, const CLI::App& bake, const std::vector<std::string>& args) {
    static const std::set<std::string> not_passed = {"--out",       "--frames",      "--threads",
                                                     "--video",     "--no-progress", "--chunk",
                                                     "--partition", "--dry-run",     "--cpus-per-task"};
    ForwardedOptions forwarded;
    for (size_t i = 0; i < args.size(); ++i) {
        if (args[i].size() < 2 || args[i][0] != '-') continue;  // the scene: given to the jobs as an absolute path
        const std::string name = args[i].substr(0, args[i].find('='));
        const CLI::Option* option = submit.get_option_no_throw(name);
        if (!option) continue;
        std::vector<std::string> words = {args[i]};
        if (option->get_type_size() != 0 && args[i].find('=') == std::string::npos && i + 1 < args.size())
            words.push_back(args[++i]);
        if (std::any_of(not_passed.begin(), not_passed.end(),
                        [&](const std::string& n) { return option->check_name(n); }))
            continue;
        forwarded.render.insert(forwarded.render.end(), words.begin(), words.end());
        if (bake.get_option_no_throw(name)) forwarded.bake.insert(forwarded.bake.end(), words.begin(), words.end());
    }
    return forwarded;
}

/// `steadylight submit`: plans and submits the jobs, then prints what it did and how to watch.
void run_submit(const CLI::App& submit, const CLI::App& bake, int argc, char** argv, RenderSettings settings,
                SubmitSettings submit_settings) {
    namespace fs = std::filesystem;
    const std::vector<std::string> all(argv + 1, argv + argc);
    const auto first = std::find(all.begin(), all.end(), "submit");
    const ForwardedOptions forwarded = forwarded_options(submit, bake, std::vector<std::string>(first + 1, all.end()));
    submit_settings.render_options = forwarded.render;
    submit_settings.bake_options = forwarded.bake;
    submit_settings.program = fs::read_symlink("/proc/self/exe").string();
    settings.scene_file = fs::absolute(settings.scene_file).string();
    settings.out_dir = fs::absolute(settings.out_dir).lexically_normal().string();
    if (!settings.output.video_file.empty())
        settings.output.video_file = fs::absolute(settings.output.video_file).string();
    const SubmitResult result = submit_animation(settings, submit_settings);
    const JobPlan& plan = result.plan;
    size_t chunks = 0, bakes = 0;
    for (const SegmentJobs& jobs : plan.segments) chunks += jobs.chunks.size(), bakes += jobs.bake;
    std::printf(
        "%zu of %zu frame(s) to render (%zu complete), in %zu chunk(s) of at most %d over %zu segment(s); "
        "%zu static cache(s) to bake\njob scripts in %s\n",
        plan.missing.size(), plan.selected.size(), plan.selected.size() - plan.missing.size(), chunks,
        submit_settings.chunk_frames, plan.segments.size(), bakes, result.script_dir.c_str());
    if (!result.earlier_jobs_waited_for.empty())
        std::printf("still running from the earlier submission (the finishing job waits for them): %s\n",
                    fmt::format("{}", fmt::join(result.earlier_jobs_waited_for, " ")).c_str());
    for (const std::string& line : result.commands)
        std::printf("%s%s\n", submit_settings.dry_run ? "would run: " : "ran: ", line.c_str());
    if (submit_settings.dry_run) return;
    const std::string ids = fmt::format("{}", fmt::join(result.job_ids, ","));
    std::printf(
        "submitted jobs %s (the last one finishes: checks the frames, %sreport)\n"
        "watch them: squeue -j %s    afterwards: sacct -j %s    logs: %s/*.log\n",
        ids.c_str(), settings.output.video_file.empty() ? "" : "video, ", ids.c_str(), ids.c_str(),
        result.script_dir.c_str());
}

/// The command line: its subcommands and the values their options fill.
struct CommandLine {
    CLI::App app{"steadylight: global-illumination animations with localized final gathering"};
    RenderSettings settings;
    RawOptions raw;
    LogOptions log;
    SubmitSettings submit_settings;
    std::optional<int> bake_segment;
    std::string info_scene;
    bool info_confine_inputs = false;
    ReportSettings report_settings;
    CLI::App* render = nullptr;
    CLI::App* submit = nullptr;
    CLI::App* bake = nullptr;
    CLI::App* info = nullptr;
    CLI::App* report = nullptr;
};

void add_render_command(CommandLine& cli) {
    CLI::App* render = cli.render = cli.app.add_subcommand("render", "Render the frames of a scene");
    add_method_options(render, cli.settings, cli.raw);
    add_render_options(render, cli.settings, cli.raw);
    add_output_options(render, cli.settings, cli.raw);
    render->add_flag("--overwrite", cli.settings.overwrite, "Render frames again whose outputs are complete already");
    render->add_flag("--require-cache", cli.settings.require_cache,
                     "A missing or stale static cache file is an error instead of being computed (farm workers)");
    add_input_options(render, cli.settings.confine_inputs);
    render->add_flag("--check-complete", cli.settings.check_complete,
                     "Render nothing: fail listing the selected frames whose outputs are not complete");
    add_console_options(render, cli.log);
}

void add_submit_command(CommandLine& cli) {
    CLI::App* submit = cli.submit = cli.app.add_subcommand(
        "submit", "Render the frames on a Slurm cluster: bake, chunk and finishing jobs (docs/farm.md)");
    add_method_options(submit, cli.settings, cli.raw);
    add_render_options(submit, cli.settings, cli.raw);
    add_output_options(submit, cli.settings, cli.raw);
    SubmitSettings& submit_settings = cli.submit_settings;
    submit->add_option("--chunk", submit_settings.chunk_frames, "Frames per array task (chunks never span segments)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1 << 20));
    submit->add_option("--partition", submit_settings.partition, "Slurm partition (default: the cluster's)");
    submit->add_option("--cpus-per-task", submit_settings.cpus_per_task, "CPUs of each job, also its --threads")
        ->capture_default_str()
        ->check(CLI::Range(1, 1024));
    submit->add_flag("--dry-run", submit_settings.dry_run,
                     "Write the job scripts and print the sbatch lines; submit nothing");
    add_input_options(submit, cli.settings.confine_inputs);
    add_console_options(submit, cli.log);
}

void add_bake_command(CommandLine& cli) {
    CLI::App* bake = cli.bake =
        cli.app.add_subcommand("bake", "Compute the static irradiance cache of a scene and save it");
    add_method_options(bake, cli.settings, cli.raw);
    bake->add_option("--segment", cli.bake_segment, "Bake only segment K (0 = the first; see `steadylight info`)");
    add_input_options(bake, cli.settings.confine_inputs);
    add_console_options(bake, cli.log);
}

void add_info_and_report_commands(CommandLine& cli) {
    cli.info = cli.app.add_subcommand("info", "Describe a scene: objects, lights, frames, static/dynamic");
    cli.info->add_option("scene", cli.info_scene, "Scene file (JSON)")->required();
    add_input_options(cli.info, cli.info_confine_inputs);
    ReportSettings& report_settings = cli.report_settings;
    CLI::App* report = cli.report = cli.app.add_subcommand(
        "report",
        "Write one HTML page about the frames in a folder: summary tables, statistics plots, contact sheet, "
        "AOV layers");
    report->add_option("outdir", report_settings.out_dir, "Folder that `render --out` wrote")->required();
    report->add_option("--frame", report_settings.frame, "Frame whose AOV layers are shown (default: the middle one)");
    report->add_option("--out", report_settings.html_file, "HTML file to write (default: OUTDIR/report.html)");
}

/// Renders the frames and says what was done; 130 when interrupted.
int run_render(const RenderSettings& settings) {
    const RenderSummary summary = render_animation(settings);
    if (summary.interrupted) {
        print_interrupted(summary, settings.overwrite);
        return 130;
    }
    std::vector<int> elsewhere = summary.frames_completed_elsewhere;
    std::sort(elsewhere.begin(), elsewhere.end());
    const std::string others = elsewhere.empty() ? ""
                                                 : fmt::format(" ({} by other processes that claimed them: {})",
                                                               elsewhere.size(), format_frame_list(elsewhere));
    spdlog::info("{} frame(s) written, {} complete ones skipped{}, in {} in {:.1f} s", summary.frames_written.size(),
                 summary.frames_skipped, others, settings.out_dir, summary.seconds);
    return 0;
}

/// Runs the command the line chose; its exit code.
int run_command(CommandLine& cli, int argc, char** argv) {
    if (*cli.info) {
        std::fputs(describe_scene(cli.info_scene, cli.info_confine_inputs).c_str(), stdout);
        return 0;
    }
    if (*cli.report) {
        spdlog::info("report written to {}", write_report(cli.report_settings));
        return 0;
    }
    setup_logging(cli.log);
    if (cli.log.quiet) cli.settings.show_progress = false;
    finish_settings(cli.raw, cli.settings);
    install_interrupt_handlers();
    std::unique_ptr<tbb::global_control> thread_limit;
    if (cli.raw.threads > 0)
        thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                             size_t(cli.raw.threads));
    if (*cli.submit) {
        run_submit(*cli.submit, *cli.bake, argc, argv, cli.settings, cli.submit_settings);
        return 0;
    }
    if (*cli.bake) {
        for (const std::string& file : bake_static_caches(cli.settings, cli.bake_segment))
            spdlog::info("static cache: {}", file);
        return 0;
    }
    return run_render(cli.settings);
}

/// The message and exit code of the error being handled: errors are caught once, here.
int report_error() {
    try {
        throw;
    } catch (const RenderInterrupted&) {
        std::fputs("steadylight: interrupted\n", stderr);
        return 130;
    } catch (const InputError& e) {
        std::fprintf(stderr, "steadylight: error: %s\n", e.what());
        return 1;
    } catch (const OutputError& e) {
        // Frames written before are whole (each file appears whole or not at all): the same
        // command resumes once the cause is gone.
        std::fprintf(stderr,
                     "steadylight: error: %s (the frames written so far are complete; the same command resumes)\n",
                     e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "steadylight: internal error: %s\n", e.what());
        return 1;
    }
}

}  // namespace

int main(int argc, char** argv) {
    steadylight::keep_freed_memory_mapped();  // frames reuse their large arrays (freed_memory.h)
    CommandLine cli;
    cli.app.set_version_flag("--version", std::string("steadylight ") + STEADYLIGHT_VERSION);
    cli.app.require_subcommand(1);
    add_render_command(cli);
    add_submit_command(cli);
    add_bake_command(cli);
    add_info_and_report_commands(cli);
    try {
        cli.app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help and --version exit 0; usage errors exit 2, as most command-line tools do.
        return cli.app.exit(e) == 0 ? 0 : 2;
    }
    try {
        return run_command(cli, argc, argv);
    } catch (...) {
        return report_error();
    }
}
