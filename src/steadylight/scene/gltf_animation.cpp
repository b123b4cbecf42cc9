// glTF node placements and animations (gltf_animation.h).
#include "steadylight/scene/gltf_animation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include "steadylight/scene/gltf_accessors.h"

namespace steadylight::gltf {
namespace {

Vec3 to_vec3(const std::vector<double>& v) { return {float(v[0]), float(v[1]), float(v[2])}; }

Quat normalized_or_identity(Quat q) { return dot(q, q) > 0 ? normalize(q) : Quat{}; }

/// Splits a column-major node matrix into T * R * S. glTF 2.0 §5.25 requires node matrices
/// to be decomposable (no shear), so three column lengths and one rotation say everything.
AnimatedTrs decompose(const std::vector<double>& m) {
    AnimatedTrs trs;
    trs.translation = {float(m[12]), float(m[13]), float(m[14])};
    Vec3 columns[3];
    for (size_t c = 0; c < 3; ++c) columns[c] = {float(m[4 * c]), float(m[4 * c + 1]), float(m[4 * c + 2])};
    trs.scale = {length(columns[0]), length(columns[1]), length(columns[2])};
    // A mirroring matrix is a rotation times a negative scale; put the sign on x.
    if (dot(cross(columns[0], columns[1]), columns[2]) < 0) trs.scale.x = -trs.scale.x;
    // A zero scale flattens the basis beyond recovering a rotation; the object is invisible.
    if (trs.scale.x == 0 || trs.scale.y == 0 || trs.scale.z == 0) return trs;
    trs.rotation = Quat::from_basis(columns[0] / trs.scale.x, columns[1] / trs.scale.y, columns[2] / trs.scale.z);
    return trs;
}

Interpolation parse_interpolation(const GltfFile& file, const std::string& name, const std::string& where) {
    if (name == "LINEAR") return Interpolation::linear;
    if (name == "STEP") return Interpolation::step;
    if (name == "CUBICSPLINE") return Interpolation::cubic_spline;
    file.fail(where, "unknown interpolation \"" + name + "\" (LINEAR, STEP or CUBICSPLINE)");
}

std::vector<float> read_key_times(const GltfFile& file, int accessor, const std::string& where) {
    std::vector<float> times = read_floats(file, accessor, where + ", input");
    if (times.empty()) file.fail(where, "animation sampler has no keys");
    for (size_t i = 1; i < times.size(); ++i)
        if (!(times[i] > times[i - 1]))
            file.fail(where, "input times must be strictly increasing (key " + std::to_string(i) + ")");
    return times;
}

template <class T>
Track<T> make_track(const GltfFile& file, const tinygltf::AnimationSampler& sampler, std::vector<T> values,
                    const std::string& where) {
    Track<T> track;
    track.interpolation = parse_interpolation(file, sampler.interpolation, where);
    track.times = read_key_times(file, sampler.input, where);
    // CUBICSPLINE stores in-tangent, value, out-tangent per key (glTF 2.0 Appendix C).
    const size_t per_key = track.interpolation == Interpolation::cubic_spline ? 3 : 1;
    if (values.size() != per_key * track.times.size())
        file.fail(where, "output has " + std::to_string(values.size()) + " values for " +
                             std::to_string(track.times.size()) + " keys");
    track.values = std::move(values);
    return track;
}

Track<Quat> make_rotation_track(const GltfFile& file, const tinygltf::AnimationSampler& sampler,
                                const std::string& where) {
    Track<Quat> track = make_track(file, sampler, read_quats(file, sampler.output, where + ", output"), where);
    // Normalise the values but not the tangents of a cubic spline, which are derivatives.
    const bool cubic = track.interpolation == Interpolation::cubic_spline;
    for (size_t i = 0; i < track.values.size(); ++i)
        if (!cubic || i % 3 == 1) track.values[i] = normalized_or_identity(track.values[i]);
    return track;
}

/// Points the channel's sampler at the node path it targets; false for paths it cannot animate.
bool apply_channel(const GltfFile& file, const tinygltf::AnimationSampler& sampler, const std::string& path,
                   AnimatedTrs& target, const std::string& where) {
    const auto vec3_track = [&] {
        return make_track(file, sampler, read_vec3s(file, sampler.output, where + ", output"), where);
    };
    if (path == "translation") {
        target.translation_track = vec3_track();
    } else if (path == "rotation") {
        target.rotation_track = make_rotation_track(file, sampler, where);
    } else if (path == "scale") {
        target.scale_track = vec3_track();
    } else {
        file.warn_once(path == "weights" ? "morph target weight animations are ignored"
                                         : "animation target path \"" + path + "\" is ignored",
                       where);
        return false;
    }
    return true;
}

/// The end of the animation's longest sampler, in seconds.
float animation_duration_s(const GltfFile& file, const tinygltf::Animation& animation, const std::string& where) {
    float duration_s = 0;
    for (size_t s = 0; s < animation.samplers.size(); ++s) {
        const std::string sampler_where = where + ", sampler " + std::to_string(s);
        duration_s = std::max(duration_s, read_key_times(file, animation.samplers[s].input, sampler_where).back());
    }
    return duration_s;
}

// The bounds of a sampled rate: slower keys are hand-set ones far apart, faster ones are not
// frames anybody renders.
constexpr double min_sampled_fps = 10;
constexpr double max_sampled_fps = 240;
// Keys are evenly spaced when every interval is within this fraction of their mean spacing, and
// two samplers agree when their spacings are.
constexpr double spacing_tolerance_rel = 1e-3;
// A measured rate within this fraction of a whole number is that number (39.0003 is 39): half
// the 1e-3 between an NTSC rate (30000/1001) and its whole neighbour, and above the drift of
// float32 times summed step by step over five minutes at up to 120 fps (1.7e-4).
constexpr double whole_rate_tolerance_rel = 5e-4;

/// The mean spacing of `times` in seconds when every interval is within the tolerance of it,
/// else nothing. Each float32 time is off by up to half an ulp (FLT_EPSILON / 2 of it), whether
/// the exporter wrote k / fps or summed a float step, so an interval may miss the mean by up to
/// FLT_EPSILON times the latest time on top of the relative tolerance.
std::optional<double> even_key_spacing_s(const std::vector<float>& times) {
    const double dt = (double(times.back()) - times.front()) / double(times.size() - 1);
    const double latest_s = std::max(std::abs(double(times.front())), std::abs(double(times.back())));
    const double slack_s = spacing_tolerance_rel * dt + std::numeric_limits<float>::epsilon() * latest_s;
    for (size_t i = 1; i < times.size(); ++i)
        if (!(std::abs(double(times[i]) - times[i - 1] - dt) <= slack_s)) return std::nullopt;
    return dt;
}

/// Key times of every LINEAR or STEP sampler with three or more keys: the ones an exporter
/// samples. CUBICSPLINE keys are hand-set Bezier keys, and two keys are any two moments.
std::vector<std::vector<float>> sampled_key_times(const GltfFile& file) {
    std::vector<std::vector<float>> sampled;
    for (size_t a = 0; a < file.model.animations.size(); ++a) {
        const tinygltf::Animation& animation = file.model.animations[a];
        for (size_t s = 0; s < animation.samplers.size(); ++s) {
            const tinygltf::AnimationSampler& sampler = animation.samplers[s];
            if (sampler.interpolation == "CUBICSPLINE") continue;
            const std::string where = describe("animation", a, animation.name) + ", sampler " + std::to_string(s);
            std::vector<float> times = read_floats(file, sampler.input, where + ", input");
            if (times.size() >= 3) sampled.push_back(std::move(times));
        }
    }
    return sampled;
}

/// 1 / `spacing_s`, made whole when it is within float noise of a whole number (39.0003 is 39,
/// 29.97003 stays).
float rate_of_spacing(double spacing_s) {
    const double fps = 1 / spacing_s;
    const double whole = std::round(fps);
    return float(std::abs(fps - whole) <= whole_rate_tolerance_rel * fps ? whole : fps);
}

}  // namespace

std::optional<float> sampled_frame_rate(const GltfFile& file) {
    // Take the spacing of the longest sampler: its mean spacing carries the least rounding.
    std::optional<double> spacing_s;
    float longest_s = 0;
    for (const std::vector<float>& times : sampled_key_times(file)) {
        const std::optional<double> dt = even_key_spacing_s(times);
        if (!dt) return std::nullopt;
        if (spacing_s && std::abs(*dt - *spacing_s) > spacing_tolerance_rel * *spacing_s) return std::nullopt;
        if (!spacing_s || times.back() - times.front() > longest_s) {
            spacing_s = dt;
            longest_s = times.back() - times.front();
        }
    }
    if (!spacing_s) return std::nullopt;
    const float fps = rate_of_spacing(*spacing_s);
    if (fps < min_sampled_fps || fps > max_sampled_fps) return std::nullopt;
    return fps;
}

AnimatedTrs node_placement(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) return decompose(node.matrix);
    AnimatedTrs trs;
    if (node.translation.size() == 3) trs.translation = to_vec3(node.translation);
    if (node.rotation.size() == 4)
        trs.rotation = normalized_or_identity(
            {float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2]), float(node.rotation[3])});
    if (node.scale.size() == 3) trs.scale = to_vec3(node.scale);
    return trs;
}

/// Attaches every channel of every animation to `placements`, one per node; returns the
/// longest animation's length in seconds.
float apply_animations(const GltfFile& file, std::vector<AnimatedTrs>& placements) {
    float duration_s = 0;
    std::set<std::pair<int, std::string>> animated;
    for (size_t a = 0; a < file.model.animations.size(); ++a) {
        const tinygltf::Animation& animation = file.model.animations[a];
        const std::string where = describe("animation", a, animation.name);
        duration_s = std::max(duration_s, animation_duration_s(file, animation, where));
        for (size_t c = 0; c < animation.channels.size(); ++c) {
            const tinygltf::AnimationChannel& channel = animation.channels[c];
            const std::string channel_where = where + ", channel " + std::to_string(c);
            // A channel without a node targets something an extension defines; none are supported.
            if (channel.target_node < 0) continue;
            if (size_t(channel.target_node) >= placements.size()) file.fail(channel_where, "target node out of range");
            if (channel.sampler < 0 || size_t(channel.sampler) >= animation.samplers.size())
                file.fail(channel_where, "sampler index out of range");
            const tinygltf::AnimationSampler& sampler = animation.samplers[size_t(channel.sampler)];
            if (!apply_channel(file, sampler, channel.target_path, placements[size_t(channel.target_node)],
                               channel_where))
                continue;
            if (!animated.insert({channel.target_node, channel.target_path}).second)
                spdlog::warn("{}: {}: node {} {} is animated by several channels; the last one wins", file.path,
                             channel_where, channel.target_node, channel.target_path);
        }
    }
    return duration_s;
}

}  // namespace steadylight::gltf
