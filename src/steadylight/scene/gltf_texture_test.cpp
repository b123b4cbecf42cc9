// glTF textures (docs/materials.md, "Textures"): PNG and JPEG images, external and embedded, decoded
// by stb_image; samplers, KHR_texture_transform, TEXCOORD_0/1, COLOR_0, generated tangents,
// alpha modes and KHR_materials_specular, read from a hand-written .gltf; the image size limit.
#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "steadylight/base/error.h"
#include "steadylight/scene/gltf_loader.h"
#include "steadylight/scene/image_decoding.h"
#include "support/input_error.h"

namespace steadylight {
namespace {

namespace fs = std::filesystem;

std::string base64(const std::string& bytes) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t n = uint32_t(uint8_t(bytes[i])) << 16 |
                           (i + 1 < bytes.size() ? uint32_t(uint8_t(bytes[i + 1])) << 8 : 0) |
                           (i + 2 < bytes.size() ? uint32_t(uint8_t(bytes[i + 2])) : 0);
        out += table[n >> 18 & 63];
        out += table[n >> 12 & 63];
        out += i + 1 < bytes.size() ? table[n >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? table[n & 63] : '=';
    }
    return out;
}

std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

/// One triangle with POSITION, TEXCOORD_0, TEXCOORD_1 and COLOR_0 in one base64 buffer.
std::string triangle_buffer() {
    const float data[] = {0,    0,    0,     1,    0,    0,     0, 1,    0,       // POSITION
                          0,    0,    1,     0,    0,    1,                       // TEXCOORD_0
                          0.5f, 0.5f, 0.5f,  0.5f, 0.5f, 0.5f,                    // TEXCOORD_1
                          1,    0.5f, 0.25f, 1,    0.5f, 0.25f, 1, 0.5f, 0.25f};  // COLOR_0 (VEC3)
    return base64(std::string(reinterpret_cast<const char*>(data), sizeof data));
}

class GltfTexture : public ::testing::Test {
protected:
    void SetUp() override {
        m_dir = fs::temp_directory_path() / ("steadylight_gltf_texture_" + std::to_string(::getpid()));
        fs::create_directories(m_dir);
        // A 2 x 1 PNG: sRGB 128 grey (alpha 255), then white with alpha 0; and a grey JPEG.
        const unsigned char png[] = {128, 128, 128, 255, 255, 255, 255, 0};
        ASSERT_TRUE(stbi_write_png((m_dir / "tex.png").c_str(), 2, 1, 4, png, 8));
        unsigned char jpg[8 * 8 * 3];
        std::fill(std::begin(jpg), std::end(jpg), 200);
        ASSERT_TRUE(stbi_write_jpg((m_dir / "tex.jpg").c_str(), 8, 8, 3, jpg, 95));
    }
    void TearDown() override { fs::remove_all(m_dir); }

    SceneDesc load(const std::string& images) {
        const std::string gltf = R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_texture_transform", "KHR_materials_specular"],
  "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "buffers": [{"byteLength": 120, "uri": "data:application/octet-stream;base64,)" +
                                 triangle_buffer() + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24},
                  {"buffer": 0, "byteOffset": 60, "byteLength": 24}, {"buffer": 0, "byteOffset": 84, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]},
                {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"},
                {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"},
                {"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC3"}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1, "TEXCOORD_1": 2, "COLOR_0": 3}, "material": 0}]}],
  "materials": [{"name": "Textured",
    "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform":
        {"offset": [0.5, 0.25], "rotation": 0.5, "scale": [2, 3], "texCoord": 1}}},
      "metallicFactor": 0.25, "roughnessFactor": 0.75, "metallicRoughnessTexture": {"index": 1}},
    "normalTexture": {"index": 1, "scale": 0.5},
    "emissiveTexture": {"index": 1}, "emissiveFactor": [1, 1, 1],
    "alphaMode": "MASK", "alphaCutoff": 0.3,
    "extensions": {"KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [0.2, 0.8, 0.4]}}}],
  "samplers": [{"wrapS": 33071, "wrapT": 33648, "magFilter": 9728}],
  "textures": [{"source": 0, "sampler": 0}, {"source": 1}],
  "images": [)" + images + R"(]
})";
        const fs::path path = m_dir / "scene.gltf";
        std::ofstream(path) << gltf;
        SceneDesc desc;
        bool has_camera = false;
        append_gltf(path.string(), desc, has_camera);
        return desc;
    }

    fs::path m_dir;
};

TEST_F(GltfTexture, ExternalPngAndJpegAreDecodedToRgba) {
    const SceneDesc desc = load(R"({"uri": "tex.png"}, {"uri": "tex.jpg"})");
    ASSERT_EQ(desc.images.size(), 2u);
    EXPECT_EQ(desc.images[0].width, 2);
    EXPECT_EQ(desc.images[0].rgba, (std::vector<uint8_t>{128, 128, 128, 255, 255, 255, 255, 0}));
    EXPECT_EQ(desc.images[1].width, 8);
    EXPECT_NEAR(desc.images[1].rgba[0], 200, 2);  // JPEG is lossy
    EXPECT_EQ(desc.images[1].rgba[3], 255);       // opaque alpha added
}

TEST_F(GltfTexture, PercentEncodedImageUriIsFound) {
    fs::copy_file(m_dir / "tex.png", m_dir / "my tex.png");
    const SceneDesc desc = load(R"({"uri": "my%20tex.png"}, {"uri": "tex.jpg"})");
    EXPECT_EQ(desc.images.at(0).width, 2);
}

TEST_F(GltfTexture, EmbeddedDataUriPngGivesTheSamePixels) {
    const SceneDesc desc =
        load(R"({"uri": "data:image/png;base64,)" + base64(read_file(m_dir / "tex.png")) + R"("}, {"uri": "tex.jpg"})");
    ASSERT_EQ(desc.images.size(), 2u);
    EXPECT_EQ(desc.images[0].rgba, (std::vector<uint8_t>{128, 128, 128, 255, 255, 255, 255, 0}));
}

TEST_F(GltfTexture, MaterialReadsSamplersTransformsAndFactors) {
    const SceneDesc desc = load(R"({"uri": "tex.png"}, {"uri": "tex.jpg"})");
    const MaterialDesc& m = desc.materials.at(0);
    EXPECT_EQ(m.type, MaterialType::pbr);
    EXPECT_EQ(m.metallic, 0.25f);
    EXPECT_EQ(m.roughness, 0.75f);
    EXPECT_EQ(m.alpha_mode, AlphaMode::mask);
    EXPECT_NEAR(m.alpha_cutoff, 0.3f, 1e-6f);
    EXPECT_NEAR(m.specular, 0.5f, 1e-6f);
    EXPECT_NEAR(m.specular_color, 0.8f, 1e-6f);
    const TextureRef& base = m.base_color_texture;
    EXPECT_EQ(base.image, 0);
    EXPECT_EQ(base.texcoord, 1);  // KHR_texture_transform's texCoord overrides
    EXPECT_EQ(base.wrap_s, TextureWrap::clamp_to_edge);
    EXPECT_EQ(base.wrap_t, TextureWrap::mirrored_repeat);
    EXPECT_EQ(base.filter, TextureFilter::nearest);
    EXPECT_NEAR(base.offset.x, 0.5f, 1e-6f);
    EXPECT_NEAR(base.scale.y, 3, 1e-6f);
    EXPECT_NEAR(base.rotation, 0.5f, 1e-6f);
    EXPECT_EQ(m.metallic_roughness_texture.image, 1);
    EXPECT_EQ(m.metallic_roughness_texture.wrap_s, TextureWrap::repeat);  // no sampler: glTF's defaults
    EXPECT_EQ(m.normal_texture.image, 1);
    EXPECT_NEAR(m.normal_scale, 0.5f, 1e-6f);
    EXPECT_EQ(m.emissive_texture.image, 1);
}

TEST_F(GltfTexture, MeshReadsTexcoordsColoursAndGeneratesTangents) {
    const SceneDesc desc = load(R"({"uri": "tex.png"}, {"uri": "tex.jpg"})");
    const auto& mesh = std::get<TriangleMesh>(desc.objects.at(0).geometry);
    ASSERT_EQ(mesh.uv0.size(), 3u);
    EXPECT_EQ(mesh.uv0[1].x, 1.0f);
    EXPECT_EQ(mesh.uv1[2].y, 0.5f);
    ASSERT_EQ(mesh.colors.size(), 3u);
    EXPECT_EQ(mesh.colors[0][1], 0.5f);
    EXPECT_EQ(mesh.colors[0][3], 1.0f);  // VEC3 colours are opaque
    // The normal map asks for tangents; u runs along +x here.
    ASSERT_EQ(mesh.tangents.size(), 3u);
    EXPECT_NEAR(mesh.tangents[0][0], 1, 1e-6f);
    EXPECT_NEAR(mesh.tangents[0][3], 1, 1e-6f);
}

TEST_F(GltfTexture, UndecodableImageLeavesItsTexturesOut) {
    const SceneDesc desc =
        load(R"({"uri": "data:image/png;base64,)" + base64("not a png at all") + R"("}, {"uri": "tex.jpg"})");
    ASSERT_EQ(desc.images.size(), 2u);  // the indices of the others stay as they were
    EXPECT_FALSE(desc.materials.at(0).base_color_texture.is_set());
    EXPECT_EQ(desc.materials.at(0).normal_texture.image, 1);
}

// A chunk whose length runs past the end of the file (a truncated PNG) is refused before
// stb_image allocates that length (a fuzzing finding: 1.4 GB for a 152-byte file).
TEST(ImageDecoding, PngChunkRunningPastTheEndIsADamagedImage) {
    std::vector<unsigned char> bytes;
    const std::vector<unsigned char> black(16 * 16 * 3, 0);
    const auto append = [](void* to, void* data, int size) {
        auto* out = static_cast<std::vector<unsigned char>*>(to);
        out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
    };
    ASSERT_TRUE(stbi_write_png_to_func(append, &bytes, 16, 16, 3, black.data(), 16 * 3));
    EXPECT_TRUE(decode_image(bytes.data(), bytes.size()).problem.empty());
    const std::vector<unsigned char> whole = bytes;
    bytes.resize(bytes.size() - 20);  // into the IDAT chunk
    EXPECT_EQ(decode_image(bytes.data(), bytes.size()).problem,
              "a damaged PNG image (its IDAT chunk runs past the end of the file)");
    // Only the length and type of a chunk after the header, which claims 2 GB.
    bytes.assign(whole.begin(), whole.begin() + 33);
    bytes.insert(bytes.end(), {0x7f, 0xff, 0xff, 0xff, 'I', 'D', 'A', 'T'});
    EXPECT_EQ(decode_image(bytes.data(), bytes.size()).problem,
              "a damaged PNG image (its IDAT chunk runs past the end of the file)");
}

TEST_F(GltfTexture, ImageTooLargeToDecodeIsAnInputErrorNamingIt) {
    // Its size is read from the header before any texel is decoded.
    const std::vector<unsigned char> row(size_t(max_image_side + 1) * 4, 255);
    ASSERT_TRUE(stbi_write_png((m_dir / "wide.png").c_str(), max_image_side + 1, 1, 4, row.data(), 0));
    const std::string error = testing::input_error_of([&] { load(R"({"uri": "wide.png"}, {"uri": "tex.jpg"})"); });
    EXPECT_NE(error.find("image 0 \"wide.png\": too large (16385 x 1 texels"), std::string::npos) << error;
}

TEST_F(GltfTexture, MissingExternalImageIsAnInputError) {
    EXPECT_THROW(load(R"({"uri": "missing.png"}, {"uri": "tex.jpg"})"), InputError);
}

}  // namespace
}  // namespace steadylight
