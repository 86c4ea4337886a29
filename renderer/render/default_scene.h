// The built-in scene `lobe render` uses when given no scene file: a material preview.
#pragma once

#include "scene.h"

#include <string>

namespace lobe::render {

// JSON text of the default scene (docs/scene-format.md describes the format).
const std::string& default_scene_json();
// Parsed; never fails (a test checks the text loads).
scene::SceneDesc default_scene();

} // namespace lobe::render
