// How JIT code links (jit.cpp): the runtime library's shadeops by the addresses in its table,
// functions outside that table (libc's) from the process, and a name found nowhere as an error
// that names it.
#include "jit.h"
#include "shadeops.h"

#include <gtest/gtest.h>
#include <llvm/AsmParser/Parser.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/Module.h>
#include <llvm/Support/SourceMgr.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace lobe;

// Compiles `ir` at -O0 and returns the addresses of `entries` (empty, with `err` set, if the
// module does not link).
std::vector<void*> compile(jit::Jit& j, const std::string& ir,
                           const std::vector<std::string>& entries, std::string& err) {
  auto ctx = std::make_unique<llvm::LLVMContext>();
  llvm::SMDiagnostic diag;
  auto mod = llvm::parseAssemblyString(ir, diag, *ctx);
  if (!mod) {
    err = diag.getMessage().str();
    return {};
  }
  j.configure(*mod);
  jit::CompiledGroup code;
  jit::JitTimes times;
  std::vector<void*> addr;
  if (!j.add(std::move(ctx), std::move(mod), 0, entries, addr, code, times, err)) return {};
  return addr;
}

TEST(JitLink, ShadeopsComeFromTheRuntimeTableAndLibcFromTheProcess) {
  std::string err;
  auto j = jit::Jit::create(err);
  ASSERT_TRUE(j) << err;
  ASSERT_FALSE(shadeops::shadeop_symbols().empty());
  const shadeops::ShadeOpSymbol& op = shadeops::shadeop_symbols().front();
  const std::string ir = std::string("declare void @") + op.name + "()\n" +
                         "declare i64 @strlen(ptr)\n"
                         "define ptr @op() {\n  ret ptr @" +
                         op.name +
                         "\n}\n"
                         "define i64 @len(ptr %s) {\n"
                         "  %n = call i64 @strlen(ptr %s)\n  ret i64 %n\n}\n";
  std::vector<void*> addr = compile(*j, ir, {"op", "len"}, err);
  ASSERT_EQ(addr.size(), 2u) << err;
  EXPECT_EQ(reinterpret_cast<void* (*)()>(addr[0])(), op.address) << op.name;
  EXPECT_EQ(reinterpret_cast<int64_t (*)(const char*)>(addr[1])("seventeen"), 9);
}

TEST(JitLink, ANameFoundNowhereIsAnErrorNamingIt) {
  std::string err;
  auto j = jit::Jit::create(err);
  ASSERT_TRUE(j) << err;
  const std::string ir =
      "declare i32 @lobe_no_such_function_anywhere(i32)\n"
      "define i32 @f(i32 %x) {\n"
      "  %y = call i32 @lobe_no_such_function_anywhere(i32 %x)\n  ret i32 %y\n}\n";
  EXPECT_TRUE(compile(*j, ir, {"f"}, err).empty());
  EXPECT_NE(err.find("lobe_no_such_function_anywhere"), std::string::npos) << err;
}

} // namespace
