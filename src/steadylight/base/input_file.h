// Reading the files a scene refers to (the scene file, OBJ meshes, glTF files, their buffers and
// images): only regular files are read. A FIFO would block the reader forever and a device such
// as /dev/zero never ends, so both, and folders, are refused with a message naming the file
// before a byte is read.
#pragma once

#include <string>

namespace steadylight {

/// The most bytes read from one input file: beyond it a file is refused, not read (the largest
/// scene file we have, a 2-million-triangle terrain, is 59 MB; the glTF reader takes at most 4 GB).
constexpr size_t max_input_file_bytes = size_t(2) << 30;

/// Where a scene's input files may lie: anywhere (the default: relative paths, absolute ones and
/// `..` alike), or, for a farm that renders scene files from others (--confine-inputs), only
/// inside the scene file's folder.
class InputFolder {
public:
    InputFolder() = default;
    /// Inputs only inside the folder of `scene_file`, compared as canonical paths (symbolic
    /// links resolved, so a link inside that points outside does not count as inside).
    static InputFolder of_scene(const std::string& scene_file);

    /// Throws InputError naming `path` when it lies outside the folder.
    void check(const std::string& path) const;
    bool confined() const { return !m_folder.empty(); }

private:
    std::string m_folder;  // canonical; empty: anywhere
};

/// The whole content of `path`, which must lie where `inputs` allows. Throws InputError naming
/// `path`: outside the folder, "cannot open: file not found", "not a regular file: it is a FIFO"
/// (or a device, a folder, a socket), or why it could not be read.
std::string read_input_file(const std::string& path, const InputFolder& inputs = {});

}  // namespace steadylight
