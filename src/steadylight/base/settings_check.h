// Checks for the settings structs' validate() functions (docs/style.md): each names the setting by
// its place in the settings file's JSON ("/photon/cache/accuracy"), so that a bad value reads the
// same whether it came from the command line, a test or a benchmark.
#pragma once

#include <string>

#include <fmt/format.h>

#include "steadylight/base/error.h"

namespace steadylight {

/// Throws InputError("settings <where>", ...) unless lo <= value <= hi (NaN fails too).
template <class T>
void check_setting_range(const std::string& where, T value, T lo, T hi) {
    if (!(lo <= value && value <= hi))
        throw InputError("settings " + where, fmt::format("{} is outside [{}, {}]", value, lo, hi));
}

/// Throws InputError("settings <where>", what) unless `ok`.
inline void check_setting(bool ok, const std::string& where, const std::string& what) {
    if (!ok) throw InputError("settings " + where, what);
}

}  // namespace steadylight
