// MaterialImpl: runs the group entry on a copy of the initial group data kept in the calling
// thread's ShadingContext (so shade() is re-entrant across threads), and reads outputs back.
#include "material.h"

#include "closure_kernels.h"

#include "lobe/context.h"

#include <cstring>

namespace lobe::group {

MaterialImpl::MaterialImpl(std::shared_ptr<jit::Jit> jit, std::shared_ptr<shadeops::RuntimeEnv> env,
                           jit::CompiledGroup code, std::vector<unsigned char> groupdata,
                           std::map<std::string, OutputSlot> slots, uint64_t globals,
                           CompileStats stats, std::vector<int> closure_ids)
    : jit_(std::move(jit)), env_(std::move(env)), code_(code),
      entry_(reinterpret_cast<Entry>(code.entry)), groupdata_(std::move(groupdata)),
      slots_(std::move(slots)), globals_(globals), stats_(stats),
      closure_ids_(std::move(closure_ids)) {}

MaterialImpl::~MaterialImpl() {
  jit_->remove(kernels_code_);
  jit_->remove(code_);
}

const ClosureKernels* MaterialImpl::closure_kernels() const {
  std::call_once(kernels_once_, [this] {
    if (closure_ids_.empty()) return;
    jit::JitTimes times;
    // On failure, or with no closure the bitcode provides, kernels_ stays empty (eval null).
    jit::compile_closure_kernels(*jit_, closure_ids_, kernels_, kernels_code_, times,
                                 kernels_error_);
    kernels_cached_ = times.from_cache;
  });
  return kernels_.eval ? &kernels_ : nullptr;
}

bool MaterialImpl::closure_kernels_cached() const {
  closure_kernels();
  return kernels_cached_;
}

std::string MaterialImpl::closure_kernels_error() const {
  closure_kernels();
  return kernels_error_;
}

void MaterialImpl::shade(ShaderGlobals& sg) const {
  sg.Ci = nullptr;
  ShadingContext* ctx = sg.context;
  if (!ctx) { // no context: no closures, no messages; still run for outputs
    std::vector<unsigned char> gd = groupdata_;
    entry_(&sg, gd.data());
    return;
  }
  if (ctx->groupdata.size() < groupdata_.size()) ctx->groupdata.resize(groupdata_.size());
  std::memcpy(ctx->groupdata.data(), groupdata_.data(), groupdata_.size());
  ctx->groupdata_owner = this;
  ctx->begin_shade();
  entry_(&sg, ctx->groupdata.data());
  if (ctx->stopped) sg.Ci = nullptr; // a stopped shade leaves no closure (context.h)
}

bool MaterialImpl::read_output(const ShadingContext& ctx, const std::string& layer,
                               const std::string& param, std::vector<float>& dst) const {
  return read_from(ctx.groupdata_owner == this ? ctx.groupdata.data() : groupdata_.data(), layer,
                   param, dst);
}

std::optional<Material::OutputInfo> MaterialImpl::output_info(const std::string& layer,
                                                              const std::string& param) const {
  auto it = slots_.find(layer + "." + param);
  if (it == slots_.end() || !it->second.output) return std::nullopt;
  const ir::Type& t = it->second.type;
  OutputInfo info;
  info.closure = t.base == ir::BaseType::Closure;
  info.offset = it->second.offset;
  using B = DataType::Base;
  switch (t.base) {
  case ir::BaseType::Int:
    info.type.base = B::Int;
    break;
  case ir::BaseType::Color:
    info.type.base = B::Color;
    break;
  case ir::BaseType::Point:
    info.type.base = B::Point;
    break;
  case ir::BaseType::Vector:
    info.type.base = B::Vector;
    break;
  case ir::BaseType::Normal:
    info.type.base = B::Normal;
    break;
  case ir::BaseType::Matrix:
    info.type.base = B::Matrix;
    break;
  case ir::BaseType::String:
    info.type.base = B::String;
    break;
  default:
    info.type.base = B::Float;
    break;
  }
  info.type.arraylen = std::max(0, t.arraylen);
  return info;
}

const unsigned char* MaterialImpl::output_data(const ShadingContext& ctx) const {
  return ctx.groupdata_owner == this ? ctx.groupdata.data() : groupdata_.data();
}

bool MaterialImpl::read_output_bytes(const ShadingContext& ctx, const std::string& layer,
                                     const std::string& param,
                                     std::vector<unsigned char>& dst) const {
  auto it = slots_.find(layer + "." + param);
  if (it == slots_.end() || it->second.type.base == ir::BaseType::Closure) return false;
  const ir::Type& t = it->second.type;
  size_t scalar = t.base == ir::BaseType::String ? sizeof(const char*) : 4;
  size_t n = size_t(t.components()) * size_t(std::max(1, t.arraylen)) * scalar;
  const unsigned char* gd = output_data(ctx) + it->second.offset;
  dst.assign(gd, gd + n);
  return true;
}

bool MaterialImpl::read_from(const unsigned char* gd, const std::string& layer,
                             const std::string& param, std::vector<float>& dst) const {
  auto it = slots_.find(layer + "." + param);
  if (it == slots_.end()) return false;
  const OutputSlot& s = it->second;
  if (s.type.base == ir::BaseType::String || s.type.base == ir::BaseType::Closure) return false;
  int n = s.type.components() * std::max(1, s.type.arraylen);
  dst.resize(size_t(n));
  for (int k = 0; k < n; ++k) {
    const unsigned char* p = gd + s.offset + 4 * size_t(k);
    if (s.type.base == ir::BaseType::Int) {
      int32_t i;
      std::memcpy(&i, p, 4);
      dst[size_t(k)] = float(i);
    } else {
      std::memcpy(&dst[size_t(k)], p, 4);
    }
  }
  return true;
}

} // namespace lobe::group
