#include "steadylight/report/html.h"

#include <algorithm>
#include <fstream>
#include <iterator>

#include "steadylight/base/error.h"

namespace steadylight {

std::string escape_html(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&#39;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

std::string encode_base64(const std::vector<unsigned char>& bytes) {
    static constexpr char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    // Each group of 3 bytes becomes 4 characters of 6 bits; a short last group is padded with '='.
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const size_t n = std::min<size_t>(3, bytes.size() - i);
        unsigned group = unsigned(bytes[i]) << 16;
        if (n > 1) group |= unsigned(bytes[i + 1]) << 8;
        if (n > 2) group |= unsigned(bytes[i + 2]);
        for (size_t k = 0; k < 4; ++k) out += k <= n ? alphabet[(group >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

std::string png_data_uri(const std::vector<unsigned char>& png) {
    return "data:image/png;base64," + encode_base64(png);
}

std::vector<unsigned char> read_file_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, "cannot open");
    std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) throw InputError(path, "cannot read");
    return bytes;
}

}  // namespace steadylight
