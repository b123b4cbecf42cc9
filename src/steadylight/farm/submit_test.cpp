// The farm's pieces that need no Slurm: chunks of a segment's frames, shell quoting, and the
// batch scripts' text (job arrays pick their chunk by SLURM_ARRAY_TASK_ID).
#include "steadylight/farm/submit.h"

#include <gtest/gtest.h>

#include "steadylight/farm/job_plan.h"
#include "steadylight/farm/slurm_jobs.h"

namespace steadylight {
namespace {

TEST(FarmChunks, NoFramesGiveNoChunks) { EXPECT_TRUE(chunk_frame_lists({}, 3).empty()); }

TEST(FarmChunks, CutsFramesIntoRunsOfAtMostN) {
    EXPECT_EQ(chunk_frame_lists({0, 1, 2, 3, 4, 5, 6}, 3), (std::vector<std::string>{"0-2", "3-5", "6"}));
    EXPECT_EQ(chunk_frame_lists({0, 1, 2, 3, 5}, 2), (std::vector<std::string>{"0-1", "2-3", "5"}));
    EXPECT_EQ(chunk_frame_lists({4, 7, 8, 20}, 10), (std::vector<std::string>{"4,7-8,20"}));
}

TEST(FarmScripts, QuotesOnlyWhatNeedsIt) {
    EXPECT_EQ(shell_quote("/out/ball_%A_%a.log"), "/out/ball_%A_%a.log");
    EXPECT_EQ(shell_quote("--frames=0-2"), "--frames=0-2");
    EXPECT_EQ(shell_quote("my scene.json"), "'my scene.json'");
    EXPECT_EQ(shell_quote("it's"), "'it'\\''s'");
    EXPECT_EQ(shell_quote(""), "''");
}

TEST(FarmScripts, AnArrayScriptPicksItsChunkByTaskId) {
    JobScript job;
    job.name = "steadylight-ball-render_0";
    job.log_file = "/out/slurm/render_0_%A_%a.log";
    job.cpus_per_task = 2;
    job.partition = "render";
    job.comment = "frames of segment 0";
    job.chunks = {"0-2", "3-5"};
    job.commands = {{"/bin/steadylight", "render", "/s/ball.json", "--frames", array_task_frames, "--out", "/o u t"}};
    const std::string text = job_script_text(job);
    EXPECT_EQ(text.rfind("#!/bin/bash\n", 0), 0u);
    for (const char* line :
         {"#SBATCH --job-name=steadylight-ball-render_0\n", "#SBATCH --output=/out/slurm/render_0_%A_%a.log\n",
          "#SBATCH --cpus-per-task=2\n", "#SBATCH --partition=render\n", "set -euo pipefail\n", "chunks=(0-2 3-5)\n",
          "/bin/steadylight render /s/ball.json --frames \"${chunks[$SLURM_ARRAY_TASK_ID]}\" --out '/o u t'\n"})
        EXPECT_NE(text.find(line), std::string::npos) << line << " not in\n" << text;
}

TEST(FarmScripts, AMissingProgramReportsStatus127) {
    EXPECT_EQ(run_command({"steadylight-no-such-program"}).status, 127);
    const CommandOutput echo = run_command({"echo", "a b"});
    EXPECT_EQ(echo.status, 0);
    EXPECT_EQ(echo.output, "a b\n");
}

}  // namespace
}  // namespace steadylight
