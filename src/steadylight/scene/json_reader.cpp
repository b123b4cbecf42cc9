#include "steadylight/scene/json_reader.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>

#include "steadylight/base/error.h"
#include "steadylight/base/input_file.h"

namespace steadylight {

using nlohmann::json;

JsonObject::JsonObject(const json& value, std::string file, std::string pointer)
    : m_json(value), m_file(std::move(file)), m_pointer(std::move(pointer)) {
    if (!m_json.is_object()) fail("", "expected an object");
}

bool JsonObject::has(const std::string& key) const {
    m_read.insert(key);
    return m_json.contains(key);
}

bool JsonObject::is_array(const std::string& key) const { return has(key) && m_json.at(key).is_array(); }

std::string JsonObject::path(const std::string& key) const {
    return key.empty() ? (m_pointer.empty() ? "/" : m_pointer) : m_pointer + "/" + key;
}

void JsonObject::fail(const std::string& key, const std::string& message) const {
    throw InputError(m_file + ":" + path(key), message);
}

const json& JsonObject::at(const std::string& key) const {
    m_read.insert(key);
    if (!m_json.contains(key)) fail(key, "missing required field");
    return m_json.at(key);
}

namespace {

float checked_number(const json& value, const JsonObject& where, const std::string& key) {
    if (!value.is_number()) where.fail(key, "expected a number, got " + value.dump());
    const double v = value.get<double>();
    if (!std::isfinite(v) || std::abs(v) > 3.0e38) where.fail(key, "number is not finite");
    return float(v);
}

}  // namespace

float JsonObject::number(const std::string& key) const { return checked_number(at(key), *this, key); }

float JsonObject::number(const std::string& key, float fallback) const { return has(key) ? number(key) : fallback; }

int JsonObject::integer(const std::string& key, int fallback) const {
    if (!has(key)) return fallback;
    const json& value = at(key);
    if (!value.is_number_integer()) fail(key, "expected an integer, got " + value.dump());
    // Non-negative integers are unsigned in nlohmann::json: 2^64 - 1 read as int64_t would be -1.
    const bool fits = value.is_number_unsigned() ? value.get<uint64_t>() <= uint64_t(std::numeric_limits<int>::max())
                                                 : value.get<int64_t>() >= std::numeric_limits<int>::min() &&
                                                       value.get<int64_t>() <= std::numeric_limits<int>::max();
    if (!fits) fail(key, "expected an integer within +-2^31, got " + value.dump());
    return value.get<int>();
}

bool JsonObject::boolean(const std::string& key, bool fallback) const {
    if (!has(key)) return fallback;
    const json& value = at(key);
    if (!value.is_boolean()) fail(key, "expected true or false, got " + value.dump());
    return value.get<bool>();
}

std::string JsonObject::string(const std::string& key) const {
    const json& value = at(key);
    if (!value.is_string()) fail(key, "expected a string, got " + value.dump());
    return value.get<std::string>();
}

std::string JsonObject::string(const std::string& key, const std::string& fallback) const {
    return has(key) ? string(key) : fallback;
}

std::vector<float> JsonObject::fixed_numbers(const json& value, const std::string& where, size_t size) const {
    if (!value.is_array() || (size != 0 && value.size() != size))
        fail(where, size ? "expected an array of " + std::to_string(size) + " numbers, got " + value.dump()
                         : "expected an array of numbers, got " + value.dump());
    std::vector<float> result;
    for (size_t i = 0; i < value.size(); ++i)
        result.push_back(checked_number(value[i], *this, where + "/" + std::to_string(i)));
    return result;
}

Vec3 JsonObject::vec3(const std::string& key) const {
    const std::vector<float> v = fixed_numbers(at(key), key, 3);
    return {v[0], v[1], v[2]};
}

Vec3 JsonObject::vec3(const std::string& key, Vec3 fallback) const { return has(key) ? vec3(key) : fallback; }

Rgb JsonObject::rgb_value(const json& value, const std::string& where) const {
    if (value.is_number()) {
        const float v = checked_number(value, *this, where);
        return {v, v, v};
    }
    const std::vector<float> v = fixed_numbers(value, where, 3);
    return {v[0], v[1], v[2]};
}

Rgb JsonObject::rgb(const std::string& key, Rgb fallback) const {
    return has(key) ? rgb_value(at(key), key) : fallback;
}

std::vector<Rgb> JsonObject::rgbs(const std::string& key) const {
    const json& value = at(key);
    if (!value.is_array()) fail(key, "expected an array, got " + value.dump());
    std::vector<Rgb> result;
    for (size_t i = 0; i < value.size(); ++i) result.push_back(rgb_value(value[i], key + "/" + std::to_string(i)));
    return result;
}

std::vector<float> JsonObject::numbers(const std::string& key) const { return fixed_numbers(at(key), key, 0); }

std::vector<std::vector<float>> JsonObject::tuples(const std::string& key, size_t size) const {
    const json& value = at(key);
    if (!value.is_array()) fail(key, "expected an array, got " + value.dump());
    std::vector<std::vector<float>> result;
    for (size_t i = 0; i < value.size(); ++i)
        result.push_back(fixed_numbers(value[i], key + "/" + std::to_string(i), size));
    return result;
}

JsonObject JsonObject::object(const std::string& key) const { return JsonObject(at(key), m_file, path(key)); }

std::vector<JsonObject> JsonObject::objects(const std::string& key) const {
    const json& value = at(key);
    if (!value.is_array()) fail(key, "expected an array, got " + value.dump());
    std::vector<JsonObject> result;
    for (size_t i = 0; i < value.size(); ++i)
        result.emplace_back(value[i], m_file, path(key) + "/" + std::to_string(i));
    return result;
}

std::vector<std::pair<std::string, JsonObject>> JsonObject::members(const std::string& key) const {
    const json& value = at(key);
    if (!value.is_object()) fail(key, "expected an object, got " + value.dump());
    std::vector<std::pair<std::string, JsonObject>> result;
    for (auto it = value.begin(); it != value.end(); ++it)
        result.emplace_back(it.key(), JsonObject(it.value(), m_file, path(key) + "/" + it.key()));
    return result;
}

std::vector<std::string> JsonObject::keys() const {
    std::vector<std::string> result;
    for (auto it = m_json.begin(); it != m_json.end(); ++it) result.push_back(it.key());
    return result;
}

void JsonObject::warn_unread() const {
    for (auto it = m_json.begin(); it != m_json.end(); ++it)
        if (!m_read.count(it.key())) spdlog::warn("{}:{}: unknown field \"{}\" ignored", m_file, path(""), it.key());
}

json parse_json_file(const std::string& path) {
    const std::string text = read_input_file(path);
    try {
        return json::parse(text);
    } catch (const json::exception& e) {
        throw InputError(path, std::string("invalid JSON: ") + e.what());
    }
}

}  // namespace steadylight
