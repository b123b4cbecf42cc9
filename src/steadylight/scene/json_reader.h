// Typed, checked reading of a JSON object for the scene loader. Every error names the file and
// the JSON pointer (`ball.json:/objects/3/radius: expected a number`), and keys that nobody read
// are reported, which catches misspellings such as "radus" (docs/style.md).
#pragma once

#include <nlohmann/json.hpp>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "steadylight/base/color.h"
#include "steadylight/base/transform.h"

namespace steadylight {

class JsonObject {
public:
    /// Throws InputError unless `json` is an object.
    JsonObject(const nlohmann::json& json, std::string file, std::string pointer);

    bool has(const std::string& key) const;
    /// True when `key` is present and holds an array.
    bool is_array(const std::string& key) const;
    const std::string& pointer() const { return m_pointer; }
    const std::string& file() const { return m_file; }

    float number(const std::string& key) const;
    float number(const std::string& key, float fallback) const;
    int integer(const std::string& key, int fallback) const;
    bool boolean(const std::string& key, bool fallback) const;
    std::string string(const std::string& key) const;
    std::string string(const std::string& key, const std::string& fallback) const;
    Vec3 vec3(const std::string& key) const;
    Vec3 vec3(const std::string& key, Vec3 fallback) const;
    Rgb rgb(const std::string& key, Rgb fallback) const;
    /// A list of colours, each [r, g, b] or one number for grey, such as keyframe values.
    std::vector<Rgb> rgbs(const std::string& key) const;
    std::vector<float> numbers(const std::string& key) const;
    /// A list of fixed-size numeric tuples, such as keyframe values.
    std::vector<std::vector<float>> tuples(const std::string& key, size_t size) const;

    JsonObject object(const std::string& key) const;
    std::vector<JsonObject> objects(const std::string& key) const;
    /// The members of an object-valued key, in key order: each must be an object.
    std::vector<std::pair<std::string, JsonObject>> members(const std::string& key) const;
    /// The keys of this object, in key order, whatever their values.
    std::vector<std::string> keys() const;

    /// Throws InputError for `key` (or for this object when `key` is empty).
    [[noreturn]] void fail(const std::string& key, const std::string& message) const;
    /// Logs a warning for each key of this object that was never read.
    void warn_unread() const;

private:
    const nlohmann::json& at(const std::string& key) const;
    std::vector<float> fixed_numbers(const nlohmann::json& value, const std::string& where, size_t size) const;
    Rgb rgb_value(const nlohmann::json& value, const std::string& where) const;
    std::string path(const std::string& key) const;

    const nlohmann::json& m_json;
    std::string m_file;
    std::string m_pointer;
    mutable std::set<std::string> m_read;
};

/// Parses a JSON file; syntax errors become InputError with the line and column.
nlohmann::json parse_json_file(const std::string& path);

}  // namespace steadylight
