// The compiled Material (shadingsys.h): machine code of one specialised group, its initial
// group data, and where each layer's parameters live for read_output(). The JIT and the
// runtime environment are shared, so a Material stays valid after its ShadingSystem is gone.
#pragma once

#include "env.h"
#include "ir/ir.h"
#include "jit.h"
#include "lobe/detail/closure_kernels.h"
#include "lobe/shadingsys.h"

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace lobe::group {

struct OutputSlot {
  size_t offset = 0;
  ir::Type type;
  bool output = false; // an `output` parameter (the others are readable, not outputs)
};

class MaterialImpl final : public Material {
public:
  using Entry = void (*)(ShaderGlobals*, void*);

  MaterialImpl(std::shared_ptr<jit::Jit> jit, std::shared_ptr<shadeops::RuntimeEnv> env,
               jit::CompiledGroup code, std::vector<unsigned char> groupdata,
               std::map<std::string, OutputSlot> slots, uint64_t globals, CompileStats stats,
               std::vector<int> closure_ids = {});
  ~MaterialImpl() override;

  void shade(ShaderGlobals& sg) const override;
  uint64_t globals_read() const override { return globals_; }
  bool read_output(const ShadingContext& ctx, const std::string& layer, const std::string& param,
                   std::vector<float>& dst) const override;
  std::optional<OutputInfo> output_info(const std::string& layer,
                                        const std::string& param) const override;
  size_t groupdata_bytes() const override { return groupdata_.size(); }
  const unsigned char* output_data(const ShadingContext& ctx) const override;
  bool read_output_bytes(const ShadingContext& ctx, const std::string& layer,
                         const std::string& param, std::vector<unsigned char>& dst) const override;
  const CompileStats& stats() const override { return stats_; }
  const ClosureKernels* closure_kernels() const override;
  std::string closure_kernels_error() const override;
  bool closure_kernels_cached() const override;

private:
  bool read_from(const unsigned char* gd, const std::string& layer, const std::string& param,
                 std::vector<float>& dst) const;

  std::shared_ptr<jit::Jit> jit_;
  std::shared_ptr<shadeops::RuntimeEnv> env_; // strings baked into the code live here
  jit::CompiledGroup code_;
  Entry entry_;
  std::vector<unsigned char> groupdata_;    // initial contents, copied at every shade()
  std::map<std::string, OutputSlot> slots_; // "layer.param" -> storage
  uint64_t globals_;
  CompileStats stats_;
  // Closure kernels, compiled on first use (closure_kernels()).
  std::vector<int> closure_ids_; // registry ids of the closures the group can create
  mutable std::once_flag kernels_once_;
  mutable ClosureKernels kernels_;
  mutable jit::CompiledGroup kernels_code_;
  mutable std::string kernels_error_;
  mutable bool kernels_cached_ = false;
};

// A cache hit: the same compiled material, with the stats of this request.
class CachedMaterial final : public Material {
public:
  CachedMaterial(std::shared_ptr<const Material> m, CompileStats stats)
      : m_(std::move(m)), stats_(stats) {}
  void shade(ShaderGlobals& sg) const override { m_->shade(sg); }
  uint64_t globals_read() const override { return m_->globals_read(); }
  bool read_output(const ShadingContext& ctx, const std::string& layer, const std::string& param,
                   std::vector<float>& dst) const override {
    return m_->read_output(ctx, layer, param, dst);
  }
  std::optional<OutputInfo> output_info(const std::string& layer,
                                        const std::string& param) const override {
    return m_->output_info(layer, param);
  }
  size_t groupdata_bytes() const override { return m_->groupdata_bytes(); }
  const unsigned char* output_data(const ShadingContext& ctx) const override {
    return m_->output_data(ctx);
  }
  bool read_output_bytes(const ShadingContext& ctx, const std::string& layer,
                         const std::string& param, std::vector<unsigned char>& dst) const override {
    return m_->read_output_bytes(ctx, layer, param, dst);
  }
  const CompileStats& stats() const override { return stats_; }
  const ClosureKernels* closure_kernels() const override { return m_->closure_kernels(); }
  std::string closure_kernels_error() const override { return m_->closure_kernels_error(); }
  bool closure_kernels_cached() const override { return m_->closure_kernels_cached(); }

private:
  std::shared_ptr<const Material> m_;
  CompileStats stats_;
};

} // namespace lobe::group
