// The summary tables of `steadylight report`: per scene, the mean of every statistic per frame
// for each method, and where the photon method (the paper's reference) is present the ratio
// photon / method, as the paper's Tables 1-3 and build/animation_bench show them.
#pragma once

#include <string>
#include <vector>

#include "steadylight/report/stats_series.h"

namespace steadylight {

/// One `<table class="summary">` per scene, as HTML.
std::string build_summary_tables_html(const std::vector<StatsSeries>& series);

}  // namespace steadylight
