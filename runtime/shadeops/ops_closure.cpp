// Shadeops that build closure trees in the ShadingContext arena. A component's parameter
// block arrives fully packed (registry layout) and is copied behind its ClosureComponent
// header. Zero weights and null operands fold away here, so a closure whose weight is zero at
// run time never reaches the renderer.
#include "lobe/context.h"
#include "lobe/shading.h"
#include "shadeop_decls.h"

#include <cstring>

using namespace lobe;

extern "C" {

const ClosureNode* lobe_closure_component(ShaderGlobals* sg, int id, const void* block,
                                          int block_size) {
  ShadingContext* ctx = sg->context;
  if (!ctx) return nullptr;
  void* mem = ctx->allocate(sizeof(ClosureComponent) + size_t(block_size));
  if (!mem) {
    ctx->closures_dropped++;
    return nullptr;
  }
  auto* c = static_cast<ClosureComponent*>(mem);
  c->id = id;
  c->weight = {1, 1, 1};
  if (block_size > 0) std::memcpy(c->params(), block, size_t(block_size));
  return c;
}

const ClosureNode* lobe_closure_declared(ShaderGlobals* sg, const DeclaredClosureInfo* info,
                                         const void* block) {
  ShadingContext* ctx = sg->context;
  if (!ctx) return nullptr;
  void* mem = ctx->allocate(sizeof(ClosureDeclared) + info->block_size);
  if (!mem) {
    ctx->closures_dropped++;
    return nullptr;
  }
  auto* c = static_cast<ClosureDeclared*>(mem);
  c->id = kClosureDeclared;
  c->weight = {1, 1, 1};
  c->info = info;
  if (info->block_size > 0) std::memcpy(c->values(), block, info->block_size);
  return c;
}

const ClosureNode* lobe_closure_add(ShaderGlobals* sg, const ClosureNode* a, const ClosureNode* b) {
  if (!a) return b;
  if (!b) return a;
  auto* n = static_cast<ClosureAdd*>(sg->context->allocate(sizeof(ClosureAdd)));
  if (!n) {
    sg->context->closures_dropped++;
    return a;
  }
  n->id = kClosureAdd;
  n->a = a;
  n->b = b;
  return n;
}

// weight: pointer to three floats (a float weight arrives splatted).
const ClosureNode* lobe_closure_mul(ShaderGlobals* sg, const ClosureNode* c, const float* w) {
  if (!c || (w[0] == 0.0f && w[1] == 0.0f && w[2] == 0.0f)) return nullptr;
  auto* n = static_cast<ClosureMul*>(sg->context->allocate(sizeof(ClosureMul)));
  if (!n) {
    sg->context->closures_dropped++;
    return nullptr;
  }
  n->id = kClosureMul;
  n->weight = {w[0], w[1], w[2]};
  n->closure = c;
  return n;
}

// `c` is a ClosureComponent fresh from lobe_closure_component (weight 1) that nothing else
// refers to: weighting it in place gives the tree a ClosureMul over it would (a weight times 1
// is the weight, exactly), with one node fewer.
const ClosureNode* lobe_closure_weight(ShaderGlobals* sg, const ClosureNode* c, const float* w) {
  (void)sg;
  if (!c || (w[0] == 0.0f && w[1] == 0.0f && w[2] == 0.0f)) return nullptr;
  auto* k = const_cast<ClosureComponent*>(static_cast<const ClosureComponent*>(c));
  k->weight = {w[0], w[1], w[2]};
  return c;
}

} // extern "C"
