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

/// The whole content of `path`. Throws InputError naming `path`: "cannot open: file not found",
/// "not a regular file: it is a FIFO" (or a device, a folder, a socket), or why it could not be read.
std::string read_input_file(const std::string& path);

}  // namespace steadylight
