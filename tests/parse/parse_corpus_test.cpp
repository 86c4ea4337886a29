// The material corpus (tests/parse/materials/*.osl): realistic shaders that must preprocess,
// parse and type-check without any diagnostic. One test per file.
#include "frontend.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace fs = std::filesystem;
using namespace lobe;

namespace {

const fs::path kDir = fs::path(LOBE_SOURCE_DIR) / "tests" / "parse" / "materials";

std::vector<std::string> corpus() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(kDir))
    if (e.path().extension() == ".osl") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

class MaterialCorpus : public ::testing::TestWithParam<std::string> {};

TEST_P(MaterialCorpus, CompilesCleanly) {
  fs::path file = kDir / (GetParam() + ".osl");
  diag::DiagnosticEngine diags;
  auto tu = frontend::compile_to_ast({file.string(), std::nullopt}, {}, diags);
  EXPECT_EQ(diags.diagnostics().size(), 0u) << diag::render_all(diags, *tu->sources);
  ASSERT_NE(tu->shader(), nullptr);
  EXPECT_EQ(tu->shader()->name, GetParam());
  EXPECT_FALSE(tu->shader()->metadata.empty()); // every corpus shader carries metadata
}

INSTANTIATE_TEST_SUITE_P(Files, MaterialCorpus, ::testing::ValuesIn(corpus()),
                         [](const auto& p) { return p.param; });

} // namespace
