// Bounds-checked glTF accessors (gltf_accessors.h).
#include "steadylight/scene/gltf_accessors.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <span>

namespace steadylight::gltf {
namespace {

/// An accessor checked to lie inside its buffer: element i starts at `data + i * stride`.
struct AccessorView {
    const unsigned char* data = nullptr;
    size_t stride = 0;
    size_t count = 0;
    int component_type = 0;
    size_t component_size = 0;
    int type = 0;
    bool normalized = false;

    const unsigned char* at(size_t i, int c) const { return data + i * stride + size_t(c) * component_size; }
};

template <class T>
T load_unaligned(const unsigned char* p) {
    T value;
    std::memcpy(&value, p, sizeof value);
    return value;
}

/// Component c of element i as a float; normalised integers map to [0, 1] or [-1, 1] as in
/// glTF 2.0 §3.11 "Animations" (the same rule as for vertex attributes).
float read_component(const AccessorView& view, size_t i, int c) {
    const unsigned char* p = view.at(i, c);
    const auto scale = [&](float value, float max_value) {
        return view.normalized ? std::max(value / max_value, -1.0f) : value;
    };
    switch (view.component_type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return load_unaligned<float>(p);
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            return scale(load_unaligned<int8_t>(p), 127);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return scale(load_unaligned<uint8_t>(p), 255);
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            return scale(load_unaligned<int16_t>(p), 32767);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return scale(load_unaligned<uint16_t>(p), 65535);
    }
    return 0;
}

uint32_t read_unsigned(const AccessorView& view, size_t i) {
    const unsigned char* p = view.at(i, 0);
    switch (view.component_type) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return load_unaligned<uint8_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return load_unaligned<uint16_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return load_unaligned<uint32_t>(p);
    }
    return 0;
}

/// True when `count` elements of `element_size` bytes, `stride` apart from `offset`, fit in
/// `length` bytes; written so that no product can overflow.
bool fits(size_t offset, size_t count, size_t stride, size_t element_size, size_t length) {
    if (count == 0) return offset <= length;
    if (offset > length || element_size > length - offset) return false;
    return count - 1 <= (length - offset - element_size) / stride;
}

/// The bytes of the accessor's bufferView, checked to lie inside their buffer.
std::span<const unsigned char> buffer_view_bytes(const GltfFile& file, const tinygltf::Accessor& accessor,
                                                 const std::string& where) {
    const tinygltf::Model& model = file.model;
    if (accessor.bufferView < 0 || size_t(accessor.bufferView) >= model.bufferViews.size())
        file.fail(where, "accessor has no valid bufferView");
    const tinygltf::BufferView& view = model.bufferViews[size_t(accessor.bufferView)];
    const std::string name = "bufferView " + std::to_string(accessor.bufferView);
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size()) file.fail(where, name + " has no valid buffer");
    const std::vector<unsigned char>& buffer = model.buffers[size_t(view.buffer)].data;
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
        file.fail(where, name + " reaches past the end of its buffer");
    return {buffer.data() + view.byteOffset, view.byteLength};
}

AccessorView view_accessor(const GltfFile& file, int index, const std::string& user) {
    const std::string where = user + ", accessor " + std::to_string(index);
    if (index < 0 || size_t(index) >= file.model.accessors.size()) file.fail(where, "accessor index out of range");
    const tinygltf::Accessor& accessor = file.model.accessors[size_t(index)];
    if (accessor.sparse.isSparse) file.fail(where, "sparse accessors are not supported");
    const std::span<const unsigned char> bytes = buffer_view_bytes(file, accessor, where);
    const int component_size = tinygltf::GetComponentSizeInBytes(uint32_t(accessor.componentType));
    const int components = tinygltf::GetNumComponentsInType(uint32_t(accessor.type));
    if (component_size <= 0 || components <= 0) file.fail(where, "unknown componentType or type");
    const size_t element_size = size_t(component_size) * size_t(components);
    const size_t byte_stride = file.model.bufferViews[size_t(accessor.bufferView)].byteStride;
    const size_t stride = byte_stride ? byte_stride : element_size;
    if (stride < element_size) file.fail(where, "byteStride is smaller than one element");
    if (!fits(accessor.byteOffset, accessor.count, stride, element_size, bytes.size()))
        file.fail(where, "accessor reaches past the end of its bufferView");
    return {.data = bytes.data() + accessor.byteOffset,
            .stride = stride,
            .count = accessor.count,
            .component_type = accessor.componentType,
            .component_size = size_t(component_size),
            .type = accessor.type,
            .normalized = accessor.normalized};
}

/// Views an accessor that must have element `type` and one of `component_types`, which
/// `expected` spells out for the message ("float VEC3").
AccessorView view_typed(const GltfFile& file, int index, const std::string& user, int type,
                        std::initializer_list<int> component_types, const std::string& expected) {
    const AccessorView view = view_accessor(file, index, user);
    const bool component_ok =
        std::find(component_types.begin(), component_types.end(), view.component_type) != component_types.end();
    if (view.type != type || !component_ok)
        file.fail(user, "accessor " + std::to_string(index) + " must be " + expected);
    return view;
}

}  // namespace

std::vector<float> read_floats(const GltfFile& file, int index, const std::string& user) {
    const AccessorView view =
        view_typed(file, index, user, TINYGLTF_TYPE_SCALAR, {TINYGLTF_COMPONENT_TYPE_FLOAT}, "float SCALAR");
    std::vector<float> values(view.count);
    for (size_t i = 0; i < view.count; ++i) values[i] = read_component(view, i, 0);
    return values;
}

std::vector<Vec3> read_vec3s(const GltfFile& file, int index, const std::string& user) {
    const AccessorView view =
        view_typed(file, index, user, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, "float VEC3");
    std::vector<Vec3> values(view.count);
    for (size_t i = 0; i < view.count; ++i)
        values[i] = {read_component(view, i, 0), read_component(view, i, 1), read_component(view, i, 2)};
    return values;
}

std::vector<Quat> read_quats(const GltfFile& file, int index, const std::string& user) {
    const AccessorView view =
        view_typed(file, index, user, TINYGLTF_TYPE_VEC4,
                   {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                    TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                   "VEC4 of floats or normalised integers");
    if (view.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT && !view.normalized)
        file.fail(user, "accessor " + std::to_string(index) + ": integer rotations must be normalized");
    std::vector<Quat> values(view.count);
    for (size_t i = 0; i < view.count; ++i)
        values[i] = {read_component(view, i, 0), read_component(view, i, 1), read_component(view, i, 2),
                     read_component(view, i, 3)};
    return values;
}

std::vector<Vec2> read_texcoords(const GltfFile& file, int index, const std::string& user) {
    const AccessorView view = view_typed(
        file, index, user, TINYGLTF_TYPE_VEC2,
        {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
        "VEC2 of floats or normalised unsigned bytes or shorts");
    if (view.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT && !view.normalized)
        file.fail(user, "accessor " + std::to_string(index) + ": integer texture coordinates must be normalized");
    std::vector<Vec2> values(view.count);
    for (size_t i = 0; i < view.count; ++i) values[i] = {read_component(view, i, 0), read_component(view, i, 1)};
    return values;
}

std::vector<Rgba> read_vec4s(const GltfFile& file, int index, const std::string& user, float w_default) {
    const AccessorView view = view_accessor(file, index, user);
    const bool type_ok = view.type == TINYGLTF_TYPE_VEC3 || view.type == TINYGLTF_TYPE_VEC4;
    const bool component_ok = view.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                              (view.normalized && (view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                                   view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
    if (!type_ok || !component_ok)
        file.fail(user, "accessor " + std::to_string(index) +
                            " must be VEC3 or VEC4 of floats or normalised unsigned integers");
    const int components = view.type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
    std::vector<Rgba> values(view.count);
    for (size_t i = 0; i < view.count; ++i)
        for (int c = 0; c < 4; ++c) values[i][size_t(c)] = c < components ? read_component(view, i, c) : w_default;
    return values;
}

std::vector<int> read_indices(const GltfFile& file, int index, const std::string& user, size_t vertex_count) {
    const AccessorView view = view_typed(file, index, user, TINYGLTF_TYPE_SCALAR,
                                         {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                          TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                                         "unsigned byte, short or int SCALAR");
    std::vector<int> indices(view.count);
    for (size_t i = 0; i < view.count; ++i) {
        const uint32_t vertex = read_unsigned(view, i);
        if (vertex >= vertex_count)
            file.fail(user, "index " + std::to_string(vertex) + " out of range (" + std::to_string(vertex_count) +
                                " vertices)");
        indices[i] = int(vertex);
    }
    return indices;
}

}  // namespace steadylight::gltf
