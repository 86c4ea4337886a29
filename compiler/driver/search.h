// Finding a shader by name: the one search order of Lobe (docs/runtime.md, "Finding shaders"),
// used by the ShadingSystem (and so `lobe shade`, `lobe render` and renderer plugins),
// `lobe compile` and `lobe info`. Each caller gives its list of directories; the order within
// the search is this:
//   1. `x.oso` stands for `x` (oslc's output; Lobe reads its own compiled form or the source);
//   2. a name with a directory part or an .osl/.lir extension that is an existing file is that
//      file, as given;
//   3. else each directory in order ("." or "" is the current directory; an absolute name is
//      only looked for where it is): the name itself if it ends in .osl or .lir, else name.osl
//      then name.lir, except that with Prefer::Compiled a name.lir at least as new as the
//      name.osl beside it comes first (the compiled form, as OSL's tools read name.oso: what
//      `lobe compile -DX -Idir` wrote is what `lobe shade` runs; an edited source is newer);
//   4. else, for a plain name, an .osl in the same directories, in order, that declares shader
//      `name` (files in name order, the first found): OSL finds name.oso, which oslc names
//      after the shader the source declares (raytype-envmap.osl declaring raytype_envmap).
// The path found is lexically normal ("./x.osl" is "x.osl"); "" if none.
#pragma once

#include <string>
#include <vector>

namespace lobe::driver {

// Which of name.osl and name.lir in one directory comes first (step 3). Source: the .osl
// (`lobe compile`, which compiles sources). Compiled: the .lir when it is at least as new as
// the .osl (shading and `lobe info`, which read compiled shaders as testshade and oslinfo do).
enum class Prefer { Source, Compiled };

std::string find_shader(std::string name, const std::vector<std::string>& dirs,
                        Prefer prefer = Prefer::Source);

// The shader name an OSL source declares (`surface raytype_envmap (...)`), "" if none is found.
std::string declared_shader_name(const std::string& text);

} // namespace lobe::driver
