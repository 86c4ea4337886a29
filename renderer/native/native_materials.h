// Test support: native C++ twins of the stdlib shaders (stdlib_shaders/*.osl), implementing
// lobe::Material directly: each builds the same closure tree as its .osl twin, in the
// ShadingContext arena, through the closure library's internal parameter blocks.
//
// Why: the render tests must not depend on the JIT, and `lobe render --materials native`
// measures the renderer without it. A scene material whose group is a single layer naming one
// of these shaders can be built natively. Supported: matte, plastic, metal, glass,
// brushed_metal, emitter, mirror, constant_background.
//
// The parameters (names, types, defaults) are not repeated here: they are read from the .osl
// file (lobe::stdlib_shader_dir()), compiled once by the front end (no LLVM), and instance
// values are checked against them. What each shader computes, and metal's presets, are written
// by hand (tests/render/jit_materials_test.cpp checks both render alike).
//
// Not part of the renderer proper (renderer/render uses the public API only) nor of the SDK: it
// links the closure library and the front end.
#pragma once

#include "scene_setup.h"

#include "lobe/shadingsys.h"

#include <memory>
#include <string>

namespace lobe::render {

// Null (with `error` set) when the group is not a single layer of a known stdlib shader or an
// instance value does not parse (the JIT's rules and words). An instance value for a parameter
// the shader lacks is an error, or, with `unknown_params_ignored` (testrender XML scenes, as
// MaterialDesc::unknown_params_warn says), ignored as the JIT ignores it.
std::shared_ptr<const Material> make_native_material(const ShaderGroup& group, std::string& error,
                                                     bool unknown_params_ignored = false);

// True if `shader` names a stdlib shader that has a native version.
bool has_native_material(const std::string& shader);

// make_native_material as a MaterialCompiler, for RenderScene::setup and MaterialBackend.
MaterialCompiler native_compiler();

} // namespace lobe::render
