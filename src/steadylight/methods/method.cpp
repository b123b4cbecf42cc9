// The method table (method.h). A method's layers are listed once, below, as the members of its
// frame struct that hold them: adding an AOV is a member of the frame struct (in the pass that
// computes it) and a line here.
#include "steadylight/methods/method.h"

#include <variant>

#include <fmt/format.h>

#include "steadylight/base/error.h"
#include "steadylight/methods/photon_mapping.h"
#include "steadylight/passes/frame_pass.h"

namespace steadylight {
namespace {

/// An AOV of a method's frame struct: its name, what it holds and where the frame keeps it (a
/// colour image or a grey one).
template <class Frame>
struct LayerOf {
    std::string_view name;
    LayerKind kind;
    std::variant<Image Frame::*, GreyImage Frame::*> image;
};

constexpr LayerKind term = LayerKind::term, analysis = LayerKind::analysis;

const std::vector<LayerOf<PhotonFrame>> photon_layers = {
    {"direct", term, &PhotonFrame::direct},       {"indirect", term, &PhotonFrame::indirect},
    {"caustic", term, &PhotonFrame::caustic},     {"specular", term, &PhotonFrame::specular},
    {"records", analysis, &PhotonFrame::records},
};

const std::vector<LayerOf<LocalizedFrame>> localized_layers = {
    {"direct", term, &LocalizedFrame::direct},
    {"indirect", term, &LocalizedFrame::indirect},
    {"caustic", term, &LocalizedFrame::caustic},
    {"specular", term, &LocalizedFrame::specular},
    {"indirect_static", analysis, &LocalizedFrame::indirect_static},
    {"L_y", analysis, &LocalizedFrame::L_y},
    {"L_t", analysis, &LocalizedFrame::L_t},
    {"influence", analysis, &LocalizedFrame::influence},
    {"dynamic", analysis, &LocalizedFrame::dynamic},
    {"static_records", analysis, &LocalizedFrame::static_records},
    {"dynamic_records", analysis, &LocalizedFrame::dynamic_records},
    {"changed", analysis, &LocalizedFrame::changed},
};

const std::vector<LayerOf<PathFrame>> path_layers = {};  // the beauty only

template <class Frame>
std::vector<LayerInfo> infos_of(const std::vector<LayerOf<Frame>>& layers) {
    std::vector<LayerInfo> infos;
    for (const LayerOf<Frame>& layer : layers) infos.push_back({layer.name, layer.kind});
    return infos;
}

/// `frame` as a RenderedFrame of `method`, its layers taken out in table order.
template <class Frame>
RenderedFrame rendered(Method method, Frame&& frame, const std::vector<LayerOf<std::decay_t<Frame>>>& layers) {
    RenderedFrame out{std::move(frame.beauty), {}, std::move(frame.stats), std::move(frame.alpha)};
    out.stats->method = std::string(method_info(method).name);
    for (const auto& layer : layers)
        std::visit(
            [&](auto member) {
                out.layers.push_back({std::string(layer.name), std::move(frame.*member)});
            },
            layer.image);
    return out;
}

RenderedFrame render_localized(const FrameContext& context, const StaticSolution* solution,
                               const MethodSettings& settings, AnalysisLayers analysis_layers) {
    return rendered(Method::localized,
                    run_frame_pass(context, *solution, settings.photon, settings.localized, StaticCacheUse::corrected,
                                   analysis_layers),
                    localized_layers);
}

RenderedFrame render_frozen(const FrameContext& context, const StaticSolution* solution, const MethodSettings& settings,
                            AnalysisLayers analysis_layers) {
    return rendered(Method::frozen,
                    run_frame_pass(context, *solution, settings.photon, settings.localized, StaticCacheUse::frozen,
                                   analysis_layers),
                    localized_layers);
}

// Its one analysis layer, the records' picture, costs next to nothing: always made.
RenderedFrame render_photon(const FrameContext& context, const StaticSolution* solution, const MethodSettings& settings,
                            AnalysisLayers) {
    return rendered(Method::photon,
                    render_photon_mapped(context, settings.photon, solution ? solution->photon_paths.get() : nullptr),
                    photon_layers);
}

RenderedFrame render_path(const FrameContext& context, const StaticSolution*, const MethodSettings& settings,
                          AnalysisLayers) {
    return rendered(Method::path, render_path_traced(context, settings.path), path_layers);
}

}  // namespace

const std::vector<MethodInfo>& methods() {
    static const std::vector<MethodInfo> table = {
        {Method::localized,
         "localized",
         "the paper's method",
         true,
         false,
         {.photon = true, .localized = true},
         infos_of(localized_layers),
         render_localized},
        {Method::photon,
         "photon",
         "photon mapping every frame from scratch",
         false,
         true,
         {.photon = true},
         infos_of(photon_layers),
         render_photon},
        {Method::frozen,
         "frozen",
         "static cache reused as it is",
         true,
         false,
         {.photon = true},
         infos_of(localized_layers),
         render_frozen},
        {Method::path,
         "path",
         "path-traced ground truth",
         false,
         false,
         {.path = true},
         infos_of(path_layers),
         render_path},
    };
    return table;
}

const MethodInfo& method_info(Method method) {
    for (const MethodInfo& info : methods())
        if (info.method == method) return info;
    throw std::logic_error("method missing from the method table");
}

const MethodInfo* find_method(std::string_view name) {
    for (const MethodInfo& info : methods())
        if (info.name == name) return &info;
    return nullptr;
}

Method parse_method(std::string_view name, const std::string& where) {
    if (const MethodInfo* info = find_method(name)) return info->method;
    throw InputError(where, fmt::format("unknown method \"{}\" ({})", name, method_names()));
}

std::string method_names() {
    std::string names;
    for (const MethodInfo& info : methods()) names += (names.empty() ? "" : ", ") + std::string(info.name);
    return names;
}

/// Calls `visit(key, part)` for each part of `settings` that its method reads.
template <class Visit>
void for_each_part_read(const MethodSettings& settings, Visit&& visit) {
    const MethodInfo::Reads& reads = method_info(settings.method).reads;
    if (reads.path) visit("path", settings.path);
    if (reads.photon) visit("photon", settings.photon);
    if (reads.localized) visit("localized", settings.localized);
}

nlohmann::json method_settings_json(const MethodSettings& settings) {
    nlohmann::json json = nlohmann::json::object();
    for_each_part_read(settings, [&](const char* key, const auto& part) { json[key] = part; });
    return json;
}

void validate(const MethodSettings& settings) {
    for_each_part_read(settings, [](const char* key, const auto& part) { validate(part, std::string("/") + key); });
}

}  // namespace steadylight
