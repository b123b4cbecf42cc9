// Errors in what the user gave us (scene files, meshes, settings, command-line values).
// They carry the file and the place inside it, and are caught once, in main (STYLE.md §5).
#pragma once

#include <stdexcept>
#include <string>

namespace steadylight {

class InputError : public std::runtime_error {
public:
    /// `where` is a file name, optionally followed by ":" and a JSON pointer or line.
    InputError(const std::string& where, const std::string& what)
        : std::runtime_error(where.empty() ? what : where + ": " + what) {}
};

}  // namespace steadylight
