// The diagnostics corpus: every tests/diagnostics/*.osl is compiled and its diagnostics are
// checked against the expectations written inline (see verify.h). One test per file.
#include "frontend.h"
#include "verify.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace lobe;

namespace {

const fs::path kDir = fs::path(LOBE_SOURCE_DIR) / "tests" / "diagnostics";

std::vector<std::string> corpus() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(kDir))
    if (e.path().extension() == ".osl") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class DiagnosticsCorpus : public ::testing::TestWithParam<std::string> {};

TEST_P(DiagnosticsCorpus, MatchesInlineExpectations) {
  fs::path file = kDir / (GetParam() + ".osl");
  std::string source = read(file);
  std::vector<std::string> problems;
  auto expected = verify::parse_expectations(source, problems);
  diag::DiagnosticEngine diags(200);
  frontend::FrontendOptions opts;
  opts.include_dirs = {(kDir / "include").string()};
  auto tu = frontend::compile_to_ast({file.string(), std::nullopt}, opts, diags);
  auto more = verify::verify(expected, file.string(), diags, *tu->sources);
  problems.insert(problems.end(), more.begin(), more.end());
  std::string all;
  for (auto& p : problems) all += "  " + p + "\n";
  EXPECT_TRUE(problems.empty()) << file.string() << ":\n"
                                << all << "rendered diagnostics:\n"
                                << diag::render_all(diags, *tu->sources);
}

INSTANTIATE_TEST_SUITE_P(Files, DiagnosticsCorpus, ::testing::ValuesIn(corpus()),
                         [](const auto& p) { return p.param; });

} // namespace
