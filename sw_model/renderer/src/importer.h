// Model files through the Open Asset Importer (assimp): triangles, smooth normals, vertex
// colours, texture coordinates, a material per mesh (diffuse colour and map, specular colour
// and shininess, opacity, emission; glass, mirror and emissive when the file says so), the
// file's first perspective camera and its point and spot lights.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "scene.h"

namespace msr {

struct Model {
    std::vector<Mesh> meshes;         // Mesh::material indexes Model::materials
    std::vector<Material> materials;  // Material::texture indexes Model::textures
    std::vector<std::shared_ptr<const Texture>> textures;
    Bounds bounds;
    size_t triangles = 0;
    // The file's camera (model units; tan_half spans the image height), when it has one.
    bool has_camera = false;
    Camera camera;
    // The file's point and spot lights (model units; intensities as the file gives them).
    std::vector<PointLight> lights;
    std::vector<std::string> warnings;  // also printed on stderr once, when loading
};

// Reads `path`. Returns false with a one-line message when the file cannot be read or holds
// no triangles. A texture that cannot be found or decoded, or that is found but cannot be
// applied (a material that takes no map, meshes without texture coordinates), is a warning on
// stderr naming the file and the reason; the material then keeps its colour.
bool load_model(const std::string &path, Model &out, std::string &err);

// Adds the model to a scene through the placement p' = R_yaw (p - pivot) * scale + offset.
// Normals are rotated the same way. Records the placement as scene.model_placement.
void add_model(Scene &scene, const Model &model, Vec3 pivot, float scale, float yaw_deg, Vec3 offset);

// A texture path as the file wrote it, found on disk: relative to the model's folder (or
// absolute), with backslashes as separators, "file://" and %-escapes undone, and each path
// component matched without regard to case; a path from the drive's root ("\\..\\x.jpg")
// also relative to the model's folder; finally the bare file name in the model's folder.
// Returns "" when nothing matches.
std::string find_texture_file(const std::string &model_dir, const std::string &written);
// A skin for a format's placeholder name: a picture named `stem` (any case, a common image
// extension) in model_dir; "" if none.
std::string find_skin_file(const std::string &model_dir, const std::string &stem);

}  // namespace msr
