// Runs each shader of tests/shade over its grid through the ShadingSystem, with
// specialisation off and on, and compares the printed output with `<name>.expected` (and, where
// it exists, the unspecialised run's with `<name>.O0.expected`).
#include "grid.h"
#include "lobe/shadingsys.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> corpus() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(LOBE_SHADE_CORPUS)) {
    auto ext = e.path().extension();
    if ((ext == ".osl" || ext == ".lir") &&
        fs::exists(fs::path(e.path()).replace_extension(".expected")))
      names.push_back(e.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

struct Directives {
  lobe::group::GridSpec grid;
  std::vector<lobe::InstanceValue> params;
  std::vector<std::string> colorspaces; // run once per space, each output after "== NAME"
};

// `// shade: -g W H --center --raytype name -param name value --colorspaces A,B,...` (first
// such line).
Directives directives(const std::string& text) {
  Directives d;
  size_t at = text.find("shade:");
  if (at == std::string::npos) return d;
  std::istringstream in(text.substr(at + 6, text.find('\n', at) - at - 6));
  for (std::string w; in >> w;) {
    if (w == "-g")
      in >> d.grid.width >> d.grid.height;
    else if (w == "--center")
      d.grid.center = true;
    else if (w == "--raytype") {
      std::string r;
      in >> r;
      d.grid.raytype = lobe::group::raytype_from_name(r);
    } else if (w == "-param") {
      lobe::InstanceValue v{"float", "", ""};
      in >> v.name >> v.value;
      d.params.push_back(v);
    } else if (w == "--colorspaces") {
      std::string list;
      in >> list;
      std::istringstream names(list);
      for (std::string n; std::getline(names, n, ',');) d.colorspaces.push_back(n);
    }
  }
  return d;
}

std::string run_in(const fs::path& file, const Directives& d, int opt, const std::string& space,
                   std::string& error) {
  lobe::ShadingSystem ss;
  if (!space.empty()) ss.options().colorspace = space;
  ss.options().opt_level = opt;
  ss.options().specialize = opt > 0;
  ss.options().include_dirs.push_back(LOBE_SHADE_CORPUS);
  lobe::ShaderGroup g;
  g.layers.push_back({file.string(), file.stem().string(), d.params});
  lobe::DiagnosticList diags;
  auto mat = ss.compile(g, diags);
  if (!mat) {
    for (auto& x : diags) error += x.text + "\n";
    return "";
  }
  lobe::ShadingContext ctx;
  for (int y = 0; y < d.grid.height; ++y)
    for (int x = 0; x < d.grid.width; ++x) {
      ctx.reset();
      lobe::ShaderGlobals sg = lobe::group::grid_globals(d.grid, x, y, &ctx);
      mat->shade(sg);
    }
  // Locations print the path the shader was found at; expectations use the file name.
  std::string out = ctx.output, dir = std::string(LOBE_SHADE_CORPUS) + "/";
  for (size_t at; (at = out.find(dir)) != std::string::npos;) out.erase(at, dir.size());
  return out;
}

std::string run(const fs::path& file, const Directives& d, int opt, std::string& error) {
  if (d.colorspaces.empty()) return run_in(file, d, opt, "", error);
  std::string out;
  for (const std::string& space : d.colorspaces)
    out += "== " + space + "\n" + run_in(file, d, opt, space, error);
  return out;
}

class Corpus : public ::testing::TestWithParam<std::string> {};

TEST_P(Corpus, MatchesExpectedWithAndWithoutSpecialisation) {
  fs::path file = fs::path(LOBE_SHADE_CORPUS) / GetParam();
  std::string text = slurp(file);
  std::string expected = slurp(fs::path(file).replace_extension(".expected"));
  // Where OSL's output differs without specialisation (its runtime optimiser's identities), the
  // -O0 expectation is `<name>.O0.expected`.
  fs::path expected_o0 = fs::path(file).replace_extension(".O0.expected");
  std::string expected0 = fs::exists(expected_o0) ? slurp(expected_o0) : expected;
  Directives d = directives(text);
  std::string err0, err2;
  std::string out0 = run(file, d, 0, err0);
  ASSERT_TRUE(err0.empty()) << err0;
  std::string out2 = run(file, d, 2, err2);
  ASSERT_TRUE(err2.empty()) << err2;
  EXPECT_EQ(out0, expected0) << "-O0 (no specialisation)";
  EXPECT_EQ(out2, expected) << "-O2 (specialised)";
}

INSTANTIATE_TEST_SUITE_P(Shade, Corpus, ::testing::ValuesIn(corpus()),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                           std::string n = i.param;
                           for (char& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

} // namespace
