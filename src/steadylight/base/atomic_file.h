// Writing files so that they appear whole or not at all: the content goes to `<path>.partial`
// in the same folder and is renamed onto `path` only when complete. Nothing is written through a
// symbolic link: an output folder may be one others can write to (a farm's shared folder), and a
// link put where a file goes must not send the write elsewhere. A temporary file is created anew
// (O_EXCL | O_NOFOLLOW, after removing a stale one) and written through its descriptor; a link
// where a finished file goes is an error.
#pragma once

#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace steadylight {

/// Runs `write(temporary_path)` and renames the result onto `path`; on failure removes the
/// temporary file and throws OutputError naming `path`. `temporary_path` names the new file
/// created for the write (through /proc/self/fd where there is one: whatever replaces the
/// temporary's name meanwhile, the write goes to the file created).
void write_file_atomically(const std::string& path, const std::function<void(const std::string&)>& write);

/// While it lives, collects the paths that write_file_atomically renames into place (from any
/// thread): the files of one frame, for its manifest (run/frame_manifest.h). One at a time.
class WrittenFiles {
public:
    WrittenFiles();
    ~WrittenFiles();
    WrittenFiles(const WrittenFiles&) = delete;
    WrittenFiles& operator=(const WrittenFiles&) = delete;

    std::vector<std::string> paths() const;
    void add(const std::string& path);

private:
    mutable std::mutex m_mutex;
    std::vector<std::string> m_paths;
};

/// Creates the folder `dir` (and its parents) and checks that a file can be written in it, before
/// any work: an InputError naming `option` (the command-line option that gave it) otherwise.
void create_output_folder(const std::string& dir, const std::string& option);

/// Creates `path` as a new regular file holding `text`, never through a symbolic link: a file or
/// link already there is removed first, and one put there meanwhile makes it fail. Throws
/// std::runtime_error with the system's reason.
void write_new_file(const std::string& path, const std::string& text);

/// Writes `text` to `path` atomically.
void write_text_file(const std::string& path, const std::string& text);
/// Writes `bytes` to `path` atomically.
void write_binary_file(const std::string& path, const std::vector<unsigned char>& bytes);

}  // namespace steadylight
