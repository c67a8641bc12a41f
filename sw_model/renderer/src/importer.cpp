#include "importer.h"

#include "detmath.h"

#include <algorithm>
#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <map>
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

// Material colours and factors (textures are attached by load_model). `map_loaded`: the
// diffuse map was found and decoded.
Material convert_material(const aiMaterial *am, bool textured, bool map_loaded) {
    aiColor4D c;
    Vec3 base{0.75f, 0.75f, 0.75f};
    if (aiGetMaterialColor(am, AI_MATKEY_BASE_COLOR, &c) == AI_SUCCESS ||
        aiGetMaterialColor(am, AI_MATKEY_COLOR_DIFFUSE, &c) == AI_SUCCESS)
        base = {c.r, c.g, c.b};
    // A textured material often leaves its constant colour black: the map alone then gives
    // the colour (and a light grey when the map is missing, rather than a black hole).
    if (textured && max_component(base) < 0.05f) base = {1.f, 1.f, 1.f};
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
        // A mapped surface glowing more faintly than it reflects is a self-illumination term
        // (Milkshape writes 0.35 grey into every material), not a lamp: it keeps its map.
        const bool faint_glow = map_loaded && max_component(e) <= max_component(base);
        if (finite(e) && max_component(e) > 0.1f && !faint_glow) return Material::emissive(e);
    }
    if (transmission > 0.5f || (opacity > 0.f && opacity < 0.5f)) {
        Vec3 tint = base * 0.3f + Vec3{0.7f, 0.7f, 0.7f};  // keep glass light
        return Material::glass(tint, ior);
    }
    if (metallic >= 0.9f && roughness <= 0.2f) return Material::mirror(base * 0.8f + Vec3{0.15f, 0.15f, 0.15f});
    Material m = Material::diffuse(base);
    // Specular colour and shininess (Phong and Blinn files: OBJ Ks/Ns, Collada, 3ds, FBX).
    // A highlight needs an exponent of at least 2; the colour is capped so that diffuse plus
    // specular stays below 1.
    float shin = 0.f;
    if (aiGetMaterialFloat(am, AI_MATKEY_SHININESS, &f) == AI_SUCCESS && std::isfinite(f)) shin = float(f);
    ai_real sstr = 1;
    if (aiGetMaterialFloat(am, AI_MATKEY_SHININESS_STRENGTH, &f) == AI_SUCCESS && std::isfinite(f) && f >= 0) sstr = f;
    if (shin >= 2.f && aiGetMaterialColor(am, AI_MATKEY_COLOR_SPECULAR, &c) == AI_SUCCESS) {
        Vec3 sp = clamp_albedo(Vec3{c.r, c.g, c.b} * float(sstr));
        const float cap = minf(0.5f, maxf(0.f, 1.f - max_component(base)));
        const float peak = max_component(sp);
        if (peak > 0.01f && cap > 0.f) {
            m.specular = peak > cap ? sp * (cap / peak) : sp;
            m.shininess = minf(1024.f, shin);
        }
    }
    return m;
}

Wrap wrap_of(const aiMaterial *am, aiTextureType type, bool v_axis) {
    int mode = aiTextureMapMode_Wrap;
    if (v_axis) aiGetMaterialInteger(am, AI_MATKEY_MAPPINGMODE_V(type, 0), &mode);
    else aiGetMaterialInteger(am, AI_MATKEY_MAPPINGMODE_U(type, 0), &mode);
    switch (mode) {
    case aiTextureMapMode_Clamp:
    case aiTextureMapMode_Decal: return Wrap::Clamp;
    case aiTextureMapMode_Mirror: return Wrap::Mirror;
    default: return Wrap::Repeat;
    }
}

std::string percent_decode(const std::string &s) {
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '%' && i + 2 < s.size() && std::isxdigit((unsigned char)s[i + 1]) && std::isxdigit((unsigned char)s[i + 2])) {
            out += char(std::stoi(s.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += s[i];
        }
    }
    return out;
}

std::string lower(std::string s) {
    for (char &ch : s) ch = char(std::tolower((unsigned char)ch));
    return s;
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

// Loads the diffuse map of a material: an embedded aiTexture (compressed or raw texels) or
// a file next to the model. nullptr (with a warning) when it cannot.
std::shared_ptr<const Texture> load_texture(const aiScene *sc, const aiMaterial *am, aiTextureType type,
                                            const std::string &model_path, std::map<std::string, std::shared_ptr<const Texture>> &cache,
                                            std::vector<std::string> &warnings) {
    aiString written;
    if (am->GetTexture(type, 0, &written) != AI_SUCCESS) return nullptr;
    const std::string name = written.C_Str();
    const Wrap wu = wrap_of(am, type, false), wv = wrap_of(am, type, true);
    std::vector<uint8_t> rgba;
    int w = 0, h = 0;
    std::string why, key;
    const aiTexture *emb = name.empty() ? nullptr : sc->GetEmbeddedTexture(name.c_str());
    if (emb) {
        key = "embedded:" + name;
    } else {
        namespace fs = std::filesystem;
        std::string dir = fs::path(model_path).parent_path().string();
        if (dir.empty()) dir = ".";
        if (name.rfind("$texture", 0) == 0) {
            // A format's placeholder for a skin it does not name (MD2, MDL: "$texture_dummy.bmp"):
            // a picture with the model's own name next to it, as model viewers look for one.
            key = find_skin_file(dir, fs::path(model_path).stem().string());
            if (key.empty()) {
                warnings.push_back("texture '" + name + "' of " + model_path + " is the format's placeholder and no picture named " +
                                   fs::path(model_path).stem().string() + ".* is beside it; using the material colour");
                return nullptr;
            }
            warnings.push_back("texture '" + name + "' of " + model_path + " is the format's placeholder: using " + key +
                               " (the model's name)");
        } else {
            key = find_texture_file(dir, name);
            if (key.empty()) {
                warnings.push_back("texture '" + name + "' of " + model_path + " not found; using the material colour");
                return nullptr;
            }
            // Found elsewhere than written (another separator, another letter case, a path from
            // another machine): say what was substituted.
            std::error_code ec;
            const fs::path literal = fs::path(name).is_absolute() ? fs::path(name) : fs::path(dir) / name;
            if (!fs::equivalent(literal, fs::path(key), ec))
                warnings.push_back("texture '" + name + "' of " + model_path + " is not where it says: using " + key +
                                   " (by file name in the model's folder, ignoring case)");
        }
    }
    const std::string ckey = key + "|" + std::to_string(int(wu)) + std::to_string(int(wv));
    auto it = cache.find(ckey);
    if (it != cache.end()) return it->second;
    bool ok;
    if (emb && emb->mHeight == 0) {
        ok = decode_image(reinterpret_cast<const uint8_t *>(emb->pcData), emb->mWidth, rgba, w, h, why);
    } else if (emb) {  // raw BGRA texels, row 0 at the top
        w = int(emb->mWidth);
        h = int(emb->mHeight);
        rgba.resize(size_t(w) * size_t(h) * 4);
        for (size_t i = 0; i < size_t(w) * size_t(h); ++i) {
            const aiTexel &t = emb->pcData[i];
            rgba[4 * i] = t.r; rgba[4 * i + 1] = t.g; rgba[4 * i + 2] = t.b; rgba[4 * i + 3] = t.a;
        }
        ok = w > 0 && h > 0;
        if (!ok) why = "empty texture";
    } else {
        ok = decode_image_file(key, rgba, w, h, why);
    }
    if (ok && (w < 1 || h < 1 || w > 16384 || h > 16384)) { ok = false; why = "size " + std::to_string(w) + "x" + std::to_string(h); }
    if (!ok) {
        warnings.push_back("texture '" + name + "' of " + model_path + " cannot be decoded (" + why +
                           "); using the material colour");
        cache[ckey] = nullptr;
        return nullptr;
    }
    auto tex = std::make_shared<const Texture>(w, h, 4, rgba.data(), wu, wv);
    cache[ckey] = tex;
    return tex;
}

Vec3 v3(const aiVector3D &v) { return {v.x, v.y, v.z}; }

// Absolute transformation of the node called `name` (identity when there is none).
aiMatrix4x4 node_transform(const aiScene *sc, const aiString &name) {
    aiMatrix4x4 m;
    const aiNode *n = sc->mRootNode ? sc->mRootNode->FindNode(name) : nullptr;
    for (; n; n = n->mParent) m = n->mTransformation * m;
    return m;
}
Vec3 xform_point(const aiMatrix4x4 &m, const aiVector3D &p) { return v3(m * p); }
Vec3 xform_dir(const aiMatrix4x4 &m, const aiVector3D &d) { return v3(aiMatrix3x3(m) * d); }

// The first perspective camera, in model units, placed by its node (read before the node
// hierarchy is flattened). assimp 5.2 gives mHorizontalFOV as the full horizontal angle in
// radians and mAspect = width / height, except for glTF: there mHorizontalFOV is
// yfov * aspect and mPosition repeats the node's translation (a glTF camera sits at its
// node's origin by definition).
bool convert_camera(const aiScene *sc, bool gltf, Camera &cam) {
    for (unsigned i = 0; i < sc->mNumCameras; ++i) {
        const aiCamera *c = sc->mCameras[i];
        const aiMatrix4x4 t = node_transform(sc, c->mName);
        Vec3 pos = xform_point(t, gltf ? aiVector3D(0, 0, 0) : c->mPosition), look = normalize(xform_dir(t, c->mLookAt)),
             up = normalize(xform_dir(t, c->mUp));
        float hfov = float(c->mHorizontalFOV);
        if (!(hfov > 1e-3f && hfov < 3.1f) || !finite(pos) || !(dot(look, look) > 0.5f)) continue;  // orthographic or broken
        double s, co;
        float aspect = c->mAspect > 0.01f && c->mAspect < 100.f ? c->mAspect : 1.f;
        if (gltf) {
            det_sincos(0.5 * double(hfov / aspect), s, co);
            cam.tan_half = float(s / co);
        } else {
            det_sincos(0.5 * double(hfov), s, co);
            cam.tan_half = float(s / co) / aspect;
        }
        cam.eye = pos;
        cam.target = pos + look;
        cam.up = dot(up, up) > 0.5f ? up : Vec3{0.f, 1.f, 0.f};
        cam.vertical = true;
        return true;
    }
    return false;
}

// Point and spot lights, in model units (directional, ambient and area lights are left out).
std::vector<PointLight> convert_lights(const aiScene *sc, bool gltf) {
    std::vector<PointLight> out;
    for (unsigned i = 0; i < sc->mNumLights; ++i) {
        const aiLight *l = sc->mLights[i];
        if (l->mType != aiLightSource_POINT && l->mType != aiLightSource_SPOT) continue;
        PointLight p;
        const aiMatrix4x4 t = node_transform(sc, l->mName);
        p.pos = xform_point(t, gltf ? aiVector3D(0, 0, 0) : l->mPosition);
        p.intensity = {l->mColorDiffuse.r, l->mColorDiffuse.g, l->mColorDiffuse.b};
        if (!finite(p.pos) || !finite(p.intensity) || !(max_component(p.intensity) > 0.f)) continue;
        for (int k = 0; k < 3; ++k) p.intensity[k] = maxf(0.f, p.intensity[k]);
        if (l->mType == aiLightSource_SPOT) {
            Vec3 d = normalize(xform_dir(t, l->mDirection));
            float outer = float(l->mAngleOuterCone), inner = float(l->mAngleInnerCone);
            if (dot(d, d) > 0.5f && outer > 0.f && outer < 3.14f) {
                // assimp's cone angles are full angles (Collada falloff, glTF outerConeAngle x 2).
                double s, ci, co;
                det_sincos(0.5 * double(outer), s, co);
                det_sincos(0.5 * double(minf(inner, outer)), s, ci);
                p.dir = d;
                p.cos_outer = float(co);
                p.cos_inner = float(ci);
            }
        }
        out.push_back(p);
    }
    return out;
}

}  // namespace

std::string find_skin_file(const std::string &model_dir, const std::string &stem) {
    namespace fs = std::filesystem;
    static const char *const kExt[] = {".png", ".jpg", ".jpeg", ".tga", ".bmp", ".pcx", ".gif"};
    std::error_code ec;
    std::vector<fs::path> found;
    for (fs::directory_iterator it(model_dir, ec), end; !ec && it != end; it.increment(ec)) {
        const fs::path &p = it->path();
        if (lower(p.stem().string()) != lower(stem) || !fs::is_regular_file(p, ec)) continue;
        for (const char *e : kExt)
            if (lower(p.extension().string()) == e) found.push_back(p);
    }
    if (found.empty()) return "";
    std::sort(found.begin(), found.end());      // the same choice on every machine
    return found.front().lexically_normal().string();
}

std::string find_texture_file(const std::string &model_dir, const std::string &written) {
    namespace fs = std::filesystem;
    std::string p = written;
    if (p.rfind("file://", 0) == 0) p = p.substr(7);
    for (char &ch : p)
        if (ch == '\\') ch = '/';
    std::error_code ec;
    auto regular = [&](const fs::path &q) { return fs::is_regular_file(q, ec); };
    std::vector<std::string> tries{p};
    std::string dec = percent_decode(p);
    if (dec != p) tries.push_back(dec);
    // "\..\maps\x.jpg": a Windows path from the current drive's root, in practice meant
    // relative to the model (it is never a Unix absolute path).
    if (written.size() > 1 && written[0] == '\\' && written[1] != '\\') tries.push_back(p.substr(1));
    for (const std::string &t : tries) {
        fs::path q(t);
        if (q.is_absolute() && regular(q)) return q.string();
        if (!q.is_absolute() && regular(fs::path(model_dir) / q)) return (fs::path(model_dir) / q).lexically_normal().string();
    }
    // Component by component, ignoring case (files written on Windows).
    auto match_in = [&](const fs::path &dir, const std::string &name) -> fs::path {
        if (name == "." || name == "..") return dir / name;
        if (fs::exists(dir / name, ec)) return dir / name;
        const std::string want = lower(name);
        for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
            if (lower(it->path().filename().string()) == want) return it->path();
        return {};
    };
    for (const std::string &t : tries) {
        fs::path q(t);
        fs::path cur = q.is_absolute() ? fs::path("/") : fs::path(model_dir);
        bool ok = true;
        for (const fs::path &part : q.relative_path()) {
            if (part.empty()) continue;
            fs::path next = match_in(cur, part.string());
            if (next.empty()) { ok = false; break; }
            cur = next;
        }
        if (ok && regular(cur)) return cur.lexically_normal().string();
    }
    // The bare file name next to the model (absolute paths from another machine).
    for (const std::string &t : tries) {
        std::string base = fs::path(t).filename().string();
        if (base.empty()) continue;
        fs::path q = match_in(fs::path(model_dir), base);
        if (!q.empty() && regular(q)) return q.lexically_normal().string();
    }
    return "";
}

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
                           aiProcess_GenUVCoords | aiProcess_ValidateDataStructure;
    // Parsed first without post-processing, so that cameras and lights are read with their
    // nodes' transformations; then the same steps ReadFile(path, flags) would run.
    Camera file_camera;
    bool has_camera = false;
    std::vector<PointLight> file_lights;
    const aiScene *sc = imp.ReadFile(path, 0);
    if (sc) {
        std::string ext = lower(std::filesystem::path(path).extension().string());
        const bool gltf = ext == ".gltf" || ext == ".glb";
        has_camera = convert_camera(sc, gltf, file_camera);
        file_lights = convert_lights(sc, gltf);
        sc = imp.ApplyPostProcessing(flags);
    }
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
    std::map<std::string, std::shared_ptr<const Texture>> cache;
    std::vector<unsigned> uv_channel;  // per material: the diffuse map's UV set
    std::vector<std::string> map_name; // per material: the applied map as the file names it
    for (unsigned i = 0; i < sc->mNumMaterials; ++i) {
        const aiMaterial *am = sc->mMaterials[i];
        // glTF's base colour map comes as both BASE_COLOR and DIFFUSE; the first one found wins.
        aiTextureType type = am->GetTextureCount(aiTextureType_BASE_COLOR) > 0 ? aiTextureType_BASE_COLOR
                             : aiTextureType_DIFFUSE;
        const bool textured = am->GetTextureCount(type) > 0;
        std::shared_ptr<const Texture> tex;
        unsigned uvi = 0;
        if (textured) {
            tex = load_texture(sc, am, type, path, cache, out.warnings);
            aiGetMaterialInteger(am, AI_MATKEY_UVWSRC(type, 0), reinterpret_cast<int *>(&uvi));
        }
        Material m = convert_material(am, textured, tex != nullptr);
        const Vec3 &a = m.albedo;
        if (textured && !tex && m.type == MatType::Diffuse && minf(a.x, minf(a.y, a.z)) >= 0.9f)
            m.albedo = {0.75f, 0.75f, 0.75f};  // no map and a white (or no) colour: light grey
        if (tex && m.type == MatType::Diffuse) {
            size_t k = 0;
            while (k < out.textures.size() && out.textures[k] != tex) ++k;
            if (k == out.textures.size()) out.textures.push_back(tex);
            m.texture = int(k);
        }
        aiString written;
        if (tex) am->GetTexture(type, 0, &written);
        if (tex && m.type != MatType::Diffuse) {
            const char *kind = m.type == MatType::Emissive ? "emissive" : m.type == MatType::Glass ? "glass" : "a mirror";
            out.warnings.push_back("texture '" + std::string(written.C_Str()) + "' of " + path + " is not applied: material " +
                                   std::to_string(i) + " is " + kind + ", which takes no map");
        }
        out.materials.push_back(m);
        uv_channel.push_back(uvi < AI_MAX_NUMBER_OF_TEXTURECOORDS ? uvi : 0);
        map_name.push_back(m.texture >= 0 ? written.C_Str() : "");
    }
    if (out.materials.empty()) {
        out.materials.push_back(Material::diffuse({0.75f, 0.75f, 0.75f}));
        uv_channel.push_back(0);
        map_name.push_back("");
    }
    for (const std::string &w : out.warnings) std::fprintf(stderr, "msr_render: warning: %s\n", w.c_str());
    const size_t material_warnings = out.warnings.size();
    // Per material: meshes whose map cannot be applied (no texture coordinates), and meshes
    // whose coordinates all sit on one point (the map gives one flat colour).
    std::vector<unsigned> no_uv(out.materials.size(), 0), one_point(out.materials.size(), 0);
    out.has_camera = has_camera;
    out.camera = file_camera;
    out.lights = file_lights;

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
        const Material &mat = out.materials[size_t(m.material)];
        const unsigned ch = uv_channel[size_t(m.material)];
        const unsigned set = am->mTextureCoords[ch] ? ch : 0;
        bool uv_missing = false, uv_flat = false;
        if (mat.texture >= 0 && am->mTextureCoords[set]) {
            m.uv.resize(2 * size_t(am->mNumVertices));
            bool spread = false;
            for (unsigned v = 0; v < am->mNumVertices; ++v) {
                float u = am->mTextureCoords[set][v].x, t = am->mTextureCoords[set][v].y;
                m.uv[2 * v] = std::isfinite(u) ? u : 0.f;
                m.uv[2 * v + 1] = std::isfinite(t) ? t : 0.f;
                spread = spread || m.uv[2 * v] != m.uv[0] || m.uv[2 * v + 1] != m.uv[1];
            }
            uv_flat = !spread;
        } else if (mat.texture >= 0) {
            uv_missing = true;
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
        no_uv[size_t(m.material)] += uv_missing;
        one_point[size_t(m.material)] += uv_flat;
        for (uint32_t i : m.idx) out.bounds.add(m.pos[i]);
        out.triangles += m.idx.size() / 3;
        out.meshes.push_back(std::move(m));
    }
    for (size_t k = 0; k < out.materials.size(); ++k) {
        const std::string head = "texture '" + map_name[k] + "' of " + path + " ";
        if (no_uv[k] > 0)
            out.warnings.push_back(head + "is not applied to " + std::to_string(no_uv[k]) +
                                   " mesh(es): they have no texture coordinates; using the material colour");
        if (one_point[k] > 0)
            out.warnings.push_back(head + "gives one flat colour on " + std::to_string(one_point[k]) +
                                   " mesh(es): all their texture coordinates are the same point");
    }
    for (size_t k = material_warnings; k < out.warnings.size(); ++k)
        std::fprintf(stderr, "msr_render: warning: %s\n", out.warnings[k].c_str());
    if (out.triangles == 0) { err = "model file " + path + " holds no triangles"; return false; }
    Vec3 s = out.bounds.size();
    if (!(max_component(s) > 0.f)) { err = "model file " + path + " has zero size"; return false; }
    return true;
}

void add_model(Scene &scene, const Model &model, Vec3 pivot, float scale, float yaw_deg, Vec3 offset) {
    double sd, cd;
    det_sincos_deg(yaw_deg, sd, cd);
    Placement pl;
    pl.pivot = pivot;
    pl.offset = offset;
    pl.scale = scale;
    pl.cos_yaw = float(cd);
    pl.sin_yaw = float(sd);
    scene.model_placement = pl;
    const int tex_base = int(scene.textures.size());
    for (const auto &t : model.textures) scene.textures.push_back(t);
    std::vector<int> mat_map;
    for (Material m : model.materials) {
        if (m.texture >= 0) m.texture += tex_base;
        mat_map.push_back(scene.add_material(m));
    }
    for (const Mesh &src : model.meshes) {
        Mesh m = src;
        m.material = mat_map[size_t(src.material)];
        for (Vec3 &p : m.pos) p = pl.point(p);
        for (Vec3 &n : m.nrm) n = pl.rotate(n);
        scene.add_mesh(std::move(m));
    }
}

}  // namespace msr
