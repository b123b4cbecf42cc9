// glTF node placements and animations (gltf_animation.h).
#include "steadylight/scene/gltf_animation.h"

#include <algorithm>
#include <array>
#include <cmath>
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
    for (size_t c = 0; c < 3; ++c)
        columns[c] = {float(m[4 * c]), float(m[4 * c + 1]), float(m[4 * c + 2])};
    trs.scale = {length(columns[0]), length(columns[1]), length(columns[2])};
    // A mirroring matrix is a rotation times a negative scale; put the sign on x.
    if (dot(cross(columns[0], columns[1]), columns[2]) < 0) trs.scale.x = -trs.scale.x;
    // A zero scale flattens the basis beyond recovering a rotation; the object is invisible.
    if (trs.scale.x == 0 || trs.scale.y == 0 || trs.scale.z == 0) return trs;
    trs.rotation = Quat::from_basis(columns[0] / trs.scale.x, columns[1] / trs.scale.y,
                                    columns[2] / trs.scale.z);
    return trs;
}


Interpolation parse_interpolation(const GltfFile& file, const std::string& name,
                                  const std::string& where) {
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
            file.fail(where,
                      "input times must be strictly increasing (key " + std::to_string(i) + ")");
    return times;
}

template <class T>
Track<T> make_track(const GltfFile& file, const tinygltf::AnimationSampler& sampler,
                    std::vector<T> values, const std::string& where) {
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
    Track<Quat> track =
        make_track(file, sampler, read_quats(file, sampler.output, where + ", output"), where);
    // Normalise the values but not the tangents of a cubic spline, which are derivatives.
    const bool cubic = track.interpolation == Interpolation::cubic_spline;
    for (size_t i = 0; i < track.values.size(); ++i)
        if (!cubic || i % 3 == 1) track.values[i] = normalized_or_identity(track.values[i]);
    return track;
}

/// Points the channel's sampler at the node path it targets; false for paths it cannot animate.
bool apply_channel(const GltfFile& file, const tinygltf::AnimationSampler& sampler,
                   const std::string& path, AnimatedTrs& target, const std::string& where) {
    const auto vec3_track = [&] {
        return make_track(file, sampler, read_vec3s(file, sampler.output, where + ", output"),
                          where);
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
float animation_duration_s(const GltfFile& file, const tinygltf::Animation& animation,
                           const std::string& where) {
    float duration_s = 0;
    for (size_t s = 0; s < animation.samplers.size(); ++s) {
        const std::string sampler_where = where + ", sampler " + std::to_string(s);
        duration_s = std::max(
            duration_s, read_key_times(file, animation.samplers[s].input, sampler_where).back());
    }
    return duration_s;
}

/// The key spacing of `times` when it is even (within float rounding of k / fps), else 0.
float even_key_spacing_s(const std::vector<float>& times) {
    const float dt = (times.back() - times.front()) / float(times.size() - 1);
    for (size_t i = 1; i < times.size(); ++i)
        if (!(std::abs(times[i] - times[i - 1] - dt) <= 1e-3f * dt)) return 0;
    return dt;
}

/// `rate` snapped to the common frame rate within 0.1% of it, or 0 when there is none.
float common_frame_rate(float rate) {
    constexpr std::array<float, 10> rates = {24000 / 1001.0f, 24, 25, 30000 / 1001.0f, 30, 48, 50, 60000 / 1001.0f, 60, 120};
    for (const float common : rates)
        if (std::abs(rate - common) <= 1e-3f * common) return common;
    return 0;
}

}  // namespace

std::optional<float> sampled_frame_rate(const GltfFile& file) {
    float rate = 0;
    for (size_t a = 0; a < file.model.animations.size(); ++a) {
        const tinygltf::Animation& animation = file.model.animations[a];
        for (size_t s = 0; s < animation.samplers.size(); ++s) {
            const tinygltf::AnimationSampler& sampler = animation.samplers[s];
            if (sampler.interpolation == "CUBICSPLINE") continue;
            const std::string where = describe("animation", a, animation.name) + ", sampler " + std::to_string(s);
            const std::vector<float> times = read_floats(file, sampler.input, where + ", input");
            if (times.size() < 3) continue;
            const float dt = even_key_spacing_s(times);
            const float sampler_rate = dt > 0 ? common_frame_rate(1 / dt) : 0;
            if (sampler_rate == 0 || (rate != 0 && sampler_rate != rate)) return std::nullopt;
            rate = sampler_rate;
        }
    }
    return rate > 0 ? std::optional<float>(rate) : std::nullopt;
}

AnimatedTrs node_placement(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) return decompose(node.matrix);
    AnimatedTrs trs;
    if (node.translation.size() == 3) trs.translation = to_vec3(node.translation);
    if (node.rotation.size() == 4)
        trs.rotation = normalized_or_identity({float(node.rotation[0]), float(node.rotation[1]),
                                               float(node.rotation[2]), float(node.rotation[3])});
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
            if (size_t(channel.target_node) >= placements.size())
                file.fail(channel_where, "target node out of range");
            if (channel.sampler < 0 || size_t(channel.sampler) >= animation.samplers.size())
                file.fail(channel_where, "sampler index out of range");
            const tinygltf::AnimationSampler& sampler = animation.samplers[size_t(channel.sampler)];
            if (!apply_channel(file, sampler, channel.target_path,
                               placements[size_t(channel.target_node)], channel_where))
                continue;
            if (!animated.insert({channel.target_node, channel.target_path}).second)
                spdlog::warn(
                    "{}: {}: node {} {} is animated by several channels; the last one wins",
                    file.path, channel_where, channel.target_node, channel.target_path);
        }
    }
    return duration_s;
}

}  // namespace steadylight::gltf
