// Model files through the Open Asset Importer (assimp): triangles, smooth normals, vertex
// colours and a material per mesh (diffuse colour; glass, mirror and emissive when the file
// says so). Textures are not sampled.
#pragma once

#include <string>
#include <vector>

#include "scene.h"

namespace msr {

struct Model {
    std::vector<Mesh> meshes;         // Mesh::material indexes Model::materials
    std::vector<Material> materials;
    Bounds bounds;
    size_t triangles = 0;
};

// Reads `path`. Returns false with a one-line message when the file cannot be read or holds
// no triangles.
bool load_model(const std::string &path, Model &out, std::string &err);

// Adds the model to a scene, mapping every vertex through p' = (p - pivot) * scale + offset
// after a rotation of `yaw_deg` about +y. Normals are rotated the same way.
void add_model(Scene &scene, const Model &model, Vec3 pivot, float scale, float yaw_deg, Vec3 offset);

}  // namespace msr
