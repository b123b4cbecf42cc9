#include "steadylight/report/report_images.h"

#include <fmt/format.h>

#include <algorithm>

#include "steadylight/output/image_writer.h"
#include "steadylight/report/html.h"

namespace steadylight {
namespace {

std::string thumbnail_caption(const CatalogFrame& frame) {
    std::string caption = fmt::format("{:04d}", frame.frame);
    if (frame.stats)
        caption += fmt::format("<br>{} &middot; {:.2f} s", escape_html(frame.method()), frame.stats->total_s);
    return caption;
}

std::string thumbnail(const CatalogFrame& frame) {
    const std::string image = frame.png_file.empty() ? "<div class=\"missing\">no PNG</div>"
                                                     : fmt::format(R"(<img src="{}" alt="{} frame {}">)",
                                                                   png_data_uri(read_file_bytes(frame.png_file)),
                                                                   escape_html(frame.scene), frame.frame);
    return fmt::format("<figure class=\"frame\" data-frame=\"{}\">{}<figcaption>{}</figcaption></figure>\n",
                       frame.frame, image, thumbnail_caption(frame));
}

bool has_channel(const ExrLayerInfo& layer, const char* channel) {
    return std::find(layer.channels.begin(), layer.channels.end(), channel) != layer.channels.end();
}

/// RGB, or grey (one Y channel), as read_exr reads them.
bool is_viewable(const ExrLayerInfo& layer) {
    return (has_channel(layer, "R") && has_channel(layer, "G") && has_channel(layer, "B")) || has_channel(layer, "Y");
}

bool is_beauty(const std::string& layer_name) { return layer_name.empty() || layer_name == "beauty"; }

/// The layers to show, beauty first (OpenEXR lists channels alphabetically). Frames store the
/// beauty twice, unnamed and as `beauty` (output/frame_layers.h): it is shown once, from the
/// named layer when there is one.
std::vector<ExrLayerInfo> shown_layers(std::vector<ExrLayerInfo> layers) {
    const bool named_beauty =
        std::any_of(layers.begin(), layers.end(), [](const ExrLayerInfo& l) { return l.name == "beauty"; });
    if (named_beauty) std::erase_if(layers, [](const ExrLayerInfo& l) { return l.name.empty(); });
    std::stable_partition(layers.begin(), layers.end(), [](const ExrLayerInfo& l) { return is_beauty(l.name); });
    return layers;
}

std::string layer_figure(const std::string& exr_file, const ExrLayerInfo& layer) {
    const std::string shown_name = is_beauty(layer.name) ? "beauty" : layer.name;
    if (!is_viewable(layer)) {
        std::string channels;
        for (const std::string& channel : layer.channels) channels += (channels.empty() ? "" : ", ") + channel;
        return fmt::format(
            "<figure class=\"aov-skipped\" data-layer=\"{0}\"><figcaption>{0}: channels {1}, neither "
            "RGB nor Y, not shown</figcaption></figure>\n",
            escape_html(shown_name), escape_html(channels));
    }
    // The default view (no exposure, standard curve): AOVs such as record counts are data.
    const std::vector<unsigned char> png = encode_png(read_exr(exr_file, layer.name));
    return fmt::format(
        "<figure class=\"aov\" data-layer=\"{0}\"><img src=\"{1}\" alt=\"{0}\"><figcaption>{0}</figcaption>"
        "</figure>\n",
        escape_html(shown_name), png_data_uri(png));
}

std::string scene_aovs(const std::string& scene, const std::vector<CatalogFrame>& frames,
                       std::optional<int> requested_frame) {
    std::string html = "<h3>" + escape_html(scene);
    const std::optional<int> chosen = choose_aov_frame(frames, requested_frame);
    if (!chosen) return html + "</h3>\n<p>No frame with an EXR.</p>\n";
    const CatalogFrame& frame =
        *std::find_if(frames.begin(), frames.end(), [&](const CatalogFrame& f) { return f.frame == *chosen; });
    html += fmt::format(", frame {}</h3>\n", frame.frame);
    if (requested_frame && *requested_frame != frame.frame)
        html +=
            fmt::format("<p>Frame {} has no EXR in this scene; showing frame {}.</p>\n", *requested_frame, frame.frame);
    html += "<div class=\"aovs\" data-scene=\"" + escape_html(scene) + "\">\n";
    const std::vector<ExrLayerInfo> layers = shown_layers(read_exr_layers(frame.exr_file));
    for (const ExrLayerInfo& layer : layers) html += layer_figure(frame.exr_file, layer);
    return html + "</div>\n";
}

}  // namespace

std::string build_contact_sheet_html(const FrameCatalog& catalog) {
    std::string html;
    for (const std::string& scene : catalog.scenes()) {
        html +=
            "<h3>" + escape_html(scene) + "</h3>\n<div class=\"sheet\" data-scene=\"" + escape_html(scene) + "\">\n";
        for (const CatalogFrame& frame : catalog.frames_of(scene)) html += thumbnail(frame);
        html += "</div>\n";
    }
    return html;
}

std::optional<int> choose_aov_frame(const std::vector<CatalogFrame>& frames, std::optional<int> requested) {
    std::vector<int> with_exr;
    for (const CatalogFrame& frame : frames)
        if (!frame.exr_file.empty()) with_exr.push_back(frame.frame);
    if (with_exr.empty()) return std::nullopt;
    if (requested && std::find(with_exr.begin(), with_exr.end(), *requested) != with_exr.end()) return requested;
    return with_exr[with_exr.size() / 2];
}

std::string build_aov_html(const FrameCatalog& catalog, std::optional<int> requested_frame) {
    std::string html;
    for (const std::string& scene : catalog.scenes())
        html += scene_aovs(scene, catalog.frames_of(scene), requested_frame);
    return html;
}

}  // namespace steadylight
