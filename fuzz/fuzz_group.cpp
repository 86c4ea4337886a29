// Shader-group text (`lobe shade -group`, scene files, ShadingSystem::parse_group). The first
// byte chooses OSL testrender's dialect (bare `TYPE NAME VALUE` params) and the line numbering.
#include "group_text.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lobe::group::GroupTextOptions opts;
  if (size > 0) {
    opts.allow_bare_params = data[0] & 1;
    opts.first_line = (data[0] & 2) ? 7 : 0;
    ++data, --size;
  }
  lobe::DiagnosticList diags;
  std::string text(reinterpret_cast<const char*>(data), size);
  (void)lobe::group::parse_group_text(text, "fuzz", diags, opts);
  return 0;
}
