// Test helper: run a pass on IR text, return the printed result (text in, text out).
#pragma once

#include "ir/parser.h"
#include "ir/printer.h"
#include "ir/verifier.h"

#include <gtest/gtest.h>

#include <string>

namespace lobe::passes::testing {

// Parses `text`, applies `pass`, verifies the result; returns printed IR, and the pass's
// "changed" result in `changed`.
template <class Pass> std::string run_pass(const std::string& text, Pass pass, bool* changed = nullptr) {
  ir::ParseResult r = ir::parse(text);
  EXPECT_TRUE(r.shader) << r.error.to_string() << "\n" << text;
  if (!r.shader) return "";
  bool c = pass(*r.shader);
  if (changed) *changed = c;
  auto errs = ir::verify(*r.shader);
  EXPECT_TRUE(errs.empty()) << errs[0] << "\n" << ir::print(*r.shader);
  return ir::print(*r.shader);
}

} // namespace lobe::passes::testing
