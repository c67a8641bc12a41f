#include "importer.h"

#include "detmath.h"

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace msr {

namespace {

bool finite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

Vec3 clamp_albedo(Vec3 c) {
    // Energy conservation: no surface reflects more than 90 % (keeps tone mapping sane).
    for (int i = 0; i < 3; ++i) c[i] = std::fmin(0.9f, std::fmax(0.f, std::isfinite(c[i]) ? c[i] : 0.f));
    return c;
}

Material convert_material(const aiMaterial *am) {
    aiColor4D c;
    Vec3 base{0.75f, 0.75f, 0.75f};
    if (aiGetMaterialColor(am, AI_MATKEY_BASE_COLOR, &c) == AI_SUCCESS ||
        aiGetMaterialColor(am, AI_MATKEY_COLOR_DIFFUSE, &c) == AI_SUCCESS)
        base = {c.r, c.g, c.b};
    // A textured material often leaves its constant colour black or white: without texture
    // sampling a light grey reads better than a black hole.
    bool textured = am->GetTextureCount(aiTextureType_DIFFUSE) > 0 || am->GetTextureCount(aiTextureType_BASE_COLOR) > 0;
    if (textured && max_component(base) < 0.05f) base = {0.75f, 0.75f, 0.75f};
    base = clamp_albedo(base);

    ai_real f = 0;
    float transmission = 0.f, opacity = 1.f, metallic = 0.f, roughness = 1.f, ior = 1.5f, emi_scale = 1.f;
    if (aiGetMaterialFloat(am, AI_MATKEY_TRANSMISSION_FACTOR, &f) == AI_SUCCESS) transmission = float(f);
    if (aiGetMaterialFloat(am, AI_MATKEY_OPACITY, &f) == AI_SUCCESS) opacity = float(f);
    if (aiGetMaterialFloat(am, AI_MATKEY_METALLIC_FACTOR, &f) == AI_SUCCESS) metallic = float(f);
    if (aiGetMaterialFloat(am, AI_MATKEY_ROUGHNESS_FACTOR, &f) == AI_SUCCESS) roughness = float(f);
    if (aiGetMaterialFloat(am, AI_MATKEY_REFRACTI, &f) == AI_SUCCESS && f >= 1.f && f <= 3.f) ior = float(f);
    if (aiGetMaterialFloat(am, AI_MATKEY_EMISSIVE_INTENSITY, &f) == AI_SUCCESS && f > 0.f) emi_scale = float(f);

    if (aiGetMaterialColor(am, AI_MATKEY_COLOR_EMISSIVE, &c) == AI_SUCCESS) {
        Vec3 e = Vec3{c.r, c.g, c.b} * emi_scale;
        if (finite(e) && max_component(e) > 0.1f) return Material::emissive(e);
    }
    if (transmission > 0.5f || (opacity > 0.f && opacity < 0.5f)) {
        Vec3 tint = base * 0.3f + Vec3{0.7f, 0.7f, 0.7f};  // keep glass light
        return Material::glass(tint, ior);
    }
    if (metallic >= 0.9f && roughness <= 0.2f) return Material::mirror(base * 0.8f + Vec3{0.15f, 0.15f, 0.15f});
    return Material::diffuse(base);
}

// Formats whose header declares element counts (OFF, PLY) make assimp 5.2 allocate and loop
// over whatever the header says: a 300-byte file claiming 10^9 vertices eats gigabytes and
// minutes. Every element takes at least one byte, so a count beyond the file size is a lie.
bool plausible_counts(const std::string &path, std::string &err) {
    std::ifstream f(path, std::ios::binary);
    std::error_code ec;
    const unsigned long long size = std::filesystem::file_size(path, ec);
    if (!f || ec) return true;  // the importer reports unreadable files itself
    std::string head(65536, '\0');
    f.read(&head[0], std::streamsize(head.size()));
    head.resize(size_t(f.gcount()));
    std::istringstream in(head);
    std::string line;
    unsigned long long total = 0;
    bool overflow = false;
    auto add = [&](const std::string &tok) {
        errno = 0;
        char *end = nullptr;
        unsigned long long v = std::strtoull(tok.c_str(), &end, 10);
        if (errno == ERANGE || tok.empty() || tok[0] == '-' || *end != '\0') { overflow = overflow || errno == ERANGE; return; }
        if (total + v < total) overflow = true;
        total += v;
    };
    if (!std::getline(in, line)) return true;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.rfind("ply", 0) == 0) {
        while (std::getline(in, line)) {
            std::istringstream ls(line);
            std::string kw, name, count;
            ls >> kw;
            if (kw == "end_header") break;
            if (kw == "element" && (ls >> name >> count)) add(count);
        }
    } else if (line.find("OFF") != std::string::npos && line.size() < 8) {
        while (std::getline(in, line)) {  // first line that is not a comment: nv nf ne
            std::istringstream ls(line);
            std::string a, b;
            if (!(ls >> a) || a[0] == '#') continue;
            add(a);
            if (ls >> b) add(b);
            break;
        }
    } else {
        return true;
    }
    if (overflow || total > size) {
        err = "model file " + path + " is malformed: its header declares " +
              (overflow ? std::string("more than 2^64") : std::to_string(total)) + " elements in " +
              std::to_string(size) + " bytes";
        return false;
    }
    return true;
}

}  // namespace

bool load_model(const std::string &path, Model &out, std::string &err) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(path, ec)) { err = "cannot read model file " + path + ": no such file"; return false; }
    if (!fs::is_regular_file(path, ec)) { err = "cannot read model file " + path + ": not a regular file"; return false; }

    if (!plausible_counts(path, err)) return false;

    Assimp::Importer imp;
    // Points and lines are dropped; degenerate triangles removed.
    imp.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    imp.SetPropertyBool(AI_CONFIG_PP_FD_REMOVE, true);
    imp.SetPropertyFloat(AI_CONFIG_PP_GSN_MAX_SMOOTHING_ANGLE, 60.f);
    const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType |
                           aiProcess_FindDegenerates | aiProcess_GenSmoothNormals | aiProcess_PreTransformVertices |
                           aiProcess_ValidateDataStructure;
    const aiScene *sc = imp.ReadFile(path, flags);
    if (!sc) {
        std::string why = imp.GetErrorString();
        for (char &ch : why)
            if (ch == '\n' || ch == '\r') ch = ' ';
        // Files that parse but hold only points, lines or nothing fail in post-processing.
        for (const char *empty : {"No meshes remaining", "contains no faces", "mNumMeshes is 0"})
            if (why.find(empty) != std::string::npos) {
                err = "model file " + path + " holds no triangles (assimp: " + why + ")";
                return false;
            }
        err = "cannot read model file " + path + ": " + (why.empty() ? "unknown importer error" : why);
        return false;
    }

    out = Model{};
    for (unsigned i = 0; i < sc->mNumMaterials; ++i) out.materials.push_back(convert_material(sc->mMaterials[i]));
    if (out.materials.empty()) out.materials.push_back(Material::diffuse({0.75f, 0.75f, 0.75f}));

    for (unsigned mi = 0; mi < sc->mNumMeshes; ++mi) {
        const aiMesh *am = sc->mMeshes[mi];
        if (!(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || !am->mVertices) continue;
        Mesh m;
        m.material = am->mMaterialIndex < out.materials.size() ? int(am->mMaterialIndex) : 0;
        m.pos.resize(am->mNumVertices);
        for (unsigned v = 0; v < am->mNumVertices; ++v) m.pos[v] = {am->mVertices[v].x, am->mVertices[v].y, am->mVertices[v].z};
        if (am->mNormals) {
            m.nrm.resize(am->mNumVertices);
            for (unsigned v = 0; v < am->mNumVertices; ++v) m.nrm[v] = {am->mNormals[v].x, am->mNormals[v].y, am->mNormals[v].z};
        }
        if (am->mColors[0]) {
            m.col.resize(am->mNumVertices);
            for (unsigned v = 0; v < am->mNumVertices; ++v)
                m.col[v] = clamp_albedo({am->mColors[0][v].r, am->mColors[0][v].g, am->mColors[0][v].b}) / 0.9f;
        }
        for (unsigned f = 0; f < am->mNumFaces; ++f) {
            const aiFace &face = am->mFaces[f];
            if (face.mNumIndices != 3) continue;
            bool ok = true;
            for (int k = 0; k < 3; ++k) ok = ok && face.mIndices[k] < am->mNumVertices && finite(m.pos[face.mIndices[k]]);
            if (!ok) continue;
            m.idx.insert(m.idx.end(), {face.mIndices[0], face.mIndices[1], face.mIndices[2]});
        }
        if (m.idx.empty()) continue;
        for (uint32_t i : m.idx) out.bounds.add(m.pos[i]);
        out.triangles += m.idx.size() / 3;
        out.meshes.push_back(std::move(m));
    }
    if (out.triangles == 0) { err = "model file " + path + " holds no triangles"; return false; }
    Vec3 s = out.bounds.size();
    if (!(max_component(s) > 0.f)) { err = "model file " + path + " has zero size"; return false; }
    return true;
}

void add_model(Scene &scene, const Model &model, Vec3 pivot, float scale, float yaw_deg, Vec3 offset) {
    double sd, cd;
    det_sincos_deg(yaw_deg, sd, cd);
    const float cs = float(cd), sn = float(sd);
    auto rot = [&](Vec3 v) { return Vec3{cs * v.x + sn * v.z, v.y, -sn * v.x + cs * v.z}; };
    std::vector<int> mat_map;
    for (const Material &m : model.materials) mat_map.push_back(scene.add_material(m));
    for (const Mesh &src : model.meshes) {
        Mesh m = src;
        m.material = mat_map[size_t(src.material)];
        for (Vec3 &p : m.pos) p = rot(p - pivot) * scale + offset;
        for (Vec3 &n : m.nrm) n = rot(n);
        scene.add_mesh(std::move(m));
    }
}

}  // namespace msr
