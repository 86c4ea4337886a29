// emit_shader_text (see emit_text.h).
#include "emit_text.h"

#include "codegen.h"
#include "env.h"
#include "group_build.h"
#include "jit.h"
#include "shader_source.h"

#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/Module.h>
#include <llvm/Support/raw_ostream.h>

#include <filesystem>

namespace lobe::group {

bool emit_shader_text(const std::string& path, const CompileOptions& options, EmitForm form,
                      std::string& out, DiagnosticList& diags) {
  auto error = [&](const std::string& text) {
    diags.push_back(runtime_diag(diag::DiagId::jit, text));
    return false;
  };
  CompileStats stats;
  std::optional<ir::Shader> shader = compile_shader_file(path, options, diags, stats);
  if (!shader) return false;
  ShaderGroup g;
  g.layers.push_back({path, std::filesystem::path(path).stem().string(), {}});
  GroupBuild b;
  shadeops::RuntimeEnv env; // strings interned for the printed code (not run)
  b.plan.env = &env;
  b.plan.fast_math = options.fast_math;
  b.plan.opt_level = options.opt_level;
  b.plan.userdata_isconnected = options.userdata_isconnected;
  b.plan.max_loop_iterations = options.max_loop_iterations;
  b.plan.range_checking = options.range_checking;
  b.plan.debug_nan = options.debug_nan;
  b.plan.debug_uninit = options.debug_uninit;
  bool specialize = options.specialize && options.opt_level > 0;
  if (!build_group(g, {&*shader}, specialize, b, diags)) return false;

  std::string err;
  std::unique_ptr<jit::Jit> jit = jit::Jit::create(err);
  if (!jit) return error("JIT unavailable: " + err);
  llvm::LLVMContext ctx;
  llvm::Module mod(b.layer_names.empty() ? "group" : b.layer_names.back(), ctx);
  jit->configure(mod);
  codegen::HostSymbols host; // named in the text; not loaded
  err = codegen::emit_group(b.plan, mod, host);
  if (!err.empty()) {
    diags.push_back(
        located_error(err, diag::DiagId::codegen)); // `file:line:col: error: ...` when located
    return false;
  }
  jit->optimize(mod, options.opt_level);
  if (form == EmitForm::Assembly) {
    if (!jit->emit_assembly(mod, out, err)) return error("JIT: " + err);
    return true;
  }
  out.clear();
  llvm::raw_string_ostream os(out);
  mod.print(os, nullptr);
  os.flush();
  return true;
}

} // namespace lobe::group
