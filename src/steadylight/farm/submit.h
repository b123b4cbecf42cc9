// `steadylight submit`: one animation over many machines through Slurm (docs/farm.md). Writes
// the job scripts into `<out>/slurm/` and submits, per segment, a bake job (skipped when the
// cache file is valid) and a job array over the segment's missing frames in chunks, which
// depends on the bake with afterok and --kill-on-invalid-dep=yes (a failed bake ends the array
// instead of leaving it pending for ever); then one finishing job after every array (afterany:
// a cancelled task would leave an afterok job pending for ever) that checks that every frame is
// complete, encodes --video if asked, and writes the report. Submitting again resumes: complete
// frames and valid caches are left alone, and what is still pending of the earlier submission
// (listed in `<out>/slurm/jobs.json`) is cancelled first.
#pragma once

#include <string>
#include <vector>

#include "steadylight/farm/job_plan.h"
#include "steadylight/run/render_settings.h"

namespace steadylight {

struct SubmitSettings {
    std::string program;                      // the steadylight executable every job runs (absolute)
    std::vector<std::string> render_options;  // the render options given to submit, for the render jobs
    std::vector<std::string> bake_options;    // those of them that `bake` takes (size, photon and cache options)
    int chunk_frames = 10;                    // frames per array task
    std::string partition;                    // "" for the cluster's default
    int cpus_per_task = 1;                    // also each job's --threads
    bool dry_run = false;                     // write the scripts, print the sbatch lines, submit nothing
};

struct SubmitResult {
    JobPlan plan;
    std::string script_dir;                            // <out>/slurm
    std::vector<std::string> commands;                 // the scancel and sbatch lines, as run or (dry run) to run
    std::vector<std::string> job_ids;                  // what was submitted, in order (none in a dry run)
    std::vector<std::string> earlier_jobs_waited_for;  // still running from the earlier submission
};

/// \brief Plans and submits the farm jobs of `settings` (scene_file and out_dir absolute; frames,
/// method and every render option as for `render`). Throws InputError for bad settings, a
/// settings file of other settings in the folder, or a refusing or missing sbatch.
SubmitResult submit_animation(const RenderSettings& settings, const SubmitSettings& submit);

}  // namespace steadylight
