// core/scene/gltf_adapter.cpp: glTF 2.0 (.gltf, .glb) to and from cg_scene through tinygltf.
//
// The only C++ in core: tinygltf parses the JSON and fetches buffers and images; everything
// it hands back is re-checked here (indices of every reference, every accessor against its
// bufferView and buffer, every vertex index against the vertex count) because malformed
// files must give a named error, never a crash. tinygltf is a shared library (Debian's
// libtinygltf): TINYGLTF_IMPLEMENTATION is not defined here.
#include <jansson.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <sys/stat.h>

extern "C" {
#include "cg/error.h"
#include "cg/fs.h"
#include "cg/log.h"
#include "cg/scene.h"
}
#include "scene_internal.h"

namespace {

// What extensionsRequired may name (gltf_check.c keeps the same list).
const char *const supported_extensions[] = { "KHR_lights_punctual",        "KHR_materials_emissive_strength",
                                             "KHR_materials_ior",          "KHR_materials_specular",
                                             "KHR_materials_transmission", "KHR_materials_volume",
                                             "KHR_texture_transform" };

// ------------------------------------------------------------------ loading

struct loader {
    std::string path;       // as given, for messages
    cg_progress *progress = nullptr; // cg_scene_load's, or NULL
    size_t meshes_built = 0;         // glTF meshes converted so far, for the progress
    tinygltf::Model model;
    cg_scene *scene;
    cg_error *err;
    // glTF mesh -> its cg meshes (one per triangle primitive), filled on first use.
    std::vector<std::vector<int>> mesh_map;
    std::vector<bool> mesh_done;
    // glTF texture -> its cg texture read as sRGB (base colour, emissive) and as linear data
    // (the others), or -1.
    std::vector<int> texture_srgb, texture_linear;
    // Material features the file asks for and conegraph leaves out, for the one notice at
    // load (report_left_out): feature and fallback, and the materials that ask for it.
    struct left_out_item {
        std::string feature, fallback;
        std::vector<std::string> materials;
    };
    std::vector<left_out_item> left_out;
    // glTF material i is cg material i + material_base: 1, after the loader's own material 0
    // (glTF's default material), or 0 when the file's material 0 is a conegraph export's
    // material 0 (extras "conegraph_material_0": true, export_materials).
    int material_base = 1;
    std::vector<int> explicit_kind;       // per cg mesh: -1 none, else a cg_mesh_kind
    std::map<int, std::string> image_problem; // image -> why its data cannot be used
    // The node hierarchy animation needs (visit_nodes): per glTF node, its parent, whether a
    // channel animates it, whether it is an ancestor of an animated node, and its cg node
    // (-1: flattened).
    std::vector<int> parent;
    std::vector<bool> animated, animated_below;
    std::vector<int> node_map;
    // The channels read (read_animations), on glTF nodes until visit_nodes maps them.
    struct pending_animation {
        std::string name;
        std::vector<cg_anim_channel> channels;
        std::vector<int> nodes;
    };
    std::vector<pending_animation> animations;
    // Skins (mark_joints, visit_nodes, finish_skins): per glTF node, whether it is a joint (kept
    // as a cg node, like an animated one) and whether the animation moves it; per cg mesh, its
    // glTF mesh and primitive and who uses it (0 nobody, 1 instances as it is, 2 a skin, which
    // owns it: any other user gets a copy); the skinned instances waiting for their skin.
    std::vector<bool> joint, moves;
    std::vector<int> gltf_mesh_of, prim_of;
    std::vector<char> mesh_use;
    struct skin_use {
        int skin, node, mesh, instance;
        float world[16]; // the node's, kept should the skin be unusable
    };
    std::vector<skin_use> skin_uses;
    std::vector<int> skin_map; // glTF skin -> cg skin, -1 not yet made
    int weight_channels = 0;   // animation channels on morph target weights not read
    // Morph targets (visit_nodes, finish_morphs): the instances waiting for their targets, the
    // glTF nodes whose weights a channel animates, the meshes whose targets are not read.
    struct morph_use {
        int node, mesh, instance;
    };
    std::vector<morph_use> morph_uses;
    std::vector<bool> weights_animated;
    std::vector<std::string> morph_left_out;
    ~loader()
    {
        for (auto &a : animations)
            for (auto &c : a.channels) {
                std::free(c.times);
                std::free(c.values);
            }
    }
};

void note(loader &L, const std::string &feature, const std::string &material, const std::string &fallback);
double number_or(const tinygltf::Value &o, const char *name, double fallback);

std::string
one_line(std::string s)
{
    while (!s.empty() && (s.back() == '\n' || s.back() == ' '))
        s.pop_back();
    for (char &c : s)
        if (c == '\n')
            c = ';';
    return s;
}

std::string
mesh_label(const loader &L, int m)
{
    const std::string &name = L.model.meshes[(size_t)m].name;
    return name.empty() ? "mesh " + std::to_string(m) : "mesh '" + name + "'";
}

bool
fail(loader &L, cg_status status, const std::string &what)
{
    return cg_fail(L.err, status, "%s: %s", L.path.c_str(), what.c_str());
}

// tinygltf refuses some files itself; name the class of problem from its message.
cg_status
classify_tinygltf_error(const std::string &e)
{
    if (e.find("ccessor") != std::string::npos)
        return CG_ERR_GLTF_ACCESSOR;
    const char *buffer_words[] = { "uffer", "File not found", "File size mismatch", "File is empty",
                                   "File read error", "BIN", "binary size", "Failed to decode 'uri'" };
    for (const char *w : buffer_words)
        if (e.find(w) != std::string::npos)
            return CG_ERR_GLTF_BUFFER;
    return CG_ERR_GLTF_PARSE;
}

// What an image's bytes are: PNG and JPEG are the formats glTF 2.0 allows without an
// extension (tinygltf's stb_image would also take BMP, GIF, ...). Empty when acceptable.
std::string
image_format_problem(const tinygltf::Image &image, const unsigned char *bytes, size_t size)
{
    bool png = size >= 8 && std::memcmp(bytes, "\x89PNG\r\n\x1a\n", 8) == 0;
    bool jpeg = size >= 3 && std::memcmp(bytes, "\xFF\xD8\xFF", 3) == 0;
    if (!png && !jpeg)
        return "is neither PNG nor JPEG";
    const std::string &mime = image.mimeType;
    if ((png && mime == "image/jpeg") || (jpeg && mime == "image/png"))
        return std::string("is ") + (png ? "PNG" : "JPEG") + " but its mimeType says " + mime;
    return std::string();
}

// Images in a bufferView are decoded after loading, once the bufferView is known to lie in
// its buffer (tinygltf would hand the decoder an unchecked pointer). Images from a URI
// arrive with their bytes and are decoded at once by tinygltf's own stb_image loader; what
// goes wrong is kept for convert_textures, which refuses an image a texture uses.
bool
deferred_image_loader(tinygltf::Image *image, const int index, std::string *err, std::string *warn,
                      int req_width, int req_height, const unsigned char *bytes, int size, void *user)
{
    if (image->bufferView >= 0)
        return true;
    loader *L = (loader *)user;
    std::string problem = image_format_problem(*image, bytes, size > 0 ? (size_t)size : 0);
    if (problem.empty() &&
        !tinygltf::LoadImageData(image, index, err, warn, req_width, req_height, bytes, size, nullptr))
        problem = "cannot be decoded";
    if (!problem.empty()) {
        L->image_problem[index] = problem;
        image->image.clear();
    }
    return true;
}

// Buffers and images a file names by URI are read only from regular files of at most 4 GiB
// (the loader's limit for the file itself): a URI naming a device, a FIFO or /proc would
// otherwise block the loader or have it allocate whatever size the kernel reports.
bool
read_regular_file(std::vector<unsigned char> *out, std::string *err, const std::string &path, void *user)
{
    struct stat st;
    if (stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_size > (off_t)0xFFFFFFFFu) {
        if (err)
            *err += "File not found or not a regular file of at most 4 GiB: " + path + "\n";
        return false;
    }
    return tinygltf::ReadWholeFile(out, err, path, user);
}

size_t
component_size(int component_type)
{
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

int
component_count(int type)
{
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
    }
}

const char *
type_name(int type)
{
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown";
    }
}

const char *
component_type_name(int component_type)
{
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT: return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    default: return "unknown";
    }
}

// A checked view of an accessor's elements: every byte it will read lies in its buffer.
struct accessor_view {
    const unsigned char *base = nullptr; // nullptr: no bufferView, all elements are zero
    size_t stride = 0, count = 0;
    std::vector<unsigned char> dense;    // a sparse accessor's elements, substituted
    int component_type = 0, components = 0;
    bool normalized = false;

    double component(size_t i, int c) const
    {
        if (!base)
            return 0;
        const unsigned char *p = base + i * stride + (size_t)c * component_size(component_type);
        switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            int8_t v; std::memcpy(&v, p, 1);
            return normalized ? std::fmax(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            uint8_t v; std::memcpy(&v, p, 1);
            return normalized ? v / 255.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t v; std::memcpy(&v, p, 2);
            return normalized ? std::fmax(v / 32767.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v; std::memcpy(&v, p, 2);
            return normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            uint32_t v; std::memcpy(&v, p, 4);
            return v;
        }
        case TINYGLTF_COMPONENT_TYPE_INT: {
            int32_t v; std::memcpy(&v, p, 4);
            return v;
        }
        default: {
            float v; std::memcpy(&v, p, 4);
            return v;
        }
        }
    }

    // The stored value, integers not normalized (what accessor.min and max describe).
    double raw(size_t i, int c) const
    {
        if (!base || component_type == TINYGLTF_COMPONENT_TYPE_FLOAT)
            return component(i, c);
        accessor_view plain = *this;
        plain.normalized = false;
        return plain.component(i, c);
    }

    uint32_t index(size_t i) const
    {
        if (!base)
            return 0;
        const unsigned char *p = base + i * stride;
        if (component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE)
            return *p;
        if (component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
            uint16_t v; std::memcpy(&v, p, 2);
            return v;
        }
        uint32_t v; std::memcpy(&v, p, 4);
        return v;
    }
};

// The bytes of `count` elements of `elem` bytes from `offset` in bufferView `view`, each
// checked to lie inside the view and the view inside its buffer.
bool
checked_view(loader &L, const std::string &label, int view, size_t offset, size_t count, size_t elem,
             const unsigned char **data, size_t *stride_out)
{
    const tinygltf::Model &M = L.model;
    if (view < 0 || (size_t)view >= M.bufferViews.size())
        return fail(L, CG_ERR_GLTF_BUFFER, label + ": bufferView " + std::to_string(view) + " does not exist");
    const tinygltf::BufferView &bv = M.bufferViews[(size_t)view];
    if (bv.buffer < 0 || (size_t)bv.buffer >= M.buffers.size())
        return fail(L, CG_ERR_GLTF_BUFFER,
                    label + ": bufferView " + std::to_string(view) + " refers to buffer " +
                        std::to_string(bv.buffer) + ", which does not exist");
    const tinygltf::Buffer &buf = M.buffers[(size_t)bv.buffer];
    size_t stride = stride_out && bv.byteStride ? bv.byteStride : elem;
    if (stride < elem)
        return fail(L, CG_ERR_GLTF_ACCESSOR,
                    label + ": byteStride " + std::to_string(stride) + " is shorter than an element (" +
                        std::to_string(elem) + " bytes)");
    // 64-bit sums of values each below 2^40 cannot wrap.
    uint64_t view_end = (uint64_t)bv.byteOffset + bv.byteLength;
    if (bv.byteOffset > (1ull << 40) || bv.byteLength > (1ull << 40) || view_end > buf.data.size())
        return fail(L, CG_ERR_GLTF_BUFFER,
                    label + ": bufferView " + std::to_string(view) + " (bytes " +
                        std::to_string(bv.byteOffset) + ".." + std::to_string(view_end) +
                        ") runs past the end of buffer " + std::to_string(bv.buffer) + " (" +
                        std::to_string(buf.data.size()) + " bytes)");
    if (count > (1ull << 32) || offset > (1ull << 40) ||
        (uint64_t)offset + (uint64_t)stride * (count - 1) + elem > bv.byteLength)
        return fail(L, CG_ERR_GLTF_BUFFER,
                    label + ": " + std::to_string(count) + " elements from byte " + std::to_string(offset) +
                        " need more than the " + std::to_string(bv.byteLength) + " bytes of bufferView " +
                        std::to_string(view));
    *data = buf.data.data() + bv.byteOffset + offset;
    if (stride_out)
        *stride_out = stride;
    return true;
}

// glTF 3.6.2.3: a sparse accessor is its base (bufferView or zeros) with `sparse.count`
// elements replaced, at strictly increasing indices, by the values.
bool
apply_sparse(loader &L, const std::string &label, const tinygltf::Accessor &a, size_t elem, accessor_view *out)
{
    const auto &sp = a.sparse;
    std::string what = label + " sparse";
    if (sp.count <= 0 || (size_t)sp.count > a.count)
        return fail(L, CG_ERR_GLTF_ACCESSOR,
                    what + ": count " + std::to_string(sp.count) + " outside 1.." + std::to_string(a.count));
    size_t isize = component_size(sp.indices.componentType);
    if (sp.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        sp.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        sp.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        return fail(L, CG_ERR_GLTF_ACCESSOR,
                    what + ": indices are " + component_type_name(sp.indices.componentType) +
                        "; expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0)
        return fail(L, CG_ERR_GLTF_BUFFER, what + ": negative byteOffset");
    const unsigned char *indices, *values;
    if (!checked_view(L, what + " indices", sp.indices.bufferView, (size_t)sp.indices.byteOffset,
                      (size_t)sp.count, isize, &indices, nullptr) ||
        !checked_view(L, what + " values", sp.values.bufferView, (size_t)sp.values.byteOffset,
                      (size_t)sp.count, elem, &values, nullptr))
        return false;
    out->dense.assign(a.count * elem, 0);
    if (out->base)
        for (size_t i = 0; i < a.count; i++)
            std::memcpy(out->dense.data() + i * elem, out->base + i * out->stride, elem);
    uint64_t previous = 0;
    for (size_t k = 0; k < (size_t)sp.count; k++) {
        uint64_t index = 0;
        std::memcpy(&index, indices + k * isize, isize); // little-endian, like glTF
        if (index >= a.count || (k > 0 && index <= previous))
            return fail(L, CG_ERR_GLTF_INDEX_RANGE,
                        what + ": index " + std::to_string(index) + " at position " + std::to_string(k) +
                            (index >= a.count ? " out of range (" + std::to_string(a.count) + " elements)"
                                              : " not above the previous one"));
        std::memcpy(out->dense.data() + index * elem, values + k * elem, elem);
        previous = index;
    }
    out->base = out->dense.data();
    out->stride = elem;
    return true;
}

// `what` names the use ("mesh 'roof' primitive 0 POSITION"); `types` and `component_types`
// are the accepted ones.
bool
view_accessor(loader &L, int index, const std::string &what, std::initializer_list<int> types,
              std::initializer_list<int> component_types, accessor_view *out)
{
    const tinygltf::Model &M = L.model;
    if (index < 0 || (size_t)index >= M.accessors.size())
        return fail(L, CG_ERR_GLTF_ACCESSOR,
                    what + ": accessor " + std::to_string(index) + " does not exist (" +
                        std::to_string(M.accessors.size()) + " accessors)");
    const tinygltf::Accessor &a = M.accessors[(size_t)index];
    std::string label = what + ": accessor " + std::to_string(index);
    bool type_ok = false, ctype_ok = false;
    for (int t : types)
        type_ok = type_ok || a.type == t;
    for (int t : component_types)
        ctype_ok = ctype_ok || a.componentType == t;
    if (!type_ok || !ctype_ok) {
        std::string expected, expected_components;
        for (int t : types)
            expected += std::string(expected.empty() ? "" : " or ") + type_name(t);
        for (int t : component_types)
            expected_components += std::string(expected_components.empty() ? "" : " or ") + component_type_name(t);
        return fail(L, CG_ERR_GLTF_ACCESSOR,
                    label + " is " + type_name(a.type) + " of " + component_type_name(a.componentType) +
                        "; expected " + expected + " of " + expected_components);
    }
    if (a.count == 0)
        return fail(L, CG_ERR_GLTF_ACCESSOR, label + " has count 0");
    out->count = a.count;
    out->component_type = a.componentType;
    out->components = component_count(a.type);
    out->normalized = a.normalized;
    size_t elem = component_size(a.componentType) * (size_t)out->components;
    if (a.bufferView < 0) {
        // glTF 3.6.2.1: no bufferView means zeros. Nothing bounds the count then, so a
        // huge one is refused rather than allocated.
        if (a.count > (1u << 24))
            return fail(L, CG_ERR_GLTF_ACCESSOR,
                        label + " has no bufferView and count " + std::to_string(a.count) +
                            " (more than 16777216 implicit zero elements are refused)");
        out->base = nullptr;
        out->stride = elem;
    } else {
        const unsigned char *data;
        size_t stride = 0;
        if (!checked_view(L, label, a.bufferView, a.byteOffset, a.count, elem, &data, &stride))
            return false;
        out->base = data;
        out->stride = stride;
    }
    return !a.sparse.isSparse || apply_sparse(L, label, a, elem, out);
}

// glTF-Validator's data checks on an accessor conegraph reads (ACCESSOR_INVALID_FLOAT,
// ACCESSOR_MIN_MISMATCH, ACCESSOR_MAX_MISMATCH): no NaN or infinity, and declared min and
// max equal to the elements' smallest and largest (compared as single-precision floats for
// FLOAT, as the stored integers otherwise). `element` names an element ("vertex").
bool
check_accessor_data(loader &L, const std::string &what, int index, const char *element, const accessor_view &v)
{
    const tinygltf::Accessor &a = L.model.accessors[(size_t)index];
    int n = v.components;
    std::vector<double> lo((size_t)n, INFINITY), hi((size_t)n, -INFINITY);
    for (size_t i = 0; i < v.count; i++)
        for (int c = 0; c < n; c++) {
            double x = v.raw(i, c);
            if (!std::isfinite(x))
                return fail(L, CG_ERR_GLTF_NONFINITE,
                            what + ": " + element + " " + std::to_string(i) + " component " + std::to_string(c) +
                                " is NaN or infinite (accessor " + std::to_string(index) + ")");
            lo[(size_t)c] = std::fmin(lo[(size_t)c], x);
            hi[(size_t)c] = std::fmax(hi[(size_t)c], x);
        }
    const std::pair<const char *, const std::vector<double> *> bounds[] = { { "min", &a.minValues },
                                                                            { "max", &a.maxValues } };
    for (const auto &b : bounds) {
        if (b.second->size() != (size_t)n)
            continue; // absent (the JSON check made sure a present one has n values)
        const std::vector<double> &actual = b.first[1] == 'i' ? lo : hi;
        for (int c = 0; c < n; c++) {
            double declared = (*b.second)[(size_t)c];
            if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
                declared = (double)(float)declared;
            if (declared != actual[(size_t)c]) {
                char msg[256];
                std::snprintf(msg, sizeof msg, ": accessors[%d].%s[%d] is %.9g, but the %s element's is %.9g", index,
                              b.first, c, declared, b.first[1] == 'i' ? "smallest" : "largest", actual[(size_t)c]);
                return fail(L, CG_ERR_GLTF_ACCESSOR, what + msg);
            }
        }
    }
    return true;
}

// Triangle list from a primitive's (possibly implicit) index sequence and mode.
bool
triangulate(loader &L, const std::string &what, int mode, const std::vector<uint32_t> &seq,
            std::vector<uint32_t> *tris)
{
    size_t n = seq.size();
    tris->clear();
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (n % 3 != 0)
            return fail(L, CG_ERR_GLTF_ACCESSOR,
                        what + ": " + std::to_string(n) + " indices is not a multiple of 3");
        *tris = seq;
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        // glTF 3.7.2.1: triangle i = (v_i, v_{i+1+i%2}, v_{i+2-i%2}), one winding throughout.
        for (size_t i = 0; i + 2 < n; i++) {
            tris->push_back(seq[i]);
            tris->push_back(seq[i + 1 + i % 2]);
            tris->push_back(seq[i + 2 - i % 2]);
        }
    } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        // glTF 3.7.2.1: triangle i = (v_{i+1}, v_{i+2}, v_0).
        for (size_t i = 0; i + 2 < n; i++) {
            tris->push_back(seq[i + 1]);
            tris->push_back(seq[i + 2]);
            tris->push_back(seq[0]);
        }
    } else {
        return fail(L, CG_ERR_GLTF_PARSE, what + ": unknown primitive mode " + std::to_string(mode));
    }
    return true;
}

bool
add_primitive(loader &L, int mesh_index, int prim_index, std::vector<int> *out)
{
    const tinygltf::Mesh &mesh = L.model.meshes[(size_t)mesh_index];
    const tinygltf::Primitive &prim = mesh.primitives[(size_t)prim_index];
    std::string what = mesh_label(L, mesh_index) + " primitive " + std::to_string(prim_index);
    if (prim.mode == TINYGLTF_MODE_POINTS || prim.mode == TINYGLTF_MODE_LINE ||
        prim.mode == TINYGLTF_MODE_LINE_LOOP || prim.mode == TINYGLTF_MODE_LINE_STRIP) {
        cg_log_warn("%s: %s: points or lines skipped (conegraph renders triangles)", L.path.c_str(),
                    what.c_str());
        return true;
    }
    auto pos_it = prim.attributes.find("POSITION");
    if (pos_it == prim.attributes.end())
        return fail(L, CG_ERR_GLTF_ACCESSOR, what + ": no POSITION attribute");
    accessor_view pos, nrm, uv, idx;
    if (!view_accessor(L, pos_it->second, what + " POSITION", { TINYGLTF_TYPE_VEC3 },
                       { TINYGLTF_COMPONENT_TYPE_FLOAT }, &pos) ||
        !check_accessor_data(L, what + " POSITION", pos_it->second, "vertex", pos))
        return false;
    size_t nv = pos.count;
    auto nrm_it = prim.attributes.find("NORMAL");
    bool has_normals = nrm_it != prim.attributes.end();
    if (has_normals && (!view_accessor(L, nrm_it->second, what + " NORMAL", { TINYGLTF_TYPE_VEC3 },
                                       { TINYGLTF_COMPONENT_TYPE_FLOAT }, &nrm) ||
                        !check_accessor_data(L, what + " NORMAL", nrm_it->second, "vertex", nrm)))
        return false;
    // glTF 2.0, 3.7.2.1: normals are unit vectors (to the validator's tolerance, 0.00674).
    for (size_t v = 0; has_normals && v < nrm.count; v++) {
        double x = nrm.component(v, 0), y = nrm.component(v, 1), z = nrm.component(v, 2);
        double len = std::sqrt(x * x + y * y + z * z);
        if (std::fabs(len - 1) > 0.00674)
            return fail(L, CG_ERR_GLTF_ACCESSOR,
                        what + " NORMAL: vertex " + std::to_string(v) + " has a normal of length " +
                            std::to_string(len) + ", not a unit vector (accessor " + std::to_string(nrm_it->second) +
                            ")");
    }
    auto uv_it = prim.attributes.find("TEXCOORD_0");
    bool has_uv = uv_it != prim.attributes.end();
    if (has_uv && (!view_accessor(L, uv_it->second, what + " TEXCOORD_0", { TINYGLTF_TYPE_VEC2 },
                                 { TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT },
                                 &uv) ||
                  !check_accessor_data(L, what + " TEXCOORD_0", uv_it->second, "vertex", uv)))
        return false;
    if (has_uv && uv.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT && !uv.normalized)
        return fail(L, CG_ERR_GLTF_ACCESSOR,
                    what + " TEXCOORD_0: integer texture coordinates must be normalized");
    // TANGENT (glTF 2.0, 3.7.2.1): xyz unit, w +-1. Ignored where the primitive has no
    // NORMAL (the spec says so: the normals are computed then, and tangents with them).
    auto tan_it = prim.attributes.find("TANGENT");
    bool has_tangents = tan_it != prim.attributes.end() && has_normals;
    accessor_view tan;
    if (has_tangents && (!view_accessor(L, tan_it->second, what + " TANGENT", { TINYGLTF_TYPE_VEC4 },
                                        { TINYGLTF_COMPONENT_TYPE_FLOAT }, &tan) ||
                         !check_accessor_data(L, what + " TANGENT", tan_it->second, "vertex", tan)))
        return false;
    for (size_t v = 0; has_tangents && v < tan.count; v++) {
        double x = tan.component(v, 0), y = tan.component(v, 1), z = tan.component(v, 2), w = tan.component(v, 3);
        double len = std::sqrt(x * x + y * y + z * z);
        if (std::fabs(len - 1) > 0.00674 || (w != 1 && w != -1))
            return fail(L, CG_ERR_GLTF_ACCESSOR,
                        what + " TANGENT: vertex " + std::to_string(v) + " has a tangent of length " +
                            std::to_string(len) + " and w " + std::to_string(w) +
                            ", not a unit vector with w = 1 or -1 (accessor " + std::to_string(tan_it->second) + ")");
    }
    if (has_tangents && tan.count != nv)
        return fail(L, CG_ERR_GLTF_ACCESSOR,
                    what + ": attribute counts differ (POSITION has " + std::to_string(nv) + ", TANGENT " +
                        std::to_string(tan.count) + ")");
    if (prim.attributes.count("COLOR_0") && prim.material >= 0 && (size_t)prim.material < L.model.materials.size())
        note(L, "COLOR_0 vertex colours of " + what,
             L.model.materials[(size_t)prim.material].name.empty()
                 ? "material " + std::to_string(prim.material)
                 : "material '" + L.model.materials[(size_t)prim.material].name + "'",
             "not multiplied into the base colour");
    else if (prim.attributes.count("COLOR_0"))
        note(L, "COLOR_0 vertex colours of " + what, "default material", "not multiplied into the base colour");
    if ((has_normals && nrm.count != nv) || (has_uv && uv.count != nv))
        return fail(L, CG_ERR_GLTF_ACCESSOR,
                    what + ": attribute counts differ (POSITION has " + std::to_string(nv) +
                        (has_normals ? ", NORMAL " + std::to_string(nrm.count) : std::string()) +
                        (has_uv ? ", TEXCOORD_0 " + std::to_string(uv.count) : std::string()) + ")");

    std::vector<uint32_t> seq;
    if (prim.indices >= 0) {
        if (!view_accessor(L, prim.indices, what + " indices", { TINYGLTF_TYPE_SCALAR },
                           { TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT },
                           &idx) ||
            !check_accessor_data(L, what + " indices", prim.indices, "index", idx))
            return false;
        uint32_t restart = idx.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 0xFFu
                           : idx.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 0xFFFFu
                                                                                           : 0xFFFFFFFFu;
        seq.resize(idx.count);
        for (size_t i = 0; i < idx.count; i++) {
            seq[i] = idx.index(i);
            if (seq[i] == restart)
                return fail(L, CG_ERR_GLTF_INDEX_RANGE,
                            what + ": index " + std::to_string(seq[i]) + " at position " + std::to_string(i) +
                                " is the primitive restart value, which glTF does not allow (accessor " +
                                std::to_string(prim.indices) + ")");
            if (seq[i] >= nv)
                return fail(L, CG_ERR_GLTF_INDEX_RANGE,
                            what + ": index " + std::to_string(seq[i]) + " out of range (accessor " +
                                std::to_string(pos_it->second) + " has " + std::to_string(nv) +
                                " vertices)");
        }
    } else {
        seq.resize(nv);
        for (size_t i = 0; i < nv; i++)
            seq[i] = (uint32_t)i;
    }
    std::vector<uint32_t> tris;
    if (!triangulate(L, what, prim.mode, seq, &tris))
        return false;
    if (tris.empty()) {
        cg_log_warn("%s: %s: no triangles, skipped", L.path.c_str(), what.c_str());
        return true;
    }

    cg_mesh m = {};
    std::string name = mesh.name.empty() ? "mesh" + std::to_string(mesh_index) : mesh.name;
    if (mesh.primitives.size() > 1)
        name += "." + std::to_string(prim_index);
    cg_copy_name(m.name, name.c_str());
    m.vertex_count = (uint32_t)nv;
    m.index_count = (uint32_t)tris.size();
    m.positions = (float *)std::malloc(nv * 3 * sizeof(float));
    m.normals = (float *)std::malloc(nv * 3 * sizeof(float));
    m.texcoords = has_uv ? (float *)std::malloc(nv * 2 * sizeof(float)) : nullptr;
    m.tangents = has_tangents ? (float *)std::malloc(nv * 4 * sizeof(float)) : nullptr;
    m.indices = (uint32_t *)std::malloc(tris.size() * sizeof(uint32_t));
    if (!m.positions || !m.normals || !m.indices || (has_uv && !m.texcoords) || (has_tangents && !m.tangents)) {
        std::free(m.positions), std::free(m.normals), std::free(m.texcoords), std::free(m.indices);
        std::free(m.tangents);
        return fail(L, CG_ERR_OUT_OF_MEMORY, what + ": out of memory");
    }
    std::memcpy(m.indices, tris.data(), tris.size() * sizeof(uint32_t));
    bool finite = true;
    size_t bad_vertex = 0;
    for (size_t v = 0; v < nv; v++)
        for (int k = 0; k < 3; k++) {
            double x = pos.component(v, k);
            if (!std::isfinite(x) && finite) {
                finite = false;
                bad_vertex = v;
            }
            m.positions[3 * v + k] = (float)x;
        }
    bool normals_ok = true;
    if (has_normals)
        for (size_t v = 0; v < nv; v++) {
            double n[3] = { nrm.component(v, 0), nrm.component(v, 1), nrm.component(v, 2) };
            double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (!std::isfinite(len))
                normals_ok = false;
            for (int k = 0; k < 3; k++)
                m.normals[3 * v + k] = len > 0 ? (float)(n[k] / len) : (k == 1 ? 1.0f : 0.0f);
        }
    if (has_uv)
        for (size_t v = 0; v < nv; v++)
            for (int k = 0; k < 2; k++)
                m.texcoords[2 * v + k] = (float)uv.component(v, k);
    if (has_tangents)
        for (size_t v = 0; v < nv; v++) {
            double t[3] = { tan.component(v, 0), tan.component(v, 1), tan.component(v, 2) };
            double len = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
            for (int k = 0; k < 3; k++)
                m.tangents[4 * v + k] = (float)(t[k] / len);
            m.tangents[4 * v + 3] = (float)tan.component(v, 3);
        }
    int material = prim.material < 0 ? 0 : prim.material + L.material_base;
    m.material = material;
    cg_error local = {};
    bool ok = true;
    if (!finite)
        ok = fail(L, CG_ERR_GLTF_NONFINITE,
                  what + ": vertex " + std::to_string(bad_vertex) + " position is NaN or infinite (accessor " +
                      std::to_string(pos_it->second) + ")");
    else if (!normals_ok)
        ok = fail(L, CG_ERR_GLTF_NONFINITE, what + ": a NORMAL is NaN or infinite");
    else if (prim.material >= (int)L.model.materials.size())
        ok = fail(L, CG_ERR_GLTF_INDEX_RANGE,
                  what + ": material " + std::to_string(prim.material) + " does not exist");
    else if (!has_normals && !cg_mesh_generate_normals(&m, &local))
        ok = fail(L, local.status, local.message);
    // Tangents for a normal map when the file gives none (glTF 2.0, 3.7.2.1: the client
    // computes them; build.c's generator says how it departs from MikkTSpace).
    else if (!m.tangents && L.scene->materials[material].normal_texture >= 0 &&
             !cg_mesh_generate_tangents(&m, &local))
        ok = fail(L, local.status, local.message);
    if (!ok) {
        std::free(m.positions), std::free(m.normals), std::free(m.texcoords), std::free(m.indices);
        std::free(m.tangents);
        return false;
    }
    cg_mesh_compute_bounds(&m);
    int index = cg_scene_add_mesh(L.scene, &m, L.err);
    if (index < 0) {
        std::free(m.positions), std::free(m.normals), std::free(m.texcoords), std::free(m.indices);
        std::free(m.tangents);
        return false;
    }
    // A kind stored by conegraph export wins over the classification rule.
    int kind = -1;
    if (mesh.extras.IsObject() && mesh.extras.Has("conegraph_kind")) {
        const tinygltf::Value &k = mesh.extras.Get("conegraph_kind");
        std::string s = k.IsString() ? k.Get<std::string>() : std::string();
        if (s == "heightfield")
            kind = CG_MESH_HEIGHTFIELD;
        else if (s == "complex")
            kind = CG_MESH_COMPLEX;
        else
            cg_log_warn("%s: %s: conegraph_kind '%s' is neither 'heightfield' nor 'complex'; "
                        "classified from the geometry", L.path.c_str(), mesh_label(L, mesh_index).c_str(),
                        s.c_str());
    }
    L.explicit_kind.push_back(kind);
    L.gltf_mesh_of.push_back(mesh_index);
    L.prim_of.push_back(prim_index);
    out->push_back(index);
    return true;
}

// A copy of cg mesh m with arrays of its own (for a skin, which deforms them in place).
bool
clone_mesh(loader &L, int m, int *out)
{
    cg_mesh c = L.scene->meshes[m];
    size_t nv = c.vertex_count;
    auto dup = [](const void *src, size_t bytes) -> void * {
        if (!src)
            return nullptr;
        void *d = std::malloc(bytes ? bytes : 1);
        if (d)
            std::memcpy(d, src, bytes);
        return d;
    };
    const cg_mesh &o = L.scene->meshes[m];
    c.positions = (float *)dup(o.positions, nv * 3 * sizeof(float));
    c.normals = (float *)dup(o.normals, nv * 3 * sizeof(float));
    c.texcoords = (float *)dup(o.texcoords, nv * 2 * sizeof(float));
    c.tangents = (float *)dup(o.tangents, nv * 4 * sizeof(float));
    c.indices = (uint32_t *)dup(o.indices, (size_t)c.index_count * sizeof(uint32_t));
    int index = -1;
    if ((o.positions && !c.positions) || (o.normals && !c.normals) || (o.texcoords && !c.texcoords) ||
        (o.tangents && !c.tangents) || (o.indices && !c.indices))
        fail(L, CG_ERR_OUT_OF_MEMORY, std::string("out of memory copying mesh '") + o.name + "'");
    else
        index = cg_scene_add_mesh(L.scene, &c, L.err);
    if (index < 0) {
        std::free(c.positions), std::free(c.normals), std::free(c.texcoords), std::free(c.tangents);
        std::free(c.indices);
        return false;
    }
    L.explicit_kind.push_back(L.explicit_kind[(size_t)m]);
    L.gltf_mesh_of.push_back(L.gltf_mesh_of[(size_t)m]);
    L.prim_of.push_back(L.prim_of[(size_t)m]);
    *out = index;
    return true;
}

// The cg mesh an instance of primitive mesh m draws: m itself, unless a skin owns it or a skin
// asks for it once it is used (a copy then).
bool
use_mesh(loader &L, int m, bool skinned, int *out)
{
    L.mesh_use.resize((size_t)L.scene->mesh_count, 0);
    char &use = L.mesh_use[(size_t)m];
    if (use == 0 || (use == 1 && !skinned)) {
        use = skinned ? 2 : 1;
        *out = m;
        return true;
    }
    if (!clone_mesh(L, m, out))
        return false;
    L.mesh_use.resize((size_t)L.scene->mesh_count, 0);
    L.mesh_use[(size_t)*out] = skinned ? 2 : 1;
    return true;
}

// Whether the primitive of cg mesh m has joints and weights (JOINTS_0 and WEIGHTS_0).
bool
has_skin_attributes(const loader &L, int m)
{
    const auto &attrs =
        L.model.meshes[(size_t)L.gltf_mesh_of[(size_t)m]].primitives[(size_t)L.prim_of[(size_t)m]].attributes;
    return attrs.count("JOINTS_0") && attrs.count("WEIGHTS_0");
}

bool
mesh_primitives(loader &L, int mesh_index, const std::vector<int> **out)
{
    if (!L.mesh_done[(size_t)mesh_index]) {
        L.mesh_done[(size_t)mesh_index] = true;
        const tinygltf::Mesh &mesh = L.model.meshes[(size_t)mesh_index];
        for (size_t p = 0; p < mesh.primitives.size(); p++)
            if (!add_primitive(L, mesh_index, (int)p, &L.mesh_map[(size_t)mesh_index]))
                return false;
        if (L.progress)
            cg_progress_update(L.progress, CG_LOAD_PARSED + (CG_LOAD_BUILT - CG_LOAD_PARSED) *
                                                                (double)++L.meshes_built / L.model.meshes.size());
    }
    *out = &L.mesh_map[(size_t)mesh_index];
    return true;
}

// Column-major 4x4 products and the glTF node transform (3.5.3: T * R * S, or `matrix`).
void
mat_mul(const double a[16], const double b[16], double out[16])
{
    double r[16];
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            double s = 0;
            for (int k = 0; k < 4; k++)
                s += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = s;
        }
    std::memcpy(out, r, sizeof r);
}

void
node_local(const tinygltf::Node &n, double m[16])
{
    if (n.matrix.size() == 16) {
        for (int i = 0; i < 16; i++)
            m[i] = n.matrix[(size_t)i];
        return;
    }
    double t[3] = { 0, 0, 0 }, s[3] = { 1, 1, 1 }, q[4] = { 0, 0, 0, 1 };
    if (n.translation.size() == 3)
        for (int i = 0; i < 3; i++) t[i] = n.translation[(size_t)i];
    if (n.scale.size() == 3)
        for (int i = 0; i < 3; i++) s[i] = n.scale[(size_t)i];
    if (n.rotation.size() == 4)
        for (int i = 0; i < 4; i++) q[i] = n.rotation[(size_t)i];
    double x = q[0], y = q[1], z = q[2], w = q[3];
    double r[9] = { 1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w),
                    2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                    2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y) };
    for (int c = 0; c < 3; c++) {
        for (int row = 0; row < 3; row++)
            m[c * 4 + row] = r[c * 3 + row] * s[c];
        m[c * 4 + 3] = 0;
    }
    m[12] = t[0], m[13] = t[1], m[14] = t[2], m[15] = 1;
}

void
to_float(const double d[16], float f[16])
{
    for (int i = 0; i < 16; i++)
        f[i] = (float)d[i];
}

std::string
node_label(const loader &L, int n)
{
    const std::string &name = L.model.nodes[(size_t)n].name;
    return name.empty() ? "node " + std::to_string(n) : "node '" + name + "'";
}

// Every child reference in range and no node its own ancestor, checked over the whole node
// array before any recursion (an iterative depth-first search with three colours).
bool
check_node_graph(loader &L)
{
    const auto &nodes = L.model.nodes;
    for (size_t n = 0; n < nodes.size(); n++)
        for (int c : nodes[n].children)
            if (c < 0 || (size_t)c >= nodes.size())
                return fail(L, CG_ERR_GLTF_INDEX_RANGE,
                            node_label(L, (int)n) + ": child " + std::to_string(c) + " does not exist (" +
                                std::to_string(nodes.size()) + " nodes)");
    std::vector<uint8_t> colour(nodes.size(), 0); // 0 new, 1 on the current path, 2 done
    std::vector<std::pair<int, size_t>> stack;
    for (size_t root = 0; root < nodes.size(); root++) {
        if (colour[root])
            continue;
        stack.push_back({ (int)root, 0 });
        colour[root] = 1;
        while (!stack.empty()) {
            auto &top = stack.back();
            const auto &children = nodes[(size_t)top.first].children;
            if (top.second < children.size()) {
                int c = children[top.second++];
                if (colour[(size_t)c] == 1)
                    return fail(L, CG_ERR_GLTF_NODE_CYCLE,
                                node_label(L, top.first) + " has " + node_label(L, c) +
                                    " as a child, which is also its ancestor (the node graph has a cycle)");
                if (colour[(size_t)c] == 0) {
                    colour[(size_t)c] = 1;
                    stack.push_back({ c, 0 });
                }
            } else {
                colour[(size_t)top.first] = 2;
                stack.pop_back();
            }
        }
    }
    // A node has one parent at most, and the nodes a scene lists are roots (glTF 2.0, 3.5.1).
    std::vector<int> &parent = L.parent;
    parent.assign(nodes.size(), -1);
    for (size_t n = 0; n < nodes.size(); n++)
        for (int c : nodes[n].children) {
            if (parent[(size_t)c] >= 0)
                return fail(L, CG_ERR_GLTF_SCHEMA,
                            node_label(L, c) + " is a child of both nodes[" + std::to_string(parent[(size_t)c]) +
                                "] and nodes[" + std::to_string(n) + "] (a node has one parent at most)");
            parent[(size_t)c] = (int)n;
        }
    for (size_t s = 0; s < L.model.scenes.size(); s++)
        for (int n : L.model.scenes[s].nodes)
            if (parent[(size_t)n] >= 0)
                return fail(L, CG_ERR_GLTF_SCHEMA,
                            "scenes[" + std::to_string(s) + "].nodes lists " + node_label(L, n) +
                                ", which is a child of nodes[" + std::to_string(parent[(size_t)n]) +
                                "] (a scene lists root nodes only)");
    return true;
}

bool
add_light(loader &L, int node, const double world[16], int *added)
{
    *added = -1;
    const tinygltf::Node &n = L.model.nodes[(size_t)node];
    auto it = n.extensions.find("KHR_lights_punctual");
    if (it == n.extensions.end())
        return true;
    const tinygltf::Value &ext = it->second;
    if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsNumber())
        return fail(L, CG_ERR_GLTF_PARSE, node_label(L, node) + ": KHR_lights_punctual without a light index");
    int li = ext.Get("light").GetNumberAsInt();
    if (li < 0 || (size_t)li >= L.model.lights.size())
        return fail(L, CG_ERR_GLTF_INDEX_RANGE,
                    node_label(L, node) + ": light " + std::to_string(li) + " does not exist");
    const tinygltf::Light &gl = L.model.lights[(size_t)li];
    cg_light l = {};
    cg_copy_name(l.name, gl.name.empty() ? ("light" + std::to_string(li)).c_str() : gl.name.c_str());
    if (gl.type == "directional")
        l.type = CG_LIGHT_DIRECTIONAL;
    else if (gl.type == "point")
        l.type = CG_LIGHT_POINT;
    else if (gl.type == "spot")
        l.type = CG_LIGHT_SPOT;
    else
        return fail(L, CG_ERR_GLTF_PARSE,
                    "light " + std::to_string(li) + ": unknown type '" + gl.type + "'");
    for (int k = 0; k < 3; k++)
        l.color[k] = gl.color.size() == 3 ? (float)gl.color[(size_t)k] : 1.0f;
    l.intensity = (float)gl.intensity;
    l.range = (float)gl.range;
    if (l.type == CG_LIGHT_SPOT) { // tinygltf fills the spot defaults (0, pi/4) for every light
        l.inner_cone_angle = (float)gl.spot.innerConeAngle;
        l.outer_cone_angle = (float)gl.spot.outerConeAngle;
    }
    // glTF has no field for a light's size: conegraph's extras "conegraph_angular_diameter"
    // (radians, gltf_check.c checks it is a number in [0, pi)) gives a sun its disc.
    if (gl.extras.IsObject() && gl.extras.Has("conegraph_angular_diameter")) {
        double d = number_or(gl.extras, "conegraph_angular_diameter", 0);
        if (l.type == CG_LIGHT_DIRECTIONAL)
            l.angular_diameter = (float)d;
        else if (d != 0)
            cg_log_warn("%s: light %d '%s': conegraph_angular_diameter is read on directional lights only; "
                        "this %s light stays a point", L.path.c_str(), li, l.name, gl.type.c_str());
    }
    // KHR_lights_punctual: the light sits at the node's origin and shines down its -Z.
    double d[3] = { -world[8], -world[9], -world[10] };
    double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int k = 0; k < 3; k++) {
        l.position[k] = (float)world[12 + k];
        l.direction[k] = len > 0 ? (float)(d[k] / len) : (k == 1 ? -1.0f : 0.0f);
    }
    *added = cg_scene_add_light(L.scene, &l, L.err);
    return *added >= 0;
}

bool
add_camera(loader &L, int node, const double world[16], int *added)
{
    *added = -1;
    int ci = L.model.nodes[(size_t)node].camera;
    if (ci < 0)
        return true;
    if ((size_t)ci >= L.model.cameras.size())
        return fail(L, CG_ERR_GLTF_INDEX_RANGE,
                    node_label(L, node) + ": camera " + std::to_string(ci) + " does not exist");
    const tinygltf::Camera &gc = L.model.cameras[(size_t)ci];
    cg_camera c = {};
    cg_copy_name(c.name, gc.name.empty() ? ("camera" + std::to_string(ci)).c_str() : gc.name.c_str());
    if (gc.type == "orthographic") {
        c.type = CG_CAMERA_ORTHOGRAPHIC;
        c.xmag = (float)gc.orthographic.xmag;
        c.ymag = (float)gc.orthographic.ymag;
        c.znear = (float)gc.orthographic.znear;
        c.zfar = (float)gc.orthographic.zfar;
        // glTF allows znear = 0 for orthographic cameras; cg_camera asks for znear > 0.
        if (c.znear == 0 && c.zfar > 0)
            c.znear = c.zfar * 1e-6f;
    } else if (gc.type == "perspective") {
        c.type = CG_CAMERA_PERSPECTIVE;
        c.yfov = (float)gc.perspective.yfov;
        c.aspect = (float)gc.perspective.aspectRatio;
        c.znear = (float)gc.perspective.znear;
        c.zfar = (float)gc.perspective.zfar;
    } else {
        return fail(L, CG_ERR_GLTF_PARSE, "camera " + std::to_string(ci) + ": unknown type '" + gc.type + "'");
    }
    to_float(world, c.world);
    *added = cg_scene_add_camera(L.scene, &c, L.err);
    return *added >= 0;
}

// ------------------------------------------------------------------ animation

// glTF 2.0, 3.11: a channel animates a node's translation, rotation, scale or morph target
// weights through a sampler (key times, values, interpolation). Every channel on translation,
// rotation or scale is read and its data checked as the validator checks it (times >= 0 and
// increasing, min and max equal to the data, no NaN, unit rotations), whether or not its node
// is in the default scene; channels without a node are ignored, as glTF says, and those on
// weights too: conegraph does not read morph targets, so meshes keep their base shape.
// The morph targets of the mesh on glTF node `node` (glTF 2.0, 3.7.2.2: every primitive of a
// mesh has the same number), 0 without.
int
morph_target_count(const loader &L, int node)
{
    if (node < 0 || (size_t)node >= L.model.nodes.size())
        return 0;
    int mesh = L.model.nodes[(size_t)node].mesh;
    if (mesh < 0 || (size_t)mesh >= L.model.meshes.size() || L.model.meshes[(size_t)mesh].primitives.empty())
        return 0;
    return (int)L.model.meshes[(size_t)mesh].primitives[0].targets.size();
}

bool
read_channel(loader &L, size_t ai, size_t ci, cg_anim_channel *out)
{
    const tinygltf::Animation &A = L.model.animations[ai];
    const tinygltf::AnimationChannel &ch = A.channels[ci];
    const tinygltf::AnimationSampler &sm = A.samplers[(size_t)ch.sampler];
    std::string what = "animations[" + std::to_string(ai) + "].samplers[" + std::to_string(ch.sampler) + "]";
    *out = cg_anim_channel{};
    out->path = ch.target_path == "rotation"  ? CG_ANIM_ROTATION
                : ch.target_path == "scale"   ? CG_ANIM_SCALE
                : ch.target_path == "weights" ? CG_ANIM_WEIGHTS
                                              : CG_ANIM_TRANSLATION;
    bool weights = out->path == CG_ANIM_WEIGHTS;
    if (weights)
        out->weight_count = morph_target_count(L, ch.target_node);
    out->interpolation = sm.interpolation == "STEP"          ? CG_INTERP_STEP
                         : sm.interpolation == "CUBICSPLINE" ? CG_INTERP_CUBICSPLINE
                                                             : CG_INTERP_LINEAR;
    bool cubic = out->interpolation == CG_INTERP_CUBICSPLINE, rotation = out->path == CG_ANIM_ROTATION;
    accessor_view in, o;
    if (!view_accessor(L, sm.input, what + ".input", { TINYGLTF_TYPE_SCALAR }, { TINYGLTF_COMPONENT_TYPE_FLOAT }, &in) ||
        !check_accessor_data(L, what + ".input", sm.input, "key", in))
        return false;
    for (size_t k = 0; k < in.count; k++) {
        double t = in.component(k, 0);
        if (t < 0)
            return fail(L, CG_ERR_GLTF_ACCESSOR,
                        what + ".input: key " + std::to_string(k) + " is at a negative time (" + std::to_string(t) +
                            ", accessor " + std::to_string(sm.input) + ")");
        if (k > 0 && !(t > in.component(k - 1, 0)))
            return fail(L, CG_ERR_GLTF_ACCESSOR,
                        what + ".input: key " + std::to_string(k) + " at " + std::to_string(t) +
                            " s does not come after the previous key (times must increase; accessor " +
                            std::to_string(sm.input) + ")");
    }
    if (cubic && in.count < 2)
        return fail(L, CG_ERR_GLTF_ACCESSOR, what + ": CUBICSPLINE needs 2 keys at least");
    if (weights) {
        if (!view_accessor(L, sm.output, what + ".output", { TINYGLTF_TYPE_SCALAR },
                           { TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT },
                           &o))
            return false;
    } else if (rotation) {
        if (!view_accessor(L, sm.output, what + ".output", { TINYGLTF_TYPE_VEC4 },
                           { TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT },
                           &o))
            return false;
    } else if (!view_accessor(L, sm.output, what + ".output", { TINYGLTF_TYPE_VEC3 }, { TINYGLTF_COMPONENT_TYPE_FLOAT },
                              &o)) {
        return false;
    }
    if (!check_accessor_data(L, what + ".output", sm.output, "element", o))
        return false;
    size_t per_key = (cubic ? 3 : 1) * (weights ? (size_t)out->weight_count : 1);
    if (o.count != in.count * per_key)
        return fail(L, CG_ERR_GLTF_ACCESSOR,
                    what + ".output: " + std::to_string(o.count) + " elements for " + std::to_string(in.count) +
                        " keys (expected " + std::to_string(in.count * per_key) + ")");
    if (rotation)
        // The validator's tolerance for unit quaternions; CUBICSPLINE tangents are not rotations.
        for (size_t e = cubic ? 1 : 0; e < o.count; e += per_key) {
            double len = 0;
            for (int c = 0; c < 4; c++)
                len += o.component(e, c) * o.component(e, c);
            len = std::sqrt(len);
            if (std::fabs(len - 1) > 0.00769)
                return fail(L, CG_ERR_GLTF_ACCESSOR,
                            what + ".output: element " + std::to_string(e) + " is a rotation of length " +
                                std::to_string(len) + ", not a unit quaternion (accessor " + std::to_string(sm.output) +
                                ")");
        }
    if (!cg_anim_channel_alloc(out, (int)in.count, L.err))
        return false;
    int n = weights ? 1 : cg_anim_channel_components(out); // weights: one scalar element each
    for (size_t k = 0; k < in.count; k++)
        out->times[k] = (float)in.component(k, 0);
    for (size_t e = 0; e < o.count; e++)
        for (int c = 0; c < n; c++)
            out->values[e * (size_t)n + (size_t)c] = (float)o.component(e, c);
    return true;
}

bool
read_animations(loader &L)
{
    const auto &M = L.model;
    L.animated.assign(M.nodes.size(), false);
    L.animated_below.assign(M.nodes.size(), false);
    L.weights_animated.assign(M.nodes.size(), false);
    L.node_map.assign(M.nodes.size(), -1);
    for (size_t a = 0; a < M.animations.size(); a++) {
        L.animations.emplace_back();
        auto &pending = L.animations.back();
        pending.name = M.animations[a].name.empty() ? "animation" + std::to_string(a) : M.animations[a].name;
        for (size_t c = 0; c < M.animations[a].channels.size(); c++) {
            const tinygltf::AnimationChannel &ch = M.animations[a].channels[c];
            if (ch.target_node < 0)
                continue;
            if (ch.target_path == "weights") {
                int n = morph_target_count(L, ch.target_node);
                if (n < 1 || n > CG_MAX_MORPH_TARGETS || L.model.nodes[(size_t)ch.target_node].skin >= 0) {
                    L.weight_channels++; // named in report_morph_targets
                    continue;
                }
                L.weights_animated[(size_t)ch.target_node] = true;
            }
            cg_anim_channel channel;
            if (!read_channel(L, a, c, &channel))
                return false;
            pending.channels.push_back(channel);
            pending.nodes.push_back(ch.target_node);
            L.animated[(size_t)ch.target_node] = true;
        }
    }
    // The ancestors of animated nodes are kept too, so that the hierarchy above them stays.
    for (size_t n = 0; n < M.nodes.size(); n++)
        if (L.animated[n])
            for (int p = L.parent[n]; p >= 0 && !L.animated_below[(size_t)p]; p = L.parent[(size_t)p])
                L.animated_below[(size_t)p] = true;
    return true;
}

bool
is_identity(const double m[16])
{
    for (int i = 0; i < 16; i++)
        if (m[i] != (i % 5 == 0 ? 1.0 : 0.0))
            return false;
    return true;
}

// The channels on nodes of the default scene become the scene's animations (the others
// animate nothing that is drawn).
bool
finish_animations(loader &L)
{
    for (auto &pending : L.animations) {
        cg_animation anim = {};
        cg_copy_name(anim.name, pending.name.c_str());
        std::vector<cg_anim_channel> kept;
        for (size_t c = 0; c < pending.channels.size(); c++) {
            cg_anim_channel &ch = pending.channels[c];
            int node = L.node_map[(size_t)pending.nodes[c]];
            if (node < 0) {
                cg_log_debug("%s: animation '%s': a channel on %s, which is not in the default scene, ignored",
                             L.path.c_str(), pending.name.c_str(), node_label(L, pending.nodes[c]).c_str());
                std::free(ch.times);
                std::free(ch.values);
            } else {
                ch.node = node;
                kept.push_back(ch);
            }
            ch.times = ch.values = nullptr;
        }
        if (kept.empty())
            continue;
        anim.channel_count = (int)kept.size();
        anim.channels = (cg_anim_channel *)std::malloc(sizeof(cg_anim_channel) * kept.size());
        if (!anim.channels) {
            for (auto &ch : kept)
                std::free(ch.times), std::free(ch.values);
            return fail(L, CG_ERR_OUT_OF_MEMORY, "out of memory for animation '" + pending.name + "'");
        }
        std::memcpy(anim.channels, kept.data(), sizeof(cg_anim_channel) * kept.size());
        if (cg_scene_add_animation(L.scene, &anim, L.err) < 0)
            return false;
    }
    return true;
}

// ------------------------------------------------------------------ skins

// glTF 2.0, 3.7.3: a skin's joints are nodes whose world matrices pose the skinned mesh, so
// they are kept as cg nodes (with their ancestors), as animated nodes are.
bool
mark_joints(loader &L)
{
    const auto &M = L.model;
    L.joint.assign(M.nodes.size(), false);
    L.moves.assign(M.nodes.size(), false);
    L.skin_map.assign(M.skins.size(), -1);
    for (const auto &skin : M.skins)
        for (int j : skin.joints)
            if (j >= 0 && (size_t)j < M.nodes.size())
                L.joint[(size_t)j] = true;
    for (size_t n = 0; n < M.nodes.size(); n++)
        if (L.joint[n])
            for (int p = L.parent[n]; p >= 0 && !L.animated_below[(size_t)p]; p = L.parent[(size_t)p])
                L.animated_below[(size_t)p] = true;
    return true;
}

// The cg skin of glTF skin s (made on first use): its joints' cg nodes and inverse bind
// matrices (MAT4 of FLOAT, one per joint; the identity where the file gives none). -1 with
// *why set when a joint is not in the default scene (the mesh then keeps its bind pose).
bool
skin_of(loader &L, int s, int *out, std::string *why)
{
    *out = L.skin_map[(size_t)s];
    if (*out >= 0)
        return true;
    const tinygltf::Skin &skin = L.model.skins[(size_t)s];
    std::string what = "skins[" + std::to_string(s) + "]";
    size_t n = skin.joints.size();
    if (n == 0 || n > 65536)
        return fail(L, CG_ERR_GLTF_SCHEMA, what + ": " + std::to_string(n) + " joints (1 to 65536)");
    std::vector<int> joints(n);
    for (size_t j = 0; j < n; j++) {
        int node = skin.joints[j];
        joints[j] = node >= 0 && (size_t)node < L.node_map.size() ? L.node_map[(size_t)node] : -1;
        if (joints[j] < 0) {
            *why = what + ": joint " + std::to_string(j) + " (" + node_label(L, node) + ") is not in the default scene";
            return true;
        }
    }
    std::vector<float> ibm(16 * n, 0.0f);
    for (size_t j = 0; j < n; j++)
        for (int k = 0; k < 4; k++)
            ibm[16 * j + 5 * (size_t)k] = 1.0f;
    if (skin.inverseBindMatrices >= 0) {
        accessor_view v;
        std::string label = what + ".inverseBindMatrices";
        if (!view_accessor(L, skin.inverseBindMatrices, label, { TINYGLTF_TYPE_MAT4 }, { TINYGLTF_COMPONENT_TYPE_FLOAT },
                           &v) ||
            !check_accessor_data(L, label, skin.inverseBindMatrices, "matrix", v))
            return false;
        if (v.count < n)
            return fail(L, CG_ERR_GLTF_ACCESSOR, label + ": " + std::to_string(v.count) + " matrices for " +
                                                     std::to_string(n) + " joints");
        for (size_t j = 0; j < n; j++)
            for (int k = 0; k < 16; k++)
                ibm[16 * j + (size_t)k] = (float)v.component(j, k);
    }
    int *jp = (int *)std::malloc(sizeof(int) * n);
    float *ip = (float *)std::malloc(sizeof(float) * 16 * n);
    if (!jp || !ip) {
        std::free(jp), std::free(ip);
        return fail(L, CG_ERR_OUT_OF_MEMORY, what + ": out of memory");
    }
    std::memcpy(jp, joints.data(), sizeof(int) * n);
    std::memcpy(ip, ibm.data(), sizeof(float) * 16 * n);
    std::string name = skin.name.empty() ? "skin" + std::to_string(s) : skin.name;
    *out = cg_scene_add_skin(L.scene, name.c_str(), (int)n, jp, ip, L.err);
    L.skin_map[(size_t)s] = *out;
    return *out >= 0;
}

// Each skinned instance's joints and weights, from every JOINTS_n / WEIGHTS_n pair of its
// primitive (glTF 2.0, 3.7.3.2: four joints per pair), weights normalised to sum 1.
bool
finish_skins(loader &L)
{
    bool warned_weightless = false;
    for (const auto &use : L.skin_uses) {
        int skin;
        std::string why;
        if (!skin_of(L, use.skin, &skin, &why))
            return false;
        cg_instance *inst = &L.scene->instances[use.instance];
        if (skin < 0) {
            cg_log_warn("%s: %s: %s is drawn in its bind pose, placed by its node", L.path.c_str(), why.c_str(),
                        mesh_label(L, L.gltf_mesh_of[(size_t)use.mesh]).c_str());
            std::memcpy(inst->world, use.world, sizeof use.world);
            continue;
        }
        const tinygltf::Primitive &prim =
            L.model.meshes[(size_t)L.gltf_mesh_of[(size_t)use.mesh]].primitives[(size_t)L.prim_of[(size_t)use.mesh]];
        std::string what = mesh_label(L, L.gltf_mesh_of[(size_t)use.mesh]) + " primitive " +
                           std::to_string(L.prim_of[(size_t)use.mesh]);
        int sets = 0;
        while (prim.attributes.count("JOINTS_" + std::to_string(sets)) &&
               prim.attributes.count("WEIGHTS_" + std::to_string(sets)))
            sets++;
        size_t nv = L.scene->meshes[use.mesh].vertex_count, per = 4 * (size_t)sets;
        int joint_count = L.scene->skins[skin].joint_count;
        uint16_t *joints = (uint16_t *)std::malloc(sizeof(uint16_t) * nv * per);
        float *weights = (float *)std::malloc(sizeof(float) * nv * per);
        if (!joints || !weights) {
            std::free(joints), std::free(weights);
            return fail(L, CG_ERR_OUT_OF_MEMORY, what + ": out of memory for its joints and weights");
        }
        for (int k = 0; k < sets; k++) {
            std::string jn = "JOINTS_" + std::to_string(k), wn = "WEIGHTS_" + std::to_string(k);
            int ja = prim.attributes.at(jn), wa = prim.attributes.at(wn);
            accessor_view jv, wv;
            bool ok = view_accessor(L, ja, what + " " + jn, { TINYGLTF_TYPE_VEC4 },
                                    { TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT },
                                    &jv) &&
                      view_accessor(L, wa, what + " " + wn, { TINYGLTF_TYPE_VEC4 },
                                    { TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT },
                                    &wv) &&
                      check_accessor_data(L, what + " " + wn, wa, "vertex", wv);
            if (ok && (jv.count != nv || wv.count != nv))
                ok = fail(L, CG_ERR_GLTF_ACCESSOR, what + ": attribute counts differ (POSITION has " +
                                                       std::to_string(nv) + ", " + jn + " " + std::to_string(jv.count) +
                                                       ", " + wn + " " + std::to_string(wv.count) + ")");
            for (size_t v = 0; ok && v < nv; v++)
                for (int c = 0; ok && c < 4; c++) {
                    double j = jv.component(v, c), w = wv.component(v, c);
                    if (j >= joint_count && w != 0)
                        ok = fail(L, CG_ERR_GLTF_INDEX_RANGE, what + " " + jn + ": vertex " + std::to_string(v) +
                                                                  " names joint " + std::to_string((long)j) +
                                                                  " (the skin has " + std::to_string(joint_count) + ")");
                    else if (w < 0)
                        ok = fail(L, CG_ERR_GLTF_ACCESSOR, what + " " + wn + ": vertex " + std::to_string(v) +
                                                               " has a negative weight");
                    joints[v * per + 4 * (size_t)k + (size_t)c] = (uint16_t)(j < joint_count ? j : 0);
                    weights[v * per + 4 * (size_t)k + (size_t)c] = (float)w;
                }
            if (!ok) {
                std::free(joints), std::free(weights);
                return false;
            }
        }
        // glTF asks for weights summing to 1; exporters round, so they are normalised. A vertex
        // weighing no joint follows the first joint it names.
        for (size_t v = 0; v < nv; v++) {
            double sum = 0;
            for (size_t i = 0; i < per; i++)
                sum += weights[v * per + i];
            if (sum > 0) {
                for (size_t i = 0; i < per; i++)
                    weights[v * per + i] = (float)(weights[v * per + i] / sum);
            } else {
                if (!warned_weightless)
                    cg_log_warn("%s: %s: vertex %zu has no joint weight; it follows joint %u", L.path.c_str(),
                                what.c_str(), v, (unsigned)joints[v * per]);
                warned_weightless = true;
                weights[v * per] = 1.0f;
            }
        }
        // The skinned mesh moves when any of its joints does.
        for (int j : L.model.skins[(size_t)use.skin].joints)
            if (L.moves[(size_t)j])
                inst->moving = true;
        if (cg_scene_add_skinned_mesh(L.scene, use.mesh, use.instance, skin, (int)per, joints, weights, L.err) < 0)
            return false;
    }
    return true;
}

// ------------------------------------------------------------------ morph targets

// Each morphed instance's targets (glTF 2.0, 3.7.2.2: POSITION, NORMAL and TANGENT
// displacements, VEC3 of FLOAT or normalized integers) and default weights (the node's, else the
// mesh's, else 0). Its cg node, when a channel animates its weights, is the node's.
bool
finish_morphs(loader &L)
{
    static const char *const attributes[3] = { "POSITION", "NORMAL", "TANGENT" };
    for (const auto &use : L.morph_uses) {
        int gmesh = L.gltf_mesh_of[(size_t)use.mesh];
        const tinygltf::Mesh &mesh = L.model.meshes[(size_t)gmesh];
        const tinygltf::Primitive &prim = mesh.primitives[(size_t)L.prim_of[(size_t)use.mesh]];
        std::string what = mesh_label(L, gmesh) + " primitive " + std::to_string(L.prim_of[(size_t)use.mesh]);
        size_t nv = L.scene->meshes[use.mesh].vertex_count, n = prim.targets.size();
        cg_morphed_mesh mm = {};
        mm.mesh = use.mesh;
        mm.instance = use.instance;
        mm.target_count = (int)n;
        mm.node = L.weights_animated[(size_t)use.node] ? L.node_map[(size_t)use.node] : -1;
        float **deltas[3] = { &mm.position_deltas, &mm.normal_deltas, &mm.tangent_deltas };
        bool ok = true;
        mm.weights = (float *)std::calloc(n, sizeof(float));
        ok = mm.weights != nullptr;
        for (size_t t = 0; ok && t < n; t++)
            for (int a = 0; ok && a < 3; a++) {
                auto it = prim.targets[t].find(attributes[a]);
                if (it == prim.targets[t].end())
                    continue;
                std::string label = what + " targets[" + std::to_string(t) + "]." + attributes[a];
                accessor_view v;
                ok = view_accessor(L, it->second, label, { TINYGLTF_TYPE_VEC3 },
                                   { TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                     TINYGLTF_COMPONENT_TYPE_SHORT },
                                   &v) &&
                     check_accessor_data(L, label, it->second, "vertex", v);
                if (ok && v.count != nv)
                    ok = fail(L, CG_ERR_GLTF_ACCESSOR, label + ": " + std::to_string(v.count) + " elements for " +
                                                           std::to_string(nv) + " vertices");
                if (ok && !*deltas[a]) {
                    *deltas[a] = (float *)std::calloc(n * nv * 3, sizeof(float));
                    if (!*deltas[a])
                        ok = fail(L, CG_ERR_OUT_OF_MEMORY, what + ": out of memory for its morph targets");
                }
                for (size_t e = 0; ok && e < nv; e++)
                    for (int k = 0; k < 3; k++)
                        (*deltas[a])[(t * nv + e) * 3 + (size_t)k] = (float)v.component(e, k);
            }
        const tinygltf::Node &node = L.model.nodes[(size_t)use.node];
        const std::vector<double> &defaults = node.weights.size() == n ? node.weights : mesh.weights;
        for (size_t t = 0; ok && t < n && defaults.size() == n; t++)
            mm.weights[t] = (float)defaults[t];
        if (ok && mm.node >= 0)
            L.scene->instances[use.instance].moving = true;
        if (!ok || cg_scene_add_morphed_mesh(L.scene, &mm, L.err) < 0) {
            if (!ok) {
                std::free(mm.weights), std::free(mm.position_deltas), std::free(mm.normal_deltas);
                std::free(mm.tangent_deltas);
            }
            return false;
        }
    }
    return true;
}

// The default scene's nodes, depth first. A node is flattened (its meshes, lights and camera
// placed by its world matrix) unless animation needs it: an animated node, a node under one
// (dynamic: what hangs on it moves) and the ancestors of animated nodes are kept as cg_nodes
// with their local transforms, except those that are not animated and whose transform is the
// identity (what hangs on them goes to the nearest kept ancestor, so a file conegraph exports
// loads back with the same nodes). What hangs on a dynamic node is attached to its cg node.
bool
visit_nodes(loader &L, const std::vector<int> &roots)
{
    struct item {
        int node;
        double parent[16];
        int cg_parent;
        bool dynamic;
    };
    std::vector<item> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
        item r = { *it, { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 }, -1, false };
        stack.push_back(r);
    }
    while (!stack.empty()) {
        item cur = stack.back();
        stack.pop_back();
        const tinygltf::Node &n = L.model.nodes[(size_t)cur.node];
        double local[16], world[16];
        node_local(n, local);
        mat_mul(cur.parent, local, world);
        bool animated = L.animated[(size_t)cur.node];
        bool dynamic = cur.dynamic || animated;
        L.moves[(size_t)cur.node] = dynamic;
        int here = cur.cg_parent;
        if (L.joint[(size_t)cur.node] ||
            ((dynamic || L.animated_below[(size_t)cur.node]) && (animated || !is_identity(local)))) {
            cg_node c = cg_node_default(n.name.empty() ? ("node" + std::to_string(cur.node)).c_str() : n.name.c_str());
            c.parent = cur.cg_parent;
            if (n.matrix.size() == 16) {
                c.has_matrix = true;
                for (int i = 0; i < 16; i++)
                    c.matrix[i] = (float)n.matrix[(size_t)i];
            } else {
                for (size_t i = 0; i < 3 && n.translation.size() == 3; i++)
                    c.translation[i] = (float)n.translation[i];
                for (size_t i = 0; i < 4 && n.rotation.size() == 4; i++)
                    c.rotation[i] = (float)n.rotation[i];
                for (size_t i = 0; i < 3 && n.scale.size() == 3; i++)
                    c.scale[i] = (float)n.scale[i];
            }
            std::memcpy(c.world, world, sizeof world);
            here = cg_scene_add_node(L.scene, &c, L.err);
            if (here < 0)
                return false;
            L.node_map[(size_t)cur.node] = here;
        }
        if (n.mesh >= 0) {
            if ((size_t)n.mesh >= L.model.meshes.size())
                return fail(L, CG_ERR_GLTF_INDEX_RANGE,
                            node_label(L, cur.node) + ": mesh " + std::to_string(n.mesh) + " does not exist (" +
                                std::to_string(L.model.meshes.size()) + " meshes)");
            const std::vector<int> *prims;
            if (!mesh_primitives(L, n.mesh, &prims))
                return false;
            float wf[16];
            to_float(world, wf);
            bool skinned_node = n.skin >= 0 && (size_t)n.skin < L.model.skins.size();
            for (int m : *prims) {
                bool skinned = skinned_node && has_skin_attributes(L, m);
                size_t targets = L.model.meshes[(size_t)n.mesh].primitives[(size_t)L.prim_of[(size_t)m]].targets.size();
                bool morphed = targets > 0 && targets <= CG_MAX_MORPH_TARGETS && !skinned;
                if (targets > 0 && !morphed)
                    L.morph_left_out.push_back(mesh_label(L, n.mesh) + (skinned ? " (skinned)" : " (too many targets)"));
                int use;
                if (!use_mesh(L, m, skinned || morphed, &use))
                    return false;
                int instance = cg_scene_add_instance(L.scene, use, wf, L.err);
                if (instance < 0)
                    return false;
                if (skinned) { // placed by its joints (finish_skins), not by this node
                    L.skin_uses.push_back({ n.skin, cur.node, use, instance, {} });
                    std::memcpy(L.skin_uses.back().world, wf, sizeof wf);
                    continue;
                }
                if (dynamic && cg_scene_attach(L.scene, CG_ATTACH_INSTANCE, instance, here, L.err) < 0)
                    return false;
                if (morphed)
                    L.morph_uses.push_back({ cur.node, use, instance });
            }
        }
        int light, camera;
        if (!add_light(L, cur.node, world, &light) ||
            (dynamic && light >= 0 && cg_scene_attach(L.scene, CG_ATTACH_LIGHT, light, here, L.err) < 0) ||
            !add_camera(L, cur.node, world, &camera) ||
            (dynamic && camera >= 0 && cg_scene_attach(L.scene, CG_ATTACH_CAMERA, camera, here, L.err) < 0))
            return false;
        for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) {
            item child;
            child.node = *c;
            std::memcpy(child.parent, world, sizeof world);
            child.cg_parent = here;
            child.dynamic = dynamic;
            stack.push_back(child);
        }
    }
    return true;
}

// ------------------------------------------------------------------ materials

// A textureInfo wherever it stands: the core ones (tinygltf parses them) and those inside
// material extensions (raw JSON values).
struct texture_ref {
    int index = -1;
    int texcoord = 0;
    const tinygltf::Value *transform = nullptr; // its KHR_texture_transform object, if any
};

template <class Info>
texture_ref
core_ref(const Info &info)
{
    texture_ref r;
    r.index = info.index;
    r.texcoord = info.texCoord;
    auto it = info.extensions.find("KHR_texture_transform");
    if (it != info.extensions.end() && it->second.IsObject())
        r.transform = &it->second;
    return r;
}

// A textureInfo inside an extension object (gltf_check.c has checked its types).
texture_ref
value_ref(const tinygltf::Value &ext, const char *name)
{
    texture_ref r;
    if (!ext.IsObject() || !ext.Has(name))
        return r;
    const tinygltf::Value &t = ext.Get(name);
    if (!t.IsObject() || !t.Has("index") || !t.Get("index").IsNumber())
        return r;
    r.index = t.Get("index").GetNumberAsInt();
    if (t.Has("texCoord") && t.Get("texCoord").IsNumber())
        r.texcoord = t.Get("texCoord").GetNumberAsInt();
    if (t.Has("extensions") && t.Get("extensions").IsObject() && t.Get("extensions").Has("KHR_texture_transform") &&
        t.Get("extensions").Get("KHR_texture_transform").IsObject())
        r.transform = &t.Get("extensions").Get("KHR_texture_transform");
    return r;
}

double
number_or(const tinygltf::Value &o, const char *name, double fallback)
{
    if (o.IsObject() && o.Has(name) && o.Get(name).IsNumber())
        return o.Get(name).GetNumberAsDouble();
    return fallback;
}

// KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv. The rotation is the one
// the extension's implementations (Babylon.js, three.js, Blender, the TextureTransformTest
// sample) use, u' = cos r u + sin r v, v' = -sin r u + cos r v: counter-clockwise in glTF's
// UV space, whose v axis points down. The GLSL listing of the extension's README has the
// transpose (KhronosGroup/glTF issue 1563 says so). Columns first, as cg_uv_transform.
cg_uv_transform
uv_transform_of(const tinygltf::Value *t)
{
    cg_uv_transform m = cg_uv_transform_identity();
    if (!t)
        return m;
    double off[2] = { 0, 0 }, sc[2] = { 1, 1 }, r = number_or(*t, "rotation", 0);
    for (int k = 0; k < 2; k++) {
        if (t->Has("offset") && t->Get("offset").IsArray() && t->Get("offset").ArrayLen() == 2)
            off[k] = t->Get("offset").Get(k).GetNumberAsDouble();
        if (t->Has("scale") && t->Get("scale").IsArray() && t->Get("scale").ArrayLen() == 2)
            sc[k] = t->Get("scale").Get(k).GetNumberAsDouble();
    }
    double c = std::cos(r), s = std::sin(r);
    double v[6] = { c * sc[0], -s * sc[0], s * sc[1], c * sc[1], off[0], off[1] };
    for (int k = 0; k < 6; k++)
        m.m[k] = (float)v[k] + 0.0f; // + 0: no -0 from a rotation of 0
    return m;
}

// Which way a material samples each of its textures: base colour and emissive hold sRGB
// colours, the others linear data (glTF 2.0, 3.9). A glTF texture used both ways becomes two
// cg textures with the same pixels.
enum { USE_SRGB = 1, USE_LINEAR = 2 };

void
note(loader &L, const std::string &feature, const std::string &material, const std::string &fallback)
{
    for (auto &item : L.left_out)
        if (item.feature == feature && item.fallback == fallback) {
            if (std::find(item.materials.begin(), item.materials.end(), material) == item.materials.end())
                item.materials.push_back(material);
            return;
        }
    L.left_out.push_back({ feature, fallback, { material } });
}

bool
read_texture(loader &L, const std::string &material, const char *slot, const texture_ref &ref, bool srgb,
             int *out, cg_uv_transform *uv)
{
    *out = -1;
    *uv = cg_uv_transform_identity();
    if (ref.index < 0)
        return true;
    if ((size_t)ref.index >= L.model.textures.size())
        return fail(L, CG_ERR_GLTF_INDEX_RANGE,
                    material + " " + slot + ": texture " + std::to_string(ref.index) + " does not exist");
    int texcoord = ref.texcoord;
    if (ref.transform && ref.transform->Has("texCoord") && ref.transform->Get("texCoord").IsNumber())
        texcoord = ref.transform->Get("texCoord").GetNumberAsInt();
    if (texcoord != 0)
        note(L, std::string(slot) + " on TEXCOORD_" + std::to_string(texcoord), material,
             "sampled with TEXCOORD_0 (conegraph reads one texture coordinate set)");
    *out = srgb ? L.texture_srgb[(size_t)ref.index] : L.texture_linear[(size_t)ref.index];
    if (*out < 0)
        note(L, std::string(slot) + " (texture " + std::to_string(ref.index) + " without a PNG or JPEG image)",
             material, "its factor alone");
    *uv = uv_transform_of(ref.transform);
    return true;
}

// What conegraph does instead of a material extension it does not implement.
const char *
extension_fallback(const std::string &name)
{
    static const std::pair<const char *, const char *> known[] = {
        { "KHR_materials_clearcoat", "no clear coat; the base layer alone" },
        { "KHR_materials_sheen", "no sheen; the base layer alone" },
        { "KHR_materials_iridescence", "no thin-film iridescence; plain Fresnel" },
        { "KHR_materials_anisotropy", "isotropic GGX with the material's roughness" },
        { "KHR_materials_dispersion", "one ior for every wavelength" },
        { "KHR_materials_diffuse_transmission", "no diffuse transmission; opaque diffuse" },
        { "KHR_materials_unlit", "shaded as a lit metallic-roughness material" },
        { "KHR_materials_pbrSpecularGlossiness", "its pbrMetallicRoughness values (glTF's defaults where absent)" },
        { "KHR_materials_volume_scatter", "no scattering in the volume; attenuation alone" },
    };
    for (const auto &k : known)
        if (name == k.first)
            return k.second;
    return "ignored";
}

bool
is_read_material_extension(const std::string &name)
{
    return name == "KHR_materials_emissive_strength" || name == "KHR_materials_ior" ||
           name == "KHR_materials_specular" || name == "KHR_materials_transmission" || name == "KHR_materials_volume";
}

const tinygltf::Value *
material_extension(const tinygltf::Material &gm, const char *name)
{
    auto it = gm.extensions.find(name);
    return it != gm.extensions.end() && it->second.IsObject() ? &it->second : nullptr;
}

// The sRGB and linear uses of every glTF texture (texture_srgb / texture_linear get filled by
// convert_textures from these).
void
texture_uses(const loader &L, std::vector<int> *uses)
{
    uses->assign(L.model.textures.size(), 0);
    auto mark = [&](int index, int use) {
        if (index >= 0 && (size_t)index < uses->size())
            (*uses)[(size_t)index] |= use;
    };
    for (const tinygltf::Material &gm : L.model.materials) {
        mark(gm.pbrMetallicRoughness.baseColorTexture.index, USE_SRGB);
        mark(gm.emissiveTexture.index, USE_SRGB);
        mark(gm.pbrMetallicRoughness.metallicRoughnessTexture.index, USE_LINEAR);
        mark(gm.normalTexture.index, USE_LINEAR);
        mark(gm.occlusionTexture.index, USE_LINEAR);
        if (const tinygltf::Value *t = material_extension(gm, "KHR_materials_transmission"))
            mark(value_ref(*t, "transmissionTexture").index, USE_LINEAR);
    }
}

bool
convert_materials(loader &L)
{
    for (size_t i = 0; i < L.model.materials.size(); i++) {
        const tinygltf::Material &gm = L.model.materials[i];
        std::string what = gm.name.empty() ? "material " + std::to_string(i) : "material '" + gm.name + "'";
        cg_material m = cg_material_gltf_default(gm.name.empty() ? ("material" + std::to_string(i)).c_str()
                                                                  : gm.name.c_str());
        const auto &pbr = gm.pbrMetallicRoughness;
        for (size_t k = 0; k < 4 && pbr.baseColorFactor.size() == 4; k++)
            m.base_color[k] = (float)pbr.baseColorFactor[k];
        for (size_t k = 0; k < 3 && gm.emissiveFactor.size() == 3; k++)
            m.emissive[k] = (float)gm.emissiveFactor[k];
        m.metallic = (float)pbr.metallicFactor;
        m.roughness = (float)pbr.roughnessFactor;
        m.normal_scale = (float)gm.normalTexture.scale;
        m.occlusion_strength = (float)gm.occlusionTexture.strength;
        m.alpha_mode = gm.alphaMode == "MASK" ? CG_ALPHA_MASK : gm.alphaMode == "BLEND" ? CG_ALPHA_BLEND : CG_ALPHA_OPAQUE;
        m.alpha_cutoff = (float)gm.alphaCutoff;
        m.double_sided = gm.doubleSided;
        if (const tinygltf::Value *e = material_extension(gm, "KHR_materials_emissive_strength"))
            m.emissive_strength = (float)number_or(*e, "emissiveStrength", 1);
        // KHR_materials_ior: ior 0 is allowed and means an infinite ior (F0 = 1, the formula
        // ((ior - 1) / (ior + 1))^2 gives exactly that), kept as 0.
        if (const tinygltf::Value *e = material_extension(gm, "KHR_materials_ior"))
            m.ior = (float)number_or(*e, "ior", 1.5);
        if (const tinygltf::Value *e = material_extension(gm, "KHR_materials_specular")) {
            m.specular = (float)number_or(*e, "specularFactor", 1);
            if (e->Has("specularColorFactor") && e->Get("specularColorFactor").IsArray() &&
                e->Get("specularColorFactor").ArrayLen() == 3)
                for (int k = 0; k < 3; k++)
                    m.specular_color[k] = (float)e->Get("specularColorFactor").Get(k).GetNumberAsDouble();
            if (e->Has("specularTexture"))
                note(L, "KHR_materials_specular specularTexture", what, "specularFactor alone");
            if (e->Has("specularColorTexture"))
                note(L, "KHR_materials_specular specularColorTexture", what, "specularColorFactor alone");
        }
        texture_ref transmission_ref;
        if (const tinygltf::Value *e = material_extension(gm, "KHR_materials_transmission")) {
            m.transmission = (float)number_or(*e, "transmissionFactor", 0);
            transmission_ref = value_ref(*e, "transmissionTexture");
        }
        if (const tinygltf::Value *e = material_extension(gm, "KHR_materials_volume")) {
            m.thickness = (float)number_or(*e, "thicknessFactor", 0);
            m.attenuation_distance = (float)number_or(*e, "attenuationDistance", INFINITY);
            if (e->Has("attenuationColor") && e->Get("attenuationColor").IsArray() &&
                e->Get("attenuationColor").ArrayLen() == 3)
                for (int k = 0; k < 3; k++)
                    m.attenuation_color[k] = (float)e->Get("attenuationColor").Get(k).GetNumberAsDouble();
            if (e->Has("thicknessTexture"))
                note(L, "KHR_materials_volume thicknessTexture", what, "thicknessFactor alone");
            if (!material_extension(gm, "KHR_materials_transmission") && m.thickness > 0)
                note(L, "KHR_materials_volume without KHR_materials_transmission", what,
                     "opaque (a volume is only seen through transmission)");
        }
        for (const auto &e : gm.extensions)
            if (!is_read_material_extension(e.first))
                note(L, e.first, what, extension_fallback(e.first));
        if (!read_texture(L, what, "baseColorTexture", core_ref(pbr.baseColorTexture), true, &m.base_color_texture,
                          &m.uv[CG_TEX_BASE_COLOR]) ||
            !read_texture(L, what, "emissiveTexture", core_ref(gm.emissiveTexture), true, &m.emissive_texture,
                          &m.uv[CG_TEX_EMISSIVE]) ||
            !read_texture(L, what, "metallicRoughnessTexture", core_ref(pbr.metallicRoughnessTexture), false,
                          &m.metallic_roughness_texture, &m.uv[CG_TEX_METALLIC_ROUGHNESS]) ||
            !read_texture(L, what, "normalTexture", core_ref(gm.normalTexture), false, &m.normal_texture,
                          &m.uv[CG_TEX_NORMAL]) ||
            !read_texture(L, what, "occlusionTexture", core_ref(gm.occlusionTexture), false, &m.occlusion_texture,
                          &m.uv[CG_TEX_OCCLUSION]) ||
            !read_texture(L, what, "transmissionTexture", transmission_ref, false, &m.transmission_texture,
                          &m.uv[CG_TEX_TRANSMISSION]))
            return false;
        bool is_zero = i == 0 && gm.extras.IsObject() && gm.extras.Has("conegraph_material_0") &&
                       gm.extras.Get("conegraph_material_0").IsBool() && gm.extras.Get("conegraph_material_0").Get<bool>();
        if (is_zero) {
            L.scene->materials[0] = m;
            L.material_base = 0;
        } else if (cg_scene_add_material(L.scene, &m, L.err) < 0) {
            return false;
        }
    }
    return true;
}

// One notice for the morph targets conegraph does not read: those of skinned meshes, of meshes
// with more than CG_MAX_MORPH_TARGETS, and the animation channels on their weights.
void
report_morph_targets(loader &L)
{
    if (L.morph_left_out.empty() && L.weight_channels == 0)
        return;
    std::string meshes;
    for (size_t i = 0; i < L.morph_left_out.size() && i < 4; i++)
        meshes += (meshes.empty() ? "" : ", ") + L.morph_left_out[i];
    if (L.morph_left_out.size() > 4)
        meshes += " and " + std::to_string(L.morph_left_out.size() - 4) + " more";
    std::string channels = L.weight_channels == 0 ? std::string()
                           : std::to_string(L.weight_channels) + " animation channel" +
                                 (L.weight_channels > 1 ? "s" : "") + " on their weights";
    cg_log_warn("%s: morph targets not read (%s%s%s): those meshes keep their base shape%s", L.path.c_str(),
                meshes.c_str(), !meshes.empty() && !channels.empty() ? "; " : "", channels.c_str(),
                channels.empty() ? "" : ", the channels are ignored");
}

// The one notice of what the file's materials ask for and conegraph does not render.
void
report_left_out(loader &L)
{
    if (L.left_out.empty())
        return;
    std::string list;
    for (const auto &item : L.left_out) {
        std::string materials;
        for (const std::string &m : item.materials)
            materials += (materials.empty() ? "" : ", ") + m;
        list += (list.empty() ? "" : "; ") + item.feature + " (" + materials + "): " + item.fallback;
    }
    cg_log_warn("%s: material features not rendered, each as FEATURE (MATERIALS): WHAT IS USED INSTEAD: %s",
                L.path.c_str(), list.c_str());
}

// RGBA8, rows top to bottom as in the file (cg_texture), from tinygltf's decoded image (1-4
// channels of 8 or 16 bits).
bool
convert_image(loader &L, size_t image_index, cg_texture *t)
{
    tinygltf::Image &img = L.model.images[image_index];
    std::string what = "image " + std::to_string(image_index);
    if (img.image.empty() && img.bufferView >= 0) {
        const auto &M = L.model;
        if ((size_t)img.bufferView >= M.bufferViews.size())
            return fail(L, CG_ERR_GLTF_BUFFER, what + ": bufferView does not exist");
        const auto &bv = M.bufferViews[(size_t)img.bufferView];
        if (bv.buffer < 0 || (size_t)bv.buffer >= M.buffers.size() || bv.byteLength > (1ull << 31) ||
            bv.byteOffset > (1ull << 40) || bv.byteOffset + bv.byteLength > M.buffers[(size_t)bv.buffer].data.size())
            return fail(L, CG_ERR_GLTF_BUFFER, what + ": bufferView " + std::to_string(img.bufferView) +
                                                   " runs past the end of its buffer");
        if (bv.byteStride)
            return fail(L, CG_ERR_GLTF_BUFFER, what + ": bufferView " + std::to_string(img.bufferView) +
                                                   " holds an image and must not have a byteStride");
        std::string e, w;
        const unsigned char *bytes = M.buffers[(size_t)bv.buffer].data.data() + bv.byteOffset;
        std::string problem = image_format_problem(img, bytes, bv.byteLength);
        if (problem.empty() &&
            !tinygltf::LoadImageData(&img, (int)image_index, &e, &w, 0, 0, bytes, (int)bv.byteLength, nullptr))
            problem = "cannot be decoded";
        if (!problem.empty()) {
            L.image_problem[(int)image_index] = problem;
            img.image.clear();
        }
    }
    auto problem = L.image_problem.find((int)image_index);
    if (problem != L.image_problem.end())
        return fail(L, CG_ERR_IMAGE_FORMAT, what + " " + problem->second);
    int bytes_per = img.bits == 16 ? 2 : 1;
    if (img.image.empty() || img.width <= 0 || img.height <= 0 || img.component < 1 || img.component > 4 ||
        (img.bits != 8 && img.bits != 16) ||
        img.image.size() < (size_t)img.width * img.height * img.component * bytes_per)
        return fail(L, CG_ERR_IMAGE_FORMAT, what + " cannot be decoded");
    size_t w = (size_t)img.width, h = (size_t)img.height;
    uint8_t *rgba = (uint8_t *)std::malloc(w * h * 4);
    if (!rgba)
        return fail(L, CG_ERR_OUT_OF_MEMORY, what + ": out of memory");
    for (size_t y = 0; y < h; y++)
        for (size_t x = 0; x < w; x++) {
            const unsigned char *src = img.image.data() + ((y * w + x) * (size_t)img.component) * bytes_per;
            uint8_t c[4] = { 0, 0, 0, 255 };
            for (int k = 0; k < img.component; k++)
                c[k] = bytes_per == 2 ? (uint8_t)((src[2 * k] | (src[2 * k + 1] << 8)) >> 8) : src[k];
            if (img.component <= 2) { // grey, grey + alpha
                c[3] = img.component == 2 ? c[1] : 255;
                c[1] = c[2] = c[0];
            }
            std::memcpy(rgba + (y * w + x) * 4, c, 4);
        }
    t->width = img.width;
    t->height = img.height;
    t->rgba = rgba;
    return true;
}

bool
convert_textures(loader &L)
{
    std::vector<int> uses;
    texture_uses(L, &uses);
    L.texture_srgb.assign(L.model.textures.size(), -1);
    L.texture_linear.assign(L.model.textures.size(), -1);
    // Per image and encoding, its cg texture: -2 not yet converted, -1 none.
    std::vector<int> image_texture[2] = { std::vector<int>(L.model.images.size(), -2),
                                          std::vector<int>(L.model.images.size(), -2) };
    for (size_t i = 0; i < L.model.textures.size(); i++) {
        int src = L.model.textures[i].source;
        if (src < 0) { // glTF allows a texture whose image comes from an extension only
            cg_log_warn("%s: texture %zu has no source image conegraph can read; ignored", L.path.c_str(), i);
            continue;
        }
        // A texture no material uses is converted as sRGB, so that its image is still checked.
        int use = uses[i] ? uses[i] : USE_SRGB;
        for (int linear = 0; linear < 2; linear++) {
            if (!(use & (linear ? USE_LINEAR : USE_SRGB)))
                continue;
            int &done = image_texture[linear][(size_t)src];
            if (done == -2) {
                cg_texture t = {};
                const auto &img = L.model.images[(size_t)src];
                std::string name = !img.name.empty() ? img.name : !img.uri.empty() && img.uri.compare(0, 5, "data:")
                                                                       ? img.uri : "image" + std::to_string(src);
                cg_copy_name(t.name, name.c_str());
                t.srgb = !linear;
                if (!convert_image(L, (size_t)src, &t))
                    return false;
                done = -1;
                if (t.rgba) {
                    int index = cg_scene_add_texture(L.scene, &t, L.err);
                    if (index < 0) {
                        std::free(t.rgba);
                        return false;
                    }
                    done = index;
                }
            }
            (linear ? L.texture_linear : L.texture_srgb)[i] = done;
        }
    }
    return true;
}

// How the mesh primitives use the model's accessors and bufferViews, checked as the
// validator checks them, for every mesh (whether a node uses it or not): attribute formats
// (glTF 2.0, 3.7.2.1), equal attribute counts, alignment, one use per accessor and per
// bufferView, strides where they are needed or forbidden, POSITION bounds, and a
// TEXCOORD_n for every texture a primitive's material samples with texCoord n.
// Animation samplers' accessors too (every sampler's input and output, as the validator
// marks them): an accessor has one use, and a bufferView holds one kind of data.
enum use_kind { USE_NONE, USE_VERTEX, USE_INDEX, USE_ANIM_INPUT, USE_ANIM_OUTPUT };

bool
attribute_format_ok(const std::string &name, const tinygltf::Accessor &a)
{
    bool f = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
    bool unorm = a.normalized && (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                  a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
    auto starts = [&](const char *prefix) { return name.compare(0, std::strlen(prefix), prefix) == 0; };
    if (name == "POSITION" || name == "NORMAL")
        return f && a.type == TINYGLTF_TYPE_VEC3;
    if (name == "TANGENT")
        return f && a.type == TINYGLTF_TYPE_VEC4;
    if (starts("TEXCOORD_"))
        return (f || unorm) && a.type == TINYGLTF_TYPE_VEC2;
    if (starts("COLOR_"))
        return (f || unorm) && (a.type == TINYGLTF_TYPE_VEC3 || a.type == TINYGLTF_TYPE_VEC4);
    if (starts("JOINTS_"))
        return !a.normalized && a.type == TINYGLTF_TYPE_VEC4 &&
               (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
    if (starts("WEIGHTS_"))
        return (f || unorm) && a.type == TINYGLTF_TYPE_VEC4;
    return true; // application-specific (_NAME): any format but UNSIGNED_INT, checked by the caller
}

bool
check_model(loader &L)
{
    const tinygltf::Model &M = L.model;
    for (size_t i = 0; i < M.accessors.size(); i++) {
        const tinygltf::Accessor &a = M.accessors[i];
        if (a.bufferView < 0)
            continue;
        std::string what = "accessors[" + std::to_string(i) + "]";
        const tinygltf::BufferView &bv = M.bufferViews[(size_t)a.bufferView];
        size_t size = component_size(a.componentType), elem = size * (size_t)component_count(a.type);
        size_t stride = bv.byteStride ? bv.byteStride : elem;
        if (a.byteOffset % size || (bv.byteOffset + a.byteOffset) % size)
            return fail(L, CG_ERR_GLTF_ACCESSOR,
                        what + ": byteOffset " + std::to_string(a.byteOffset) + " in bufferView " +
                            std::to_string(a.bufferView) + " (at byte " + std::to_string(bv.byteOffset) +
                            ") is not aligned to its " + std::to_string(size) + "-byte components");
        if (stride < elem)
            return fail(L, CG_ERR_GLTF_ACCESSOR,
                        what + ": byteStride " + std::to_string(stride) + " of bufferView " +
                            std::to_string(a.bufferView) + " is shorter than an element (" + std::to_string(elem) +
                            " bytes)");
        if ((uint64_t)a.byteOffset + (uint64_t)stride * (a.count - 1) + elem > bv.byteLength)
            return fail(L, CG_ERR_GLTF_BUFFER,
                        what + ": " + std::to_string(a.count) + " elements from byte " + std::to_string(a.byteOffset) +
                            " need more than the " + std::to_string(bv.byteLength) + " bytes of bufferView " +
                            std::to_string(a.bufferView));
    }
    std::vector<int> accessor_use(M.accessors.size(), USE_NONE), view_use(M.bufferViews.size(), USE_NONE);
    std::vector<std::vector<int>> view_vertex_accessors(M.bufferViews.size());
    auto use = [&](const std::string &what, int accessor, use_kind kind) {
        const char *names[] = { "", "vertex attribute", "indices", "animation input", "animation output" };
        const char *view_names[] = { "", "vertex attribute", "index", "animation", "animation" };
        int &u = accessor_use[(size_t)accessor];
        if (u != USE_NONE && u != kind)
            return fail(L, CG_ERR_GLTF_ACCESSOR,
                        what + ": accessors[" + std::to_string(accessor) + "] is used as " + names[u] +
                            " elsewhere, and cannot also be " + names[kind]);
        u = kind;
        int view = M.accessors[(size_t)accessor].bufferView;
        if (view < 0)
            return true;
        const tinygltf::BufferView &bv = M.bufferViews[(size_t)view];
        int &vu = view_use[(size_t)view];
        int view_kind = kind == USE_ANIM_OUTPUT ? USE_ANIM_INPUT : kind; // inputs and outputs may share a view
        int declared = bv.target == TINYGLTF_TARGET_ARRAY_BUFFER           ? USE_VERTEX
                       : bv.target == TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER ? USE_INDEX
                                                                           : USE_NONE;
        if ((vu != USE_NONE && vu != view_kind) || (declared != USE_NONE && declared != view_kind))
            return fail(L, CG_ERR_GLTF_BUFFER,
                        what + ": bufferView " + std::to_string(view) + " holds " +
                            view_names[declared != USE_NONE ? declared : vu] + " data and cannot also hold " +
                            view_names[view_kind] + " data");
        vu = view_kind;
        if (kind == USE_INDEX && bv.byteStride)
            return fail(L, CG_ERR_GLTF_BUFFER,
                        what + ": bufferView " + std::to_string(view) + " holds indices and must not have a byteStride");
        if (kind == USE_VERTEX) {
            const tinygltf::Accessor &a = M.accessors[(size_t)accessor];
            if ((bv.byteOffset + a.byteOffset) % 4)
                return fail(L, CG_ERR_GLTF_ACCESSOR,
                            what + ": accessors[" + std::to_string(accessor) +
                                "] starts at a byte that is not a multiple of 4 (vertex data must be 4-byte aligned)");
            auto &list = view_vertex_accessors[(size_t)view];
            if (std::find(list.begin(), list.end(), accessor) == list.end())
                list.push_back(accessor);
            if (list.size() > 1 && !bv.byteStride)
                return fail(L, CG_ERR_GLTF_BUFFER,
                            what + ": bufferView " + std::to_string(view) + " holds accessors " +
                                std::to_string(list[0]) + " and " + std::to_string(accessor) +
                                " of vertex data, so it needs a byteStride");
        }
        return true;
    };
    for (size_t m = 0; m < M.meshes.size(); m++)
        for (size_t p = 0; p < M.meshes[m].primitives.size(); p++) {
            const tinygltf::Primitive &prim = M.meshes[m].primitives[p];
            std::string what = "meshes[" + std::to_string(m) + "].primitives[" + std::to_string(p) + "]";
            size_t count = 0;
            std::string first;
            for (const auto &attr : prim.attributes) {
                const tinygltf::Accessor &a = M.accessors[(size_t)attr.second];
                std::string here = what + ".attributes." + attr.first;
                if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT || !attribute_format_ok(attr.first, a))
                    return fail(L, CG_ERR_GLTF_ACCESSOR,
                                here + ": accessors[" + std::to_string(attr.second) + "] is " + type_name(a.type) +
                                    " of " + (a.normalized ? "normalized " : "") +
                                    component_type_name(a.componentType) +
                                    ", not a format glTF allows for this attribute (glTF 2.0, 3.7.2.1)");
                if (!first.empty() && a.count != count)
                    return fail(L, CG_ERR_GLTF_ACCESSOR,
                                what + ": attribute counts differ (" + first + " has " + std::to_string(count) + ", " +
                                    attr.first + " " + std::to_string(a.count) + ")");
                if (first.empty())
                    first = attr.first, count = a.count;
                if (attr.first == "POSITION" && (a.minValues.size() != 3 || a.maxValues.size() != 3))
                    return fail(L, CG_ERR_GLTF_ACCESSOR,
                                here + ": accessors[" + std::to_string(attr.second) +
                                    "] must declare min and max (glTF 2.0, 3.7.2.1)");
                if (!use(here, attr.second, USE_VERTEX))
                    return false;
            }
            if (prim.indices >= 0) {
                const tinygltf::Accessor &a = M.accessors[(size_t)prim.indices];
                if (a.type != TINYGLTF_TYPE_SCALAR || a.normalized ||
                    (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                     a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                     a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
                    return fail(L, CG_ERR_GLTF_ACCESSOR,
                                what + ".indices: accessors[" + std::to_string(prim.indices) + "] is " +
                                    type_name(a.type) + " of " + component_type_name(a.componentType) +
                                    "; expected SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
                if (!use(what + ".indices", prim.indices, USE_INDEX))
                    return false;
            }
            if (prim.material >= 0) {
                const tinygltf::Material &mat = M.materials[(size_t)prim.material];
                const std::pair<const char *, const tinygltf::TextureInfo *> infos[] = {
                    { "pbrMetallicRoughness.baseColorTexture", &mat.pbrMetallicRoughness.baseColorTexture },
                    { "pbrMetallicRoughness.metallicRoughnessTexture",
                      &mat.pbrMetallicRoughness.metallicRoughnessTexture },
                    { "emissiveTexture", &mat.emissiveTexture },
                };
                std::vector<std::pair<std::string, int>> uses;
                // The set sampled: textureInfo.texCoord, or KHR_texture_transform's override.
                auto set = [](const texture_ref &r) {
                    return r.transform && r.transform->Has("texCoord") && r.transform->Get("texCoord").IsNumber()
                               ? r.transform->Get("texCoord").GetNumberAsInt()
                               : r.texcoord;
                };
                for (const auto &info : infos)
                    if (info.second->index >= 0)
                        uses.push_back({ info.first, set(core_ref(*info.second)) });
                if (mat.normalTexture.index >= 0)
                    uses.push_back({ "normalTexture", set(core_ref(mat.normalTexture)) });
                if (mat.occlusionTexture.index >= 0)
                    uses.push_back({ "occlusionTexture", set(core_ref(mat.occlusionTexture)) });
                if (const tinygltf::Value *t = material_extension(mat, "KHR_materials_transmission")) {
                    texture_ref r = value_ref(*t, "transmissionTexture");
                    if (r.index >= 0)
                        uses.push_back({ "extensions.KHR_materials_transmission.transmissionTexture", set(r) });
                }
                for (const auto &u : uses)
                    if (!prim.attributes.count("TEXCOORD_" + std::to_string(u.second)))
                        return fail(L, CG_ERR_GLTF_ACCESSOR,
                                    what + ": materials[" + std::to_string(prim.material) + "]." + u.first +
                                        " samples TEXCOORD_" + std::to_string(u.second) +
                                        ", which the primitive does not have");
            }
        }
    for (size_t a = 0; a < M.animations.size(); a++)
        for (size_t i = 0; i < M.animations[a].samplers.size(); i++) {
            const tinygltf::AnimationSampler &sm = M.animations[a].samplers[i];
            std::string what = "animations[" + std::to_string(a) + "].samplers[" + std::to_string(i) + "]";
            if (!use(what + ".input", sm.input, USE_ANIM_INPUT) || !use(what + ".output", sm.output, USE_ANIM_OUTPUT))
                return false;
        }
    return true;
}

bool
check_extensions(loader &L)
{
    for (const std::string &e : L.model.extensionsRequired) {
        bool known = false;
        for (const char *s : supported_extensions)
            known = known || e == s;
        std::string list;
        for (const char *s : supported_extensions)
            list += (list.empty() ? "" : ", ") + std::string(s);
        if (!known)
            return fail(L, CG_ERR_GLTF_EXTENSION,
                        "requires extension '" + e + "', which conegraph does not support (supported: " + list + ")");
    }
    return true;
}

bool
scene_roots(loader &L, std::vector<int> *roots)
{
    const auto &M = L.model;
    if (!M.scenes.empty()) {
        int s = M.defaultScene >= 0 ? M.defaultScene : 0;
        if ((size_t)s >= M.scenes.size())
            return fail(L, CG_ERR_GLTF_INDEX_RANGE, "scene " + std::to_string(s) + " does not exist");
        for (int n : M.scenes[(size_t)s].nodes) {
            if (n < 0 || (size_t)n >= M.nodes.size())
                return fail(L, CG_ERR_GLTF_INDEX_RANGE,
                            "scene " + std::to_string(s) + ": node " + std::to_string(n) + " does not exist");
            roots->push_back(n);
        }
        return true;
    }
    // No scene: every node that is nobody's child is a root (glTF leaves this to the loader).
    std::vector<bool> child(M.nodes.size(), false);
    for (const auto &n : M.nodes)
        for (int c : n.children)
            child[(size_t)c] = true;
    for (size_t n = 0; n < M.nodes.size(); n++)
        if (!child[n])
            roots->push_back((int)n);
    return true;
}

uint32_t
le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

// The GLB container (glTF 2.0, 4.4): a 12-byte header (magic, version 2, total length),
// a JSON chunk, then at most one BIN chunk, each chunk's length a multiple of 4. Checked as
// the validator checks it; unknown chunk types after those are skipped, as it allows.
bool
check_glb(loader &L, const unsigned char *data, size_t size, const char **json, size_t *json_size,
          long long *bin_size)
{
    if (size < 12)
        return fail(L, CG_ERR_GLTF_PARSE, "GLB header cut short (" + std::to_string(size) + " of 12 bytes)");
    uint32_t version = le32(data + 4), length = le32(data + 8);
    if (version == 1)
        return fail(L, CG_ERR_GLTF_VERSION, "GLB version 1 (binary glTF 1.0) is not supported (conegraph reads glTF 2.0)");
    if (version != 2)
        return fail(L, CG_ERR_GLTF_PARSE, "GLB version " + std::to_string(version) + " (expected 2)");
    if (length != size)
        return fail(L, CG_ERR_GLTF_PARSE, "GLB header says " + std::to_string(length) + " bytes, the file has " +
                                              std::to_string(size));
    *json = nullptr;
    *bin_size = 0;
    size_t at = 12;
    for (int chunk = 0; at < size; chunk++) {
        if (size - at < 8)
            return fail(L, CG_ERR_GLTF_PARSE, "GLB chunk " + std::to_string(chunk) + ": header cut short");
        uint32_t chunk_length = le32(data + at), type = le32(data + at + 4);
        std::string what = "GLB chunk " + std::to_string(chunk);
        if (chunk_length % 4)
            return fail(L, CG_ERR_GLTF_PARSE, what + ": length " + std::to_string(chunk_length) + " is not a multiple of 4");
        if (chunk_length > size - at - 8)
            return fail(L, CG_ERR_GLTF_PARSE, what + ": length " + std::to_string(chunk_length) + " runs past the end of the file");
        const uint32_t json_type = 0x4E4F534Au, bin_type = 0x004E4942u;
        if (chunk == 0 && type != json_type)
            return fail(L, CG_ERR_GLTF_PARSE, what + ": the first chunk must be JSON");
        if ((type == json_type || type == bin_type) && chunk_length == 0)
            return fail(L, CG_ERR_GLTF_PARSE, what + ": empty chunk");
        if (type == json_type && chunk > 0)
            return fail(L, CG_ERR_GLTF_PARSE, what + ": a second JSON chunk");
        if (type == bin_type) {
            if (chunk != 1)
                return fail(L, CG_ERR_GLTF_PARSE, what + ": the BIN chunk must be the second chunk");
            *bin_size = chunk_length;
        }
        if (type == json_type) {
            *json = (const char *)data + at + 8;
            *json_size = chunk_length;
        }
        at += 8 + (size_t)chunk_length;
    }
    if (!*json)
        return fail(L, CG_ERR_GLTF_PARSE, "GLB without a JSON chunk");
    return true;
}

bool
load(loader &L)
{
    char *data = nullptr;
    size_t size = 0;
    if (!cg_read_file(L.path.c_str(), &data, &size, L.err))
        return false;
    bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    // JSON glTF starts with '{' after white space (a UTF-8 byte order mark is refused by
    // cg_gltf_check_json with its own message).
    size_t first = size >= 3 && std::memcmp(data, "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;
    while (first < size && std::strchr(" \t\r\n", data[first]))
        first++;
    if (!binary && (first >= size || data[first] != '{')) {
        std::free(data);
        return fail(L, CG_ERR_GLTF_PARSE, "not a glTF file (neither JSON nor the binary 'glTF' header)");
    }
    if (size > 0xFFFFFFFFu) {
        std::free(data);
        return fail(L, CG_ERR_GLTF_PARSE, "file larger than 4 GiB");
    }
    // The JSON is checked before tinygltf sees it (gltf_check.c): tinygltf would take a
    // mistyped field for an absent one and give up on a required extension with an
    // unrelated message.
    const char *json = data;
    size_t json_size = size;
    long long bin_size = -1;
    if ((binary && !check_glb(L, (const unsigned char *)data, size, &json, &json_size, &bin_size)) ||
        !cg_gltf_check_json(L.path.c_str(), json, json_size, bin_size, L.err)) {
        std::free(data);
        return false;
    }
    std::string base_dir = ".";
    size_t slash = L.path.find_last_of('/');
    if (slash != std::string::npos)
        base_dir = slash == 0 ? "/" : L.path.substr(0, slash);
    tinygltf::TinyGLTF gltf;
    gltf.SetImageLoader(deferred_image_loader, &L);
    tinygltf::FsCallbacks fs = { &tinygltf::FileExists, &tinygltf::ExpandFilePath, &read_regular_file,
                                 &tinygltf::WriteWholeFile, nullptr };
    gltf.SetFsCallbacks(fs);
    std::string terr, twarn;
    bool ok;
    try {
        if (binary)
            ok = gltf.LoadBinaryFromMemory(&L.model, &terr, &twarn, (const unsigned char *)data,
                                           (unsigned int)size, base_dir);
        else
            ok = gltf.LoadASCIIFromString(&L.model, &terr, &twarn, data, (unsigned int)size, base_dir);
    } catch (const std::exception &e) {
        ok = false;
        terr = e.what();
    }
    std::free(data);
    if (!twarn.empty())
        cg_log_warn("%s: %s", L.path.c_str(), one_line(twarn).c_str());
    if (!ok)
        return fail(L, classify_tinygltf_error(terr), one_line(terr.empty() ? "tinygltf failed without a message" : terr));
    if (L.progress)
        cg_progress_update(L.progress, CG_LOAD_PARSED);
    L.mesh_map.assign(L.model.meshes.size(), {});
    L.mesh_done.assign(L.model.meshes.size(), false);
    std::vector<int> roots;
    ok = check_extensions(L) && check_model(L) && convert_textures(L) && convert_materials(L) &&
              check_node_graph(L) && read_animations(L) && mark_joints(L) && scene_roots(L, &roots) &&
              visit_nodes(L, roots) && finish_skins(L) && finish_morphs(L) && finish_animations(L);
    if (ok) {
        report_left_out(L);
        report_morph_targets(L);
    }
    return ok;
}

// ------------------------------------------------------------------ export

size_t
append_bytes(std::vector<unsigned char> &buf, const void *data, size_t size)
{
    while (buf.size() % 4)
        buf.push_back(0);
    size_t offset = buf.size();
    buf.insert(buf.end(), (const unsigned char *)data, (const unsigned char *)data + size);
    return offset;
}

int
add_accessor(tinygltf::Model &M, const void *data, size_t count, int type, int component_type, int target,
             const float *min = nullptr, const float *max = nullptr)
{
    size_t elem = component_size(component_type) * (size_t)component_count(type);
    tinygltf::BufferView bv;
    bv.buffer = 0;
    bv.byteLength = count * elem;
    bv.byteOffset = append_bytes(M.buffers[0].data, data, bv.byteLength);
    bv.target = target;
    M.bufferViews.push_back(bv);
    tinygltf::Accessor a;
    a.bufferView = (int)M.bufferViews.size() - 1;
    a.byteOffset = 0;
    a.componentType = component_type;
    a.type = type;
    a.count = count;
    if (min && max) {
        a.minValues.assign(min, min + component_count(type));
        a.maxValues.assign(max, max + component_count(type));
    }
    M.accessors.push_back(a);
    return (int)M.accessors.size() - 1;
}

// Unit quaternion (x, y, z, w) turning -Z onto the unit vector d (the light's direction).
void
quat_from_minus_z(const float d[3], std::vector<double> *q)
{
    double c = -d[2]; // dot((0, 0, -1), d)
    if (c < -0.999999) {
        *q = { 0, 1, 0, 0 }; // d = +Z: half a turn about Y
        return;
    }
    // axis = (0, 0, -1) x d, w = 1 + c, normalised (half-angle form).
    double x = d[1], y = -d[0], z = 0, w = 1 + c;
    double len = std::sqrt(x * x + y * y + z * z + w * w);
    *q = { x / len, y / len, z / len, w / len };
}

// KHR_texture_transform of a cg_uv_transform (uv_transform_of's inverse): scale, rotation
// and offset of A = R(r) S; a matrix with shear (no file gives one) keeps the nearest such.
tinygltf::Value
texture_transform_value(const cg_uv_transform &t)
{
    double sx = std::hypot(t.m[0], t.m[1]);
    double r = sx > 0 ? std::atan2(-t.m[1], t.m[0]) : std::atan2(t.m[2], t.m[3]);
    double c = std::cos(r), s = std::sin(r);
    double sy = sx > 0 ? t.m[2] * s + t.m[3] * c : std::hypot(t.m[2], t.m[3]);
    tinygltf::Value::Object o;
    if (t.m[4] != 0 || t.m[5] != 0)
        o["offset"] = tinygltf::Value(tinygltf::Value::Array{ tinygltf::Value((double)t.m[4]),
                                                              tinygltf::Value((double)t.m[5]) });
    if (r != 0)
        o["rotation"] = tinygltf::Value(r);
    if (sx != 1 || sy != 1)
        o["scale"] = tinygltf::Value(tinygltf::Value::Array{ tinygltf::Value(sx), tinygltf::Value(sy) });
    return tinygltf::Value(o);
}

bool
is_identity_uv(const cg_uv_transform &t)
{
    cg_uv_transform id = cg_uv_transform_identity();
    return std::memcmp(t.m, id.m, sizeof t.m) == 0;
}

// Every material, in order, so that indices stay: material 0 too, marked with extras
// "conegraph_material_0" so that the loader takes it as its material 0 (instead of glTF's
// default material, which a built-in scene's Lambertian material 0 is not). Each field is
// written where it differs from glTF's default, an extension where one of its fields does
// (its name added to `used`). A texture index outside the scene's textures is left out.
void
export_materials(const cg_scene *S, tinygltf::Model &M, std::vector<std::string> *used)
{
    auto use = [&](const char *name) {
        if (std::find(used->begin(), used->end(), name) == used->end())
            used->push_back(name);
    };
    auto valid = [&](int t) { return t >= 0 && t < S->texture_count; };
    auto transform = [&](const cg_material &c, int slot, tinygltf::ExtensionMap *ext) {
        if (is_identity_uv(c.uv[slot]))
            return;
        (*ext)["KHR_texture_transform"] = texture_transform_value(c.uv[slot]);
        use("KHR_texture_transform");
    };
    for (int i = 0; i < S->material_count; i++) {
        const cg_material &c = S->materials[i];
        tinygltf::Material m;
        m.name = c.name;
        if (i == 0) {
            tinygltf::Value::Object extras;
            extras["conegraph_material_0"] = tinygltf::Value(true);
            m.extras = tinygltf::Value(extras);
        }
        auto &pbr = m.pbrMetallicRoughness;
        pbr.baseColorFactor = { c.base_color[0], c.base_color[1], c.base_color[2], c.base_color[3] };
        pbr.metallicFactor = c.metallic;
        pbr.roughnessFactor = c.roughness;
        if (valid(c.base_color_texture)) {
            pbr.baseColorTexture.index = c.base_color_texture;
            transform(c, CG_TEX_BASE_COLOR, &pbr.baseColorTexture.extensions);
        }
        if (valid(c.metallic_roughness_texture)) {
            pbr.metallicRoughnessTexture.index = c.metallic_roughness_texture;
            transform(c, CG_TEX_METALLIC_ROUGHNESS, &pbr.metallicRoughnessTexture.extensions);
        }
        if (valid(c.emissive_texture)) {
            m.emissiveTexture.index = c.emissive_texture;
            transform(c, CG_TEX_EMISSIVE, &m.emissiveTexture.extensions);
        }
        if (valid(c.normal_texture)) {
            m.normalTexture.index = c.normal_texture;
            m.normalTexture.scale = c.normal_scale;
            transform(c, CG_TEX_NORMAL, &m.normalTexture.extensions);
        }
        if (valid(c.occlusion_texture)) {
            m.occlusionTexture.index = c.occlusion_texture;
            m.occlusionTexture.strength = c.occlusion_strength;
            transform(c, CG_TEX_OCCLUSION, &m.occlusionTexture.extensions);
        }
        m.alphaMode = c.alpha_mode == CG_ALPHA_MASK ? "MASK" : c.alpha_mode == CG_ALPHA_BLEND ? "BLEND" : "OPAQUE";
        if (c.alpha_mode == CG_ALPHA_MASK)
            m.alphaCutoff = c.alpha_cutoff;
        m.doubleSided = c.double_sided;
        // glTF keeps emissiveFactor in [0, 1]; anything brighter moves into the strength.
        double peak = std::fmax(c.emissive[0], std::fmax(c.emissive[1], c.emissive[2]));
        double scale = peak > 1 ? peak : 1;
        m.emissiveFactor = { c.emissive[0] / scale, c.emissive[1] / scale, c.emissive[2] / scale };
        double strength = (double)c.emissive_strength * scale;
        if (strength != 1) {
            tinygltf::Value::Object o;
            o["emissiveStrength"] = tinygltf::Value(strength);
            m.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(o);
            use("KHR_materials_emissive_strength");
        }
        if (c.ior != 1.5f && (c.ior == 0 || c.ior >= 1)) {
            tinygltf::Value::Object o;
            o["ior"] = tinygltf::Value((double)c.ior);
            m.extensions["KHR_materials_ior"] = tinygltf::Value(o);
            use("KHR_materials_ior");
        }
        if (c.specular != 1 || c.specular_color[0] != 1 || c.specular_color[1] != 1 || c.specular_color[2] != 1) {
            tinygltf::Value::Object o;
            if (c.specular != 1)
                o["specularFactor"] = tinygltf::Value((double)c.specular);
            if (c.specular_color[0] != 1 || c.specular_color[1] != 1 || c.specular_color[2] != 1)
                o["specularColorFactor"] = tinygltf::Value(tinygltf::Value::Array{
                    tinygltf::Value((double)c.specular_color[0]), tinygltf::Value((double)c.specular_color[1]),
                    tinygltf::Value((double)c.specular_color[2]) });
            m.extensions["KHR_materials_specular"] = tinygltf::Value(o);
            use("KHR_materials_specular");
        }
        if (c.transmission != 0 || valid(c.transmission_texture)) {
            tinygltf::Value::Object o;
            if (c.transmission != 0)
                o["transmissionFactor"] = tinygltf::Value((double)c.transmission);
            if (valid(c.transmission_texture)) {
                tinygltf::Value::Object info;
                info["index"] = tinygltf::Value(c.transmission_texture);
                if (!is_identity_uv(c.uv[CG_TEX_TRANSMISSION])) {
                    tinygltf::Value::Object ext;
                    ext["KHR_texture_transform"] = texture_transform_value(c.uv[CG_TEX_TRANSMISSION]);
                    info["extensions"] = tinygltf::Value(ext);
                    use("KHR_texture_transform");
                }
                o["transmissionTexture"] = tinygltf::Value(info);
            }
            m.extensions["KHR_materials_transmission"] = tinygltf::Value(o);
            use("KHR_materials_transmission");
        }
        bool attenuates = c.attenuation_distance > 0 && std::isfinite(c.attenuation_distance);
        bool tinted = c.attenuation_color[0] != 1 || c.attenuation_color[1] != 1 || c.attenuation_color[2] != 1;
        if (c.thickness > 0 || attenuates || tinted) {
            tinygltf::Value::Object o;
            if (c.thickness > 0)
                o["thicknessFactor"] = tinygltf::Value((double)c.thickness);
            if (attenuates)
                o["attenuationDistance"] = tinygltf::Value((double)c.attenuation_distance);
            if (tinted)
                o["attenuationColor"] = tinygltf::Value(tinygltf::Value::Array{
                    tinygltf::Value((double)c.attenuation_color[0]), tinygltf::Value((double)c.attenuation_color[1]),
                    tinygltf::Value((double)c.attenuation_color[2]) });
            m.extensions["KHR_materials_volume"] = tinygltf::Value(o);
            use("KHR_materials_volume");
        }
        M.materials.push_back(m);
    }
}

void
export_textures(const cg_scene *S, tinygltf::Model &M)
{
    for (int i = 0; i < S->texture_count; i++) {
        const cg_texture &t = S->textures[i];
        tinygltf::Image img;
        img.name = t.name[0] ? t.name : "texture" + std::to_string(i);
        for (char &ch : img.name)
            if (!std::isalnum((unsigned char)ch) && ch != '_' && ch != '-')
                ch = '_';
        img.width = t.width;
        img.height = t.height;
        img.component = 4;
        img.bits = 8;
        img.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
        img.mimeType = "image/png";
        size_t row = (size_t)t.width * 4;
        img.image.resize(row * (size_t)t.height);
        std::memcpy(img.image.data(), t.rgba, row * (size_t)t.height); // both top to bottom
        M.images.push_back(img);
        tinygltf::Texture tex;
        tex.name = t.name;
        tex.source = i;
        M.textures.push_back(tex);
    }
}

void
export_meshes(const cg_scene *S, tinygltf::Model &M)
{
    for (int i = 0; i < S->mesh_count; i++) {
        const cg_mesh &c = S->meshes[i];
        tinygltf::Primitive p;
        p.mode = TINYGLTF_MODE_TRIANGLES;
        p.material = c.material; // every material is written, 0 included (export_materials)
        p.attributes["POSITION"] = add_accessor(M, c.positions, c.vertex_count, TINYGLTF_TYPE_VEC3,
                                                TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER,
                                                c.bounds_min, c.bounds_max);
        p.attributes["NORMAL"] = add_accessor(M, c.normals, c.vertex_count, TINYGLTF_TYPE_VEC3,
                                              TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
        if (c.texcoords)
            p.attributes["TEXCOORD_0"] = add_accessor(M, c.texcoords, c.vertex_count, TINYGLTF_TYPE_VEC2,
                                                      TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
        if (c.tangents)
            p.attributes["TANGENT"] = add_accessor(M, c.tangents, c.vertex_count, TINYGLTF_TYPE_VEC4,
                                                   TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
        p.indices = add_accessor(M, c.indices, c.index_count, TINYGLTF_TYPE_SCALAR,
                                 TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        tinygltf::Mesh m;
        m.name = c.name;
        m.primitives.push_back(p);
        tinygltf::Value::Object extras;
        extras["conegraph_kind"] =
            tinygltf::Value(std::string(c.kind == CG_MESH_HEIGHTFIELD ? "heightfield" : "complex"));
        m.extras = tinygltf::Value(extras);
        M.meshes.push_back(m);
    }
}

// A node holding light i of M.lights (KHR_lights_punctual), with no transform of its own.
tinygltf::Node
light_node(int i, const char *name)
{
    tinygltf::Node n;
    n.name = name;
    tinygltf::Value::Object ext;
    ext["light"] = tinygltf::Value(i);
    n.extensions["KHR_lights_punctual"] = tinygltf::Value(ext);
    return n;
}

// Static instances, lights and cameras as root nodes with their world transforms; the kept
// node hierarchy as nodes with their local transforms (nodes.size() onwards, in cg order),
// and what follows a node as a child of it with no transform of its own, so that it loads
// back attached to the same node. Returns the glTF index of cg node 0.
int
export_nodes(const cg_scene *S, tinygltf::Model &M)
{
    tinygltf::Scene scene;
    scene.name = S->name;
    std::vector<int> instance_node((size_t)S->instance_count, -1), light_node_of((size_t)S->light_count, -1),
        camera_node((size_t)S->camera_count, -1);
    for (int i = 0; i < S->attachment_count; i++) {
        const cg_attachment &a = S->attachments[i];
        std::vector<int> &on = a.kind == CG_ATTACH_INSTANCE ? instance_node
                               : a.kind == CG_ATTACH_LIGHT  ? light_node_of
                                                            : camera_node;
        on[(size_t)a.index] = a.node;
    }
    for (int i = 0; i < S->instance_count; i++) {
        if (instance_node[(size_t)i] >= 0)
            continue;
        tinygltf::Node n;
        n.mesh = S->instances[i].mesh;
        n.matrix.assign(S->instances[i].world, S->instances[i].world + 16);
        scene.nodes.push_back((int)M.nodes.size());
        M.nodes.push_back(n);
    }
    for (int i = 0; i < S->light_count; i++) {
        const cg_light &c = S->lights[i];
        tinygltf::Light l;
        l.name = c.name;
        l.type = c.type == CG_LIGHT_DIRECTIONAL ? "directional" : c.type == CG_LIGHT_POINT ? "point" : "spot";
        l.color = { c.color[0], c.color[1], c.color[2] };
        l.intensity = c.intensity;
        l.range = c.range;
        if (c.type == CG_LIGHT_SPOT) {
            l.spot.innerConeAngle = c.inner_cone_angle;
            l.spot.outerConeAngle = c.outer_cone_angle;
        }
        if (c.type == CG_LIGHT_DIRECTIONAL && c.angular_diameter != 0) {
            tinygltf::Value::Object extras;
            extras["conegraph_angular_diameter"] = tinygltf::Value((double)c.angular_diameter);
            l.extras = tinygltf::Value(extras);
        }
        M.lights.push_back(l);
        if (light_node_of[(size_t)i] >= 0)
            continue;
        tinygltf::Node n = light_node(i, c.name);
        n.translation = { c.position[0], c.position[1], c.position[2] };
        quat_from_minus_z(c.direction, &n.rotation);
        scene.nodes.push_back((int)M.nodes.size());
        M.nodes.push_back(n);
    }
    for (int i = 0; i < S->camera_count; i++) {
        const cg_camera &c = S->cameras[i];
        tinygltf::Camera cam;
        cam.name = c.name;
        if (c.type == CG_CAMERA_ORTHOGRAPHIC) {
            cam.type = "orthographic";
            cam.orthographic.xmag = c.xmag;
            cam.orthographic.ymag = c.ymag;
            cam.orthographic.znear = c.znear;
            cam.orthographic.zfar = c.zfar;
        } else {
            cam.type = "perspective";
            cam.perspective.yfov = c.yfov;
            cam.perspective.aspectRatio = c.aspect; // 0 is left out: the image decides
            cam.perspective.znear = c.znear;
            cam.perspective.zfar = c.zfar;
        }
        M.cameras.push_back(cam);
        if (camera_node[(size_t)i] >= 0)
            continue;
        tinygltf::Node n;
        n.name = c.name;
        n.camera = i;
        n.matrix.assign(c.world, c.world + 16);
        scene.nodes.push_back((int)M.nodes.size());
        M.nodes.push_back(n);
    }
    int base = (int)M.nodes.size();
    for (int i = 0; i < S->node_count; i++) {
        const cg_node &c = S->nodes[i];
        tinygltf::Node n;
        n.name = c.name;
        if (c.has_matrix) {
            n.matrix.assign(c.matrix, c.matrix + 16);
        } else {
            if (c.translation[0] != 0 || c.translation[1] != 0 || c.translation[2] != 0)
                n.translation.assign(c.translation, c.translation + 3);
            if (c.rotation[0] != 0 || c.rotation[1] != 0 || c.rotation[2] != 0 || c.rotation[3] != 1)
                n.rotation.assign(c.rotation, c.rotation + 4);
            if (c.scale[0] != 1 || c.scale[1] != 1 || c.scale[2] != 1)
                n.scale.assign(c.scale, c.scale + 3);
        }
        M.nodes.push_back(n);
        if (c.parent < 0)
            scene.nodes.push_back(base + i);
        else
            M.nodes[(size_t)(base + c.parent)].children.push_back(base + i);
    }
    for (int i = 0; i < S->attachment_count; i++) {
        const cg_attachment &a = S->attachments[i];
        tinygltf::Node n;
        if (a.kind == CG_ATTACH_INSTANCE) {
            n.mesh = S->instances[a.index].mesh;
        } else if (a.kind == CG_ATTACH_LIGHT) {
            n = light_node(a.index, S->lights[a.index].name);
        } else {
            n.name = S->cameras[a.index].name;
            n.camera = a.index;
        }
        M.nodes[(size_t)(base + a.node)].children.push_back((int)M.nodes.size());
        M.nodes.push_back(n);
    }
    M.scenes.push_back(scene);
    M.defaultScene = 0;
    return base;
}

// Each channel as a sampler of its own: key times (SCALAR, with the min and max glTF asks
// of an input) and values, in bufferViews without target or stride.
void
export_animations(const cg_scene *S, tinygltf::Model &M, int node_base)
{
    static const char *const paths[] = { "translation", "rotation", "scale" };
    static const char *const modes[] = { "LINEAR", "STEP", "CUBICSPLINE" };
    for (int a = 0; a < S->animation_count; a++) {
        const cg_animation &anim = S->animations[a];
        tinygltf::Animation out;
        out.name = anim.name;
        for (int c = 0; c < anim.channel_count; c++) {
            const cg_anim_channel &ch = anim.channels[c];
            if (ch.path == CG_ANIM_WEIGHTS) // the morphed mesh is written as posed
                continue;
            size_t keys = (size_t)ch.key_count, per_key = ch.interpolation == CG_INTERP_CUBICSPLINE ? 3 : 1;
            tinygltf::AnimationSampler sampler;
            sampler.input = add_accessor(M, ch.times, keys, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_FLOAT, 0,
                                         &ch.times[0], &ch.times[keys - 1]);
            sampler.output = add_accessor(M, ch.values, keys * per_key,
                                          ch.path == CG_ANIM_ROTATION ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3,
                                          TINYGLTF_COMPONENT_TYPE_FLOAT, 0);
            sampler.interpolation = modes[ch.interpolation];
            tinygltf::AnimationChannel channel;
            channel.sampler = (int)out.samplers.size();
            channel.target_node = node_base + ch.node;
            channel.target_path = paths[ch.path];
            out.samplers.push_back(sampler);
            out.channels.push_back(channel);
        }
        if (!out.channels.empty())
            M.animations.push_back(out);
    }
}

bool
ends_with(const std::string &s, const char *suffix)
{
    size_t n = std::strlen(suffix);
    if (s.size() < n)
        return false;
    for (size_t i = 0; i < n; i++)
        if (std::tolower((unsigned char)s[s.size() - n + i]) != suffix[i])
            return false;
    return true;
}

// tinygltf writes "zfar": 0 for a perspective camera without a far plane, where glTF asks
// for the member to be left out (and validators reject 0): the JSON tinygltf wrote is
// edited here, through jansson, before it goes to the file.
bool
drop_infinite_zfar(std::string *json_text, bool pretty)
{
    json_error_t jerr;
    json_t *root = json_loadb(json_text->data(), json_text->size(), 0, &jerr);
    if (!root)
        return false;
    json_t *cameras = json_object_get(root, "cameras");
    for (size_t i = 0; i < json_array_size(cameras); i++) {
        json_t *p = json_object_get(json_array_get(cameras, i), "perspective");
        json_t *zfar = json_object_get(p, "zfar");
        if (zfar && json_number_value(zfar) == 0)
            json_object_del(p, "zfar");
    }
    char *text = json_dumps(root, (pretty ? JSON_INDENT(2) : JSON_COMPACT) | JSON_REAL_PRECISION(17));
    json_decref(root);
    if (!text)
        return false;
    *json_text = text;
    std::free(text);
    return true;
}

// The same for a .glb from tinygltf: its JSON chunk edited, the container rebuilt.
bool
drop_infinite_zfar_glb(std::string *glb)
{
    const unsigned char *p = (const unsigned char *)glb->data();
    if (glb->size() < 20)
        return false;
    uint32_t json_length = le32(p + 12);
    if (json_length > glb->size() - 20)
        return false;
    std::string json(glb->data() + 20, json_length), rest(glb->data() + 20 + json_length, glb->size() - 20 - json_length);
    if (!drop_infinite_zfar(&json, false))
        return false;
    while (json.size() % 4)
        json += ' ';
    auto put32 = [](std::string &s, uint32_t v) {
        for (int i = 0; i < 4; i++)
            s += (char)(v >> (8 * i) & 0xFF);
    };
    std::string out = "glTF";
    put32(out, 2);
    put32(out, (uint32_t)(12 + 8 + json.size() + rest.size()));
    put32(out, (uint32_t)json.size());
    put32(out, 0x4E4F534Au);
    out += json;
    out += rest;
    *glb = std::move(out);
    return true;
}

} // namespace

extern "C" bool
cg_scene_export_gltf(const cg_scene *scene, const char *path, cg_error *err)
{
    std::string out = path;
    bool binary = ends_with(out, ".glb");
    if (!binary && !ends_with(out, ".gltf"))
        return cg_fail(err, CG_ERR_USAGE, "%s: the output must end in .gltf or .glb", path);
    std::string bytes;
    try {
        tinygltf::Model M;
        M.asset.version = "2.0";
        M.asset.generator = "conegraph";
        M.buffers.resize(1);
        std::vector<std::string> used;
        export_materials(scene, M, &used);
        export_textures(scene, M);
        export_meshes(scene, M);
        export_animations(scene, M, export_nodes(scene, M));
        if (!M.lights.empty())
            M.extensionsUsed.push_back("KHR_lights_punctual");
        M.extensionsUsed.insert(M.extensionsUsed.end(), used.begin(), used.end());
        tinygltf::TinyGLTF gltf;
        std::ostringstream stream;
        if (!gltf.WriteGltfSceneToStream(&M, stream, !binary, binary))
            return cg_fail(err, CG_ERR_IO, "%s: writing the glTF failed", path);
        bytes = stream.str();
        if (!(binary ? drop_infinite_zfar_glb(&bytes) : drop_infinite_zfar(&bytes, true)))
            return cg_fail(err, CG_ERR_IO, "%s: tinygltf wrote a glTF that cannot be read back", path);
    } catch (const std::bad_alloc &) {
        return cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory writing the glTF", path);
    } catch (const std::exception &e) {
        return cg_fail(err, CG_ERR_IO, "%s: %s", path, e.what());
    }
    // Written to a temporary file beside the target and renamed into place (cg/fs.h).
    cg_atomic_file f;
    if (!cg_atomic_open(&f, path, err))
        return false;
    if (std::fwrite(bytes.data(), 1, bytes.size(), f.fp) != bytes.size()) {
        int e = errno;
        cg_atomic_abort(&f);
        return cg_fail(err, CG_ERR_IO, "%s: write failed: %s", path, std::strerror(e));
    }
    return cg_atomic_commit(&f, err);
}

extern "C" bool
cg_gltf_load(const char *path, cg_scene *out, cg_progress *progress, cg_error *err)
{
    std::memset(out, 0, sizeof *out);
    std::snprintf(out->name, sizeof out->name, "%s", path);
    // glTF's default material (spec 5.19) for primitives without one.
    cg_material white = cg_material_gltf_default("default");
    if (cg_scene_add_material(out, &white, err) < 0)
        return false;
    bool ok;
    try {
        loader L;
        L.path = path;
        L.progress = progress;
        L.scene = out;
        L.err = err;
        ok = load(L);
        // cg_scene_load classifies the meshes that carry no kind of their own.
        for (int m = 0; ok && m < out->mesh_count; m++) {
            int k = L.explicit_kind[(size_t)m];
            out->meshes[m].kind = k >= 0 ? (cg_mesh_kind)k : CG_MESH_COMPLEX;
            ok = cg_scene_set_kind_source(out, m, k >= 0 ? CG_KIND_EXTRAS : CG_KIND_CLASSIFIED, err);
        }
    } catch (const std::bad_alloc &) {
        ok = cg_fail(err, CG_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    } catch (const std::exception &e) {
        ok = cg_fail(err, CG_ERR_GLTF_PARSE, "%s: %s", path, e.what());
    }
    if (!ok)
        cg_scene_free(out);
    return ok;
}
