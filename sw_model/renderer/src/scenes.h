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

// A view "EX,EY,EZ,TX,TY,TZ,FOV": eye and target in model units (the scene's
// model_placement maps them into the scene), vertical field of view in degrees (0 < FOV <
// 180), up +y. parse_view checks the text (one-line message on failure); set_view also
// applies it to the scene's camera.
bool parse_view(const std::string &text, float v[7], std::string &err);
bool set_view(Scene &s, const std::string &text, std::string &err);

}  // namespace msr
