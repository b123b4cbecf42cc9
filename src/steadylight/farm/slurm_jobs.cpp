// Slurm batch scripts and the programs that submit and cancel them (slurm_jobs.h).
#include "steadylight/farm/slurm_jobs.h"

#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "steadylight/base/error.h"

namespace steadylight {
namespace {

std::string join_quoted(const std::vector<std::string>& arguments) {
    std::string line;
    for (const std::string& argument : arguments) {
        if (!line.empty()) line += ' ';
        line +=
            argument == array_task_frames ? std::string("\"${chunks[$SLURM_ARRAY_TASK_ID]}\"") : shell_quote(argument);
    }
    return line;
}

/// The job id in sbatch --parsable's answer ("123" or "123;cluster").
std::string parse_job_id(const std::string& output) {
    std::istringstream lines(output);
    std::string line, id;
    while (std::getline(lines, line))
        if (!line.empty() && std::isdigit(static_cast<unsigned char>(line[0]))) id = line.substr(0, line.find(';'));
    return id;
}

}  // namespace

std::string shell_quote(const std::string& text) {
    const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) ||
               std::string_view("_./:=,+-%@").find(c) != std::string_view::npos;
    });
    if (plain) return text;
    std::string quoted = "'";
    for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

std::string job_script_text(const JobScript& job) {
    std::string text = "#!/bin/bash\n";
    text += fmt::format("#SBATCH --job-name={}\n", shell_quote(job.name));
    text += fmt::format("#SBATCH --output={}\n", shell_quote(job.log_file));
    text += fmt::format("#SBATCH --cpus-per-task={}\n", job.cpus_per_task);
    if (!job.partition.empty()) text += fmt::format("#SBATCH --partition={}\n", shell_quote(job.partition));
    text += fmt::format("# Written by steadylight submit: {}\nset -euo pipefail\n", job.comment);
    if (!job.chunks.empty()) {
        text += "chunks=(";
        for (size_t i = 0; i < job.chunks.size(); ++i) {
            if (i) text += ' ';
            text += shell_quote(job.chunks[i]);
        }
        text += ")\n";
    }
    for (const std::vector<std::string>& command : job.commands) text += join_quoted(command) + "\n";
    return text;
}

CommandOutput run_command(const std::vector<std::string>& arguments) {
    std::string line;
    for (const std::string& argument : arguments) line += shell_quote(argument) + " ";
    FILE* pipe = ::popen((line + "2>&1").c_str(), "r");
    if (!pipe) return {127, "cannot start " + arguments.front()};
    CommandOutput result;
    std::array<char, 4096> buffer{};
    while (const size_t bytes = std::fread(buffer.data(), 1, buffer.size(), pipe))
        result.output.append(buffer.data(), bytes);
    const int status = ::pclose(pipe);
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
    return result;
}

std::string submit_batch_job(const std::vector<std::string>& sbatch_arguments) {
    std::vector<std::string> command = {"sbatch", "--parsable"};
    command.insert(command.end(), sbatch_arguments.begin(), sbatch_arguments.end());
    const CommandOutput result = run_command(command);
    const std::string script = sbatch_arguments.empty() ? "" : sbatch_arguments.back();
    if (result.status == 127)
        throw InputError("sbatch",
                         "the Slurm command sbatch is not installed here (not found in PATH); run submit "
                         "on a Slurm submit host, or use --dry-run to write the job scripts only");
    const std::string id = parse_job_id(result.output);
    if (result.status != 0 || id.empty())
        throw InputError(script, fmt::format("sbatch refused the job (exit status {}): {}", result.status,
                                             result.output.empty() ? "no message" : result.output));
    return id;
}

std::vector<std::string> jobs_still_queued(const std::vector<std::string>& job_ids) {
    const CommandOutput result = run_command({"squeue", "--noheader", "--format=%A %F"});
    std::vector<std::string> queued;
    std::istringstream lines(result.output);
    std::string job, array_job;
    // %A is a task's own id, %F the id of its array (or its own): either can be one we submitted.
    while (lines >> job >> array_job)
        for (const std::string& id : job_ids)
            if ((id == job || id == array_job) && std::find(queued.begin(), queued.end(), id) == queued.end())
                queued.push_back(id);
    return queued;
}

void cancel_pending_jobs(const std::vector<std::string>& job_ids) {
    if (job_ids.empty()) return;
    std::vector<std::string> command = {"scancel", "--state=PENDING"};
    command.insert(command.end(), job_ids.begin(), job_ids.end());
    run_command(command);  // ids that finished meanwhile make scancel complain: nothing to cancel then
}

}  // namespace steadylight
