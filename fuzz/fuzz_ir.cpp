// Lobe IR text (`lobe compile --emit=ir`, .lir files, ShadingSystem::add_shader_ir): parse,
// verify, and check the printer's promise that what it prints reads back to the same text.
#include "ir/parser.h"
#include "ir/printer.h"
#include "ir/verifier.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lobe::ir::ParseResult r =
      lobe::ir::parse(std::string_view(reinterpret_cast<const char*>(data), size));
  if (!r.shader) return 0;
  (void)lobe::ir::verify(*r.shader);
  std::string text = lobe::ir::print(*r.shader);
  lobe::ir::ParseResult again = lobe::ir::parse(text);
  if (!again.shader) {
    std::fprintf(stderr, "printed IR does not parse back: %s\n%s\n",
                 again.error.to_string().c_str(), text.c_str());
    std::abort();
  }
  if (lobe::ir::print(*again.shader) != text) {
    std::fprintf(stderr, "printed IR does not read back to the same text:\n%s\n", text.c_str());
    std::abort();
  }
  return 0;
}
