// Library ops over data outside the shader's values: split() into a string array, XML
// dictionaries (dict_find, dict_next, dict_value) and point clouds (pointcloud_search, _get,
// _write, which Lobe does not provide: see docs/language.md).
#include "op_tables.h"

#include "lobe/shading.h"

#include <llvm/IR/Constants.h>

#include <algorithm>

namespace lobe::codegen {
namespace {

using ir::BaseType;

// Stores a shadeop's int result into operand 0.
void int_result(LayerEmitter& e, const ir::Op& op, llvm::Value* r) {
  e.store(op.args[0], e.convert(Val{Dual{r}}, BaseType::Int, e.arg(op, 0).type.base));
}

// split r results str [sep [maxsplit]]: the pieces go straight into the array's storage;
// sep defaults to "" (split at whitespace), maxsplit to the array's length. The elements past
// the pieces keep what they held, except where OSL's -O2 folds the call (its inputs all
// constants): the folded result is the whole array, "" past the pieces (OSL 1.13.12 prints
// `1 [x   ]` for split("x", r, ",") after split("a,b", r, ","), `1 [x b  ]` at -O0).
void op_split(LayerEmitter& e, const ir::Op& op) {
  int len = std::max(0, e.arg(op, 1).type.arraylen);
  llvm::Value* sep = op.args.size() > 3 ? e.load(op.args[3])[0].v : e.string_const("");
  llvm::Value* max =
      op.args.size() > 4 ? e.load_as(op, 4, BaseType::Int, false)[0].v : e.iconst(len);
  llvm::Value* results = e.storage_address(op.args[1]);
  llvm::Value* count = e.call(
      "lobe_split", {e.env_ptr(), e.load(op.args[2])[0].v, sep, max, results, e.iconst(len)});
  bool folded = e.group().opt_level >= 2;
  for (size_t a = 2; a < op.args.size(); ++a)
    folded &= e.arg(op, int(a)).kind == ir::SymKind::Const;
  if (folded) {
    auto& B = e.b();
    llvm::Type* ptr = B.getPtrTy();
    for (int k = 0; k < len; ++k) {
      llvm::Value* at = B.CreateConstInBoundsGEP1_64(ptr, results, uint64_t(k));
      llvm::Value* kept = B.CreateLoad(ptr, at);
      B.CreateStore(B.CreateSelect(B.CreateICmpSGT(count, e.iconst(k)), kept, e.string_const("")),
                    at);
    }
  }
  int_result(e, op, count);
}

// dict_find r "document" "query" | dict_find r node "query"
void op_dict_find(LayerEmitter& e, const ir::Op& op) {
  bool by_node = e.arg(op, 1).type.base == BaseType::Int;
  llvm::Value* where = e.load(op.args[1])[0].v;
  llvm::Value* query = e.load(op.args[2])[0].v;
  int_result(e, op,
             e.call(by_node ? "lobe_dict_find_node" : "lobe_dict_find", {e.sg(), where, query}));
}

void op_dict_next(LayerEmitter& e, const ir::Op& op) {
  int_result(e, op, e.call("lobe_dict_next", {e.sg(), e.load_as(op, 1, BaseType::Int)[0].v}));
}

// dict_value r dest node "attribute": the shadeop parses the text into dest's storage.
void op_dict_value(LayerEmitter& e, const ir::Op& op) {
  int dest = op.args[1];
  int_result(e, op,
             e.call("lobe_dict_value",
                    {e.sg(), e.env_ptr(), e.load_as(op, 2, BaseType::Int)[0].v,
                     e.load(op.args[3])[0].v, e.iconst(LayerEmitter::type_code(e.sym(dest).type)),
                     e.iconst(e.wants_derivs(dest) ? 1 : 0), e.storage_address(dest)}));
}

// pointcloud_search / _get / _write: no point clouds, so no points (one warning per run).
void op_pointcloud(LayerEmitter& e, const ir::Op& op) {
  int_result(
      e, op,
      e.call("lobe_pointcloud", {e.sg(), e.env_ptr(), e.string_const(ir::to_string(op.opcode))}));
}

const OpEntry kDataOps[] = {
    {ir::Opcode::Split, op_split},
    {ir::Opcode::DictFind, op_dict_find},
    {ir::Opcode::DictNext, op_dict_next},
    {ir::Opcode::DictValue, op_dict_value},
    {ir::Opcode::PointcloudSearch, op_pointcloud},
    {ir::Opcode::PointcloudGet, op_pointcloud},
    {ir::Opcode::PointcloudWrite, op_pointcloud},
};

} // namespace

std::span<const OpEntry> data_ops() { return kDataOps; }

} // namespace lobe::codegen
