#include "steadylight/report/frame_catalog.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>

#include "steadylight/base/error.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

FrameStats load_frame_stats(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw InputError(path, "cannot open");
    try {
        return nlohmann::json::parse(in).get<FrameStats>();
    } catch (const nlohmann::json::exception& e) {
        throw InputError(path, std::string("not a frame statistics file: ") + e.what());
    }
}

/// Files a render writes per frame; AOV PNGs (`<scene>_<frame>.<layer>.png`) do not match.
void add_frame_file(std::map<std::pair<std::string, int>, CatalogFrame>& frames, const fs::path& path) {
    static const std::regex pattern(R"((.+)_(\d{4,9})\.(exr|png|stats\.json))");
    std::smatch match;
    const std::string name = path.filename().string();
    if (!std::regex_match(name, match, pattern)) return;
    CatalogFrame& frame = frames[{match[1].str(), std::stoi(match[2])}];
    frame.scene = match[1];
    frame.frame = std::stoi(match[2]);
    const std::string kind = match[3];
    (kind == "exr" ? frame.exr_file : kind == "png" ? frame.png_file : frame.stats_file) = path.string();
}

}  // namespace

std::vector<std::string> FrameCatalog::scenes() const {
    std::vector<std::string> names;
    for (const CatalogFrame& frame : frames)
        if (names.empty() || names.back() != frame.scene) names.push_back(frame.scene);
    return names;
}

std::vector<CatalogFrame> FrameCatalog::frames_of(const std::string& scene) const {
    std::vector<CatalogFrame> result;
    std::copy_if(frames.begin(), frames.end(), std::back_inserter(result),
                 [&](const CatalogFrame& frame) { return frame.scene == scene; });
    return result;
}

FrameCatalog load_frame_catalog(const std::string& out_dir) {
    std::error_code error;
    if (!fs::is_directory(out_dir, error)) throw InputError(out_dir, "no such folder");
    // Collect the files per (scene, frame); the map keeps them sorted.
    std::map<std::pair<std::string, int>, CatalogFrame> found;
    for (fs::directory_iterator it(out_dir, error), end; !error && it != end; it.increment(error))
        if (std::error_code ignored; it->is_regular_file(ignored)) add_frame_file(found, it->path());
    if (error) throw InputError(out_dir, "cannot list the folder: " + error.message());
    if (found.empty())
        throw InputError(out_dir, "no frames found (expected <scene>_<frame:04>.exr, .png or .stats.json)");
    // Read the statistics of each frame.
    FrameCatalog catalog{out_dir, {}};
    for (auto& [key, frame] : found) {
        if (!frame.stats_file.empty()) frame.stats = load_frame_stats(frame.stats_file);
        catalog.frames.push_back(std::move(frame));
    }
    return catalog;
}

}  // namespace steadylight
