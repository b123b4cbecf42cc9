// The rendering methods and the one table that describes them: each method's name, what it
// is, whether it runs the segment pass, which settings it reads, its AOV layers and how it
// renders a frame from the passes. Everything that differs between methods is decided here,
// so the rest of the program (render.cpp, the settings file, the report, the command line)
// asks the table instead of comparing method names.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "steadylight/base/image.h"
#include "steadylight/methods/path_tracer.h"
#include "steadylight/passes/frame_stats.h"
#include "steadylight/passes/localized_settings.h"
#include "steadylight/passes/photon_mapping_settings.h"
#include "steadylight/passes/segment_cache.h"
#include "steadylight/passes/shading_pass.h"
#include "steadylight/shading/frame_context.h"

namespace steadylight {

enum class Method {
    localized,  // the paper's method: static cache per segment, localized final gathering
    photon,     // photon mapping with final gathering, every frame from scratch (the paper's reference)
    frozen,     // the static cache reused as it is, recomputed on dynamic objects only
    path,       // the path tracer, ground truth
};

/// What an AOV layer holds: a term of the light (direct, indirect, caustic, specular: what a
/// compositor grades apart) or a picture of how the method worked (its records, the influence,
/// the corrections: the paper's figures). `--layers` chooses which a frame's files get.
enum class LayerKind { term, analysis };

struct LayerInfo {
    std::string_view name;
    LayerKind kind;

    bool operator==(const LayerInfo&) const = default;
};

/// The settings of every method; each reads its own parts (MethodInfo::reads).
struct MethodSettings {
    Method method = Method::localized;
    PathTracerSettings path;
    PhotonMappingSettings photon;  // photon, localized and frozen: one copy for all three
    LocalizedSettings localized;
};

/// A finished frame: the image, its AOV layers in the method's order, and the statistics of its
/// phases when the method has them.
struct RenderedFrame {
    Image beauty;
    std::vector<NamedImage> layers;
    std::optional<FrameStats> stats;
    /// With a transparent background (Camera::transparent_background): the share of each
    /// pixel's camera rays that met a surface, grey; the beauty and its layers are premultiplied.
    std::optional<Image> alpha;
};

/// Renders one frame; `solution` is the segment's static solution for a method with a static
/// pass, else null. With AnalysisLayers::left_out the method may leave its analysis layers
/// empty (they are not written).
using RenderFrameFunction = RenderedFrame (*)(const FrameContext& context, const StaticSolution* solution,
                                              const MethodSettings& settings, AnalysisLayers analysis);

struct MethodInfo {
    Method method;
    std::string_view name;         // on the command line, in the settings file and statistics
    std::string_view description;  // for --help
    bool has_static_pass;          // runs the segment pass (static photons and cache) once per segment
    bool is_reference;             // the method the report compares the others with (ratios)
    struct Reads {
        bool path = false, photon = false, localized = false;
    } reads;                        // the parts of MethodSettings it reads
    std::vector<LayerInfo> layers;  // its AOV layers after the beauty, in EXR order
    RenderFrameFunction render_frame;
};

/// Every method, the default (localized) first.
const std::vector<MethodInfo>& methods();
const MethodInfo& method_info(Method method);
/// The method called `name`, or nullptr.
const MethodInfo* find_method(std::string_view name);
/// The method called `name`; an InputError naming `where` and listing the methods otherwise.
Method parse_method(std::string_view name, const std::string& where);
/// "localized, photon, frozen, path".
std::string method_names();

/// The settings the chosen method reads, as the settings file holds them: {"photon": ...}.
nlohmann::json method_settings_json(const MethodSettings& settings);
/// Checks the settings the chosen method reads (validate() of each); throws InputError.
void validate(const MethodSettings& settings);

}  // namespace steadylight
