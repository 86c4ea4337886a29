// Shader source through the whole compiler: preprocess -> lex -> parse -> sema -> lowering
// -> constant folding + dead-code elimination -> IR verifier, then the IR printed (what
// `lobe compile --emit=ir` does). #include reads nothing from disk (every include is
// missing), so the input is the only file; the standard header is included as usual.
#include "ir/printer.h"
#include "lower/pipeline.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lobe::lower::PipelineOptions opts;
  opts.optimize = size > 0 && (data[0] & 1); // half the inputs also run the optimiser
  opts.frontend.read_file = [](const std::string&) -> std::optional<std::string> {
    return std::nullopt;
  };
  lobe::frontend::SourceInput in{"fuzz.osl",
                                 std::string(reinterpret_cast<const char*>(data), size)};
  lobe::lower::PipelineResult r = lobe::lower::compile_osl(in, opts);
  if (r.shader) (void)lobe::ir::print(*r.shader);
  return 0;
}
