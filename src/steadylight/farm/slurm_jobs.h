// Slurm's side of a farm submission: the batch scripts (`#SBATCH` lines, then the steadylight
// command lines they run) and the programs that submit and cancel them (sbatch, scancel,
// squeue). Commands run without a shell's word splitting surprises: every argument is quoted.
#pragma once

#include <string>
#include <vector>

namespace steadylight {

/// The argument that stands for the array task's frames in a job's command line.
inline constexpr const char* array_task_frames = "@ARRAY_TASK_FRAMES@";

/// One batch script.
struct JobScript {
    std::string name;      // --job-name
    std::string log_file;  // --output (may hold %A, %a, %j)
    int cpus_per_task = 1;
    std::string partition;                           // "" for the cluster's default
    std::string comment;                             // a line saying what the job does
    std::vector<std::string> chunks;                 // for a job array: task i renders chunks[i] (array_task_frames)
    std::vector<std::vector<std::string>> commands;  // run in order; the first failure ends the job
};

/// `text` quoted for bash when it needs it: abc stays abc, a b becomes 'a b'.
std::string shell_quote(const std::string& text);

/// The bash script of `job`.
std::string job_script_text(const JobScript& job);

/// What a program printed (stdout and stderr together) and its exit status (127: not found).
struct CommandOutput {
    int status = 0;
    std::string output;
};

/// Runs `arguments` (the program first, looked up in PATH) and waits for it.
CommandOutput run_command(const std::vector<std::string>& arguments);

/// \brief Submits with `sbatch --parsable ARGS` and returns the job id. Throws InputError when
/// sbatch is missing or refuses (no Slurm, no such partition), with its message and the script.
std::string submit_batch_job(const std::vector<std::string>& sbatch_arguments);

/// The ids of `job_ids` that Slurm still lists (pending or running).
std::vector<std::string> jobs_still_queued(const std::vector<std::string>& job_ids);

/// Cancels what is still pending of `job_ids` (`scancel --state=PENDING`); running tasks go on.
void cancel_pending_jobs(const std::vector<std::string>& job_ids);

}  // namespace steadylight
