// Small pieces of HTML for `steadylight report`: escaping text, and images embedded as base64
// data URIs so that the page needs no other file and no network.
#pragma once

#include <string>
#include <vector>

namespace steadylight {

/// `text` with &, <, >, " and ' replaced by entities, safe in element content and attributes.
std::string escape_html(const std::string& text);

/// RFC 4648 base64 with padding.
std::string encode_base64(const std::vector<unsigned char>& bytes);

/// `data:image/png;base64,...` for PNG file bytes.
std::string png_data_uri(const std::vector<unsigned char>& png);

/// The bytes of a file; throws InputError naming it when it cannot be read.
std::vector<unsigned char> read_file_bytes(const std::string& path);

}  // namespace steadylight
