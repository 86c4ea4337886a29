// Native C++ versions of the stdlib shaders (stdlib_shaders/*.osl), implementing lobe::Material
// directly: each builds the same closure tree as its .osl twin, in the ShadingContext arena.
//
// Why: the render tests must not depend on the JIT, and the renderer needs materials before
// the JIT exists. A scene material whose group is a single layer naming one of these shaders
// can be built natively; instance values are read with the .osl parameter names and defaults.
// Supported: matte, plastic, metal, glass, brushed_metal, emitter, mirror, constant_background.
#pragma once

#include "lobe/shadingsys.h"

#include <memory>
#include <string>

namespace lobe::render {

// Null (with `error` set) when the group is not a single layer of a known stdlib shader or an
// instance value does not parse.
std::shared_ptr<const Material> make_native_material(const ShaderGroup& group, std::string& error);

// True if `shader` names a stdlib shader that has a native version.
bool has_native_material(const std::string& shader);

// Bit of kGlobalFields for a global's name (for Material::globals_read), or 0.
uint64_t global_bit(const char* name);

} // namespace lobe::render
