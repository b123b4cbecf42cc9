// Planning, writing and submitting the farm jobs (submit.h).
#include "steadylight/farm/submit.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "steadylight/base/atomic_file.h"
#include "steadylight/base/error.h"
#include "steadylight/farm/slurm_jobs.h"
#include "steadylight/irradiance/cache_file.h"
#include "steadylight/passes/segment_cache.h"
#include "steadylight/run/frame_manifest.h"
#include "steadylight/run/settings_file.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

Scene load_sized_scene(const RenderSettings& settings) {
    Scene scene(load_scene_desc(settings.scene_file, settings.confine_inputs));
    const CameraDesc& camera = scene.desc().camera;
    scene.set_resolution(settings.width.value_or(camera.width), settings.height.value_or(camera.height));
    return scene;
}

/// Checks the settings against the folder's settings file, or writes it, as every job will; so
/// a folder rendered with other settings is refused now, not by every task. Returns the key.
std::string record_submit_settings(const RenderSettings& settings, const Scene& scene, const std::vector<int>& frames,
                                   int threads) {
    const Camera camera = scene.evaluate(0).camera;
    const nlohmann::json json =
        make_settings_json(settings, {scene.name(), camera.width, camera.height, frames, threads});
    write_settings_file(settings_file_name(settings.out_dir, scene.name()), json, false);
    return settings_key(json);
}

JobPlan plan_jobs(const RenderSettings& settings, const Scene& scene, const std::vector<int>& frames,
                  const std::string& key, int chunk_frames) {
    JobPlan plan;
    plan.selected = frames;
    for (const int frame : frames)
        if (!check_frame_outputs(settings.out_dir, scene.name(), frame, key).complete) plan.missing.push_back(frame);
    const std::vector<Segment>& segments = scene.segments();
    for (size_t i = 0; i < segments.size(); ++i) {
        std::vector<int> todo;
        std::copy_if(plan.missing.begin(), plan.missing.end(), std::back_inserter(todo),
                     [&](int frame) { return segments[i].first <= frame && frame <= segments[i].last; });
        if (todo.empty()) continue;
        SegmentJobs jobs{int(i), segments[i], "", false, chunk_frame_lists(todo, chunk_frames)};
        if (method_info(settings.method).has_static_pass) {
            jobs.cache_file = static_cache_file(settings.cache_file, settings.out_dir, scene, segments[i]);
            jobs.bake =
                !read_cache_file(jobs.cache_file, static_inputs_hash(scene, segments[i], settings.photon)).cache;
        }
        plan.segments.push_back(std::move(jobs));
    }
    return plan;
}

/// `steadylight COMMAND SCENE OPTIONS... --out DIR --threads C`, the start of every job's command.
std::vector<std::string> steadylight_command(const SubmitSettings& submit, const std::string& command,
                                             const RenderSettings& settings, const std::vector<std::string>& options) {
    std::vector<std::string> line = {submit.program, command, settings.scene_file};
    line.insert(line.end(), options.begin(), options.end());
    line.insert(line.end(), {"--out", settings.out_dir, "--threads", std::to_string(submit.cpus_per_task)});
    return line;
}

/// Writes `job` as `<dir>/<file>` and returns the path.
std::string write_job_script(const std::string& dir, const std::string& file, const JobScript& job) {
    const std::string path = (fs::path(dir) / file).string();
    write_text_file(path, job_script_text(job));
    fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                    fs::perm_options::add);
    return path;
}

/// Submits (or, in a dry run, only notes) `sbatch ARGS`; returns the job id, or `placeholder`.
std::string sbatch(const SubmitSettings& submit, const std::vector<std::string>& arguments,
                   const std::string& placeholder, SubmitResult& result) {
    std::string line = "sbatch --parsable";
    for (const std::string& argument : arguments) {
        line += ' ';
        line += shell_quote(argument);
    }
    result.commands.push_back(line);
    if (submit.dry_run) return placeholder;
    const std::string id = submit_batch_job(arguments);
    result.job_ids.push_back(id);
    return id;
}

std::string jobs_file_name(const std::string& script_dir) { return (fs::path(script_dir) / "jobs.json").string(); }

std::vector<std::string> read_earlier_jobs(const std::string& script_dir) {
    std::ifstream in(jobs_file_name(script_dir));
    if (!in) return {};
    try {
        return nlohmann::json::parse(in).at("jobs").get<std::vector<std::string>>();
    } catch (const nlohmann::json::exception&) {
        spdlog::warn("{}: damaged; earlier jobs are not cancelled", jobs_file_name(script_dir));
        return {};
    }
}

/// Cancels what is pending of the earlier submission; returns its jobs still running.
std::vector<std::string> cancel_earlier_submission(const SubmitSettings& submit, const std::string& script_dir,
                                                   SubmitResult& result) {
    const std::vector<std::string> earlier = read_earlier_jobs(script_dir);
    if (earlier.empty()) return {};
    std::string line = "scancel --state=PENDING";
    for (const std::string& id : earlier) {
        line += ' ';
        line += id;
    }
    result.commands.push_back(line);
    if (submit.dry_run) return {};
    cancel_pending_jobs(earlier);
    return jobs_still_queued(earlier);
}

/// Writes `<out>/slurm/jobs.json`: the next submission cancels what is pending of these jobs
/// and waits for what still runs.
void record_jobs(const SubmitSettings& submit, const SubmitResult& result) {
    if (submit.dry_run) return;
    std::vector<std::string> jobs = result.earlier_jobs_waited_for;
    jobs.insert(jobs.end(), result.job_ids.begin(), result.job_ids.end());
    write_text_file(jobs_file_name(result.script_dir), nlohmann::json{{"jobs", jobs}}.dump(2) + "\n");
}

JobScript job_base(const SubmitSettings& submit, const std::string& scene_name, const std::string& what,
                   const std::string& script_dir, const std::string& log_pattern) {
    JobScript job;
    job.name = fmt::format("steadylight-{}-{}", scene_name, what);
    job.log_file = (fs::path(script_dir) / (what + log_pattern)).string();
    job.cpus_per_task = submit.cpus_per_task;
    job.partition = submit.partition;
    return job;
}

/// The bake job of one segment, when it needs one; returns its id ("" when none).
std::string submit_bake(const RenderSettings& settings, const SubmitSettings& submit, const std::string& scene_name,
                        const SegmentJobs& jobs, SubmitResult& result) {
    if (!jobs.bake) return "";
    const std::string what = fmt::format("bake_{}", jobs.segment);
    JobScript job = job_base(submit, scene_name, what, result.script_dir, "_%j.log");
    job.comment = fmt::format("the static cache of segment {} (frames {}-{}) into {}", jobs.segment, jobs.frames.first,
                              jobs.frames.last, jobs.cache_file);
    std::vector<std::string> command = steadylight_command(submit, "bake", settings, submit.bake_options);
    command.insert(command.end(), {"--segment", std::to_string(jobs.segment)});
    job.commands = {command};
    const std::string script = write_job_script(result.script_dir, what + ".sh", job);
    return sbatch(submit, {script}, fmt::format("<{} job id>", what), result);
}

/// The job array of one segment's chunks, after its bake when there is one; returns its id.
std::string submit_render_array(const RenderSettings& settings, const SubmitSettings& submit,
                                const std::string& scene_name, const SegmentJobs& jobs, const std::string& bake_id,
                                SubmitResult& result) {
    const std::string what = fmt::format("render_{}", jobs.segment);
    JobScript job = job_base(submit, scene_name, what, result.script_dir, "_%A_%a.log");
    job.comment = fmt::format("frames of segment {} (frames {}-{}), one chunk per array task", jobs.segment,
                              jobs.frames.first, jobs.frames.last);
    job.chunks = jobs.chunks;
    std::vector<std::string> command = steadylight_command(submit, "render", settings, submit.render_options);
    command.insert(command.end(), {"--frames", array_task_frames, "--require-cache", "--no-progress"});
    job.commands = {command};
    const std::string script = write_job_script(result.script_dir, what + ".sh", job);
    std::vector<std::string> arguments = {fmt::format("--array=0-{}", jobs.chunks.size() - 1)};
    // A failed bake must end the array: without --kill-on-invalid-dep it would stay pending for ever.
    if (!bake_id.empty())
        arguments.insert(arguments.end(), {"--dependency=afterok:" + bake_id, "--kill-on-invalid-dep=yes"});
    arguments.push_back(script);
    return sbatch(submit, arguments, fmt::format("<{} job id>", what), result);
}

/// The finishing job: every selected frame complete (else it fails listing the missing ones),
/// then the video when asked, then the report.
void submit_finish(const RenderSettings& settings, const SubmitSettings& submit, const std::string& scene_name,
                   const std::vector<std::string>& after, SubmitResult& result) {
    JobScript job = job_base(submit, scene_name, "finish", result.script_dir, "_%j.log");
    job.comment = "checks that every frame is complete, then the video (if asked) and the report";
    std::vector<std::string> check = steadylight_command(submit, "render", settings, submit.render_options);
    check.insert(check.end(),
                 {"--frames", format_frame_list(result.plan.selected), "--check-complete", "--no-progress"});
    if (!settings.output.video_file.empty()) check.insert(check.end(), {"--video", settings.output.video_file});
    job.commands = {check, {submit.program, "report", settings.out_dir}};
    const std::string script = write_job_script(result.script_dir, "finish.sh", job);
    std::vector<std::string> arguments;
    if (!after.empty()) {
        // afterany: a cancelled or failed task would leave an afterok job pending for ever.
        std::string dependency = "--dependency=afterany";
        for (const std::string& id : after) dependency += ":" + id;
        arguments.push_back(dependency);
    }
    arguments.push_back(script);
    sbatch(submit, arguments, "<finish job id>", result);
}

}  // namespace

SubmitResult submit_animation(const RenderSettings& settings, const SubmitSettings& submit) {
    validate(settings);
    if (submit.chunk_frames < 1) throw InputError("--chunk", "must be at least 1 frame");
    const Scene scene = load_sized_scene(settings);
    const std::vector<int> frames = select_frames(settings.frames, scene.frame_count());
    create_output_folder(settings.out_dir, "--out");
    const std::string key = record_submit_settings(settings, scene, frames, submit.cpus_per_task);
    SubmitResult result;
    result.plan = plan_jobs(settings, scene, frames, key, submit.chunk_frames);
    result.script_dir = (fs::path(settings.out_dir) / "slurm").string();
    fs::create_directories(result.script_dir);
    result.earlier_jobs_waited_for = cancel_earlier_submission(submit, result.script_dir, result);
    try {
        // The finishing job also waits for what still runs of the earlier submission: its frames may be in progress.
        std::vector<std::string> after = result.earlier_jobs_waited_for;
        for (const SegmentJobs& jobs : result.plan.segments) {
            const std::string bake_id = submit_bake(settings, submit, scene.name(), jobs, result);
            after.push_back(submit_render_array(settings, submit, scene.name(), jobs, bake_id, result));
        }
        submit_finish(settings, submit, scene.name(), after, result);
    } catch (const std::exception&) {
        // What was submitted before sbatch refused is still recorded, for the next submission.
        record_jobs(submit, result);
        throw;
    }
    record_jobs(submit, result);
    return result;
}

}  // namespace steadylight
