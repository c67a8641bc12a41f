// Built-in scenes and the generic model-file scene.
#pragma once

#include <memory>
#include <string>

#include "scene.h"

namespace msr {

// Comma-separated built-in names, default scene ("cornell") first.
const char *builtin_scene_names();

// Builds the scene `name`: a built-in name, else a model file path. Returns nullptr with a
// one-line message in err on failure. The scene is not committed yet.
std::unique_ptr<Scene> make_scene(const std::string &name, std::string &err);

// The generic framing of any model: normalised to unit bounding-sphere radius on a ground
// plane, camera on the bounding sphere, a key area light, a fill point light and a sky.
std::unique_ptr<Scene> model_file_scene(const std::string &path, std::string &err);

}  // namespace msr
