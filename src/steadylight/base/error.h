// Errors in what the user gave us (scene files, meshes, settings, command-line values), and
// errors writing the outputs (a full disk, a folder that cannot be written). They carry the file
// and the place inside it, and are caught once, in main (docs/style.md).
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

/// Writing an output file failed (no space left, a read-only folder, a folder where a file should
/// be): the message names the file and says why. Nothing of the file is left under its name.
class OutputError : public std::runtime_error {
public:
    OutputError(const std::string& path, const std::string& what)
        : std::runtime_error("cannot write " + path + ": " + what) {}
};

}  // namespace steadylight
