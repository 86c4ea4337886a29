// The committed closures reference in docs/closures.md is what the registry generates (a
// registry edit without `closure_docs --update docs/closures.md` fails here), and the
// generator writes what the table says.
#include "closure_docs.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace lobe::registry {
namespace {

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(ClosureDocs, CommittedTableIsTheGeneratedOne) {
  std::string doc = read(LOBE_SOURCE_DIR "/docs/closures.md");
  ASSERT_FALSE(doc.empty());
  std::string regenerated = doc;
  ASSERT_TRUE(replace_generated_section(regenerated)) << "docs/closures.md lost its markers";
  EXPECT_EQ(doc, regenerated)
      << "docs/closures.md is out of date: run closure_docs --update docs/closures.md";
}

TEST(ClosureDocs, RowsFollowTheTable) {
  std::string md = closure_reference_markdown();
  // Written from the registry rows of closure_table.h, by hand.
  EXPECT_NE(md.find("| `diffuse` | `diffuse(vector N)` | - | Lambertian reflection, f = 1/pi |\n"),
            std::string::npos);
  EXPECT_NE(md.find("| `toon` | `toon(vector N, color albedo, color specular, float shininess)` | "
                    "\"bands\" (int, 3), \"softness\" (float, 0.05) |"),
            std::string::npos);
  EXPECT_NE(md.find("| `layer` | `layer(closure color top, closure color base)` | - |"),
            std::string::npos);
  EXPECT_NE(md.find("| `measured_bsdf` | `measured_bsdf(vector N, string filename)` | \"tint\" "
                    "(color, 1 1 1) |"),
            std::string::npos);
}

TEST(ClosureDocs, CommittedLibraryListIsTheGeneratedOne) {
  std::string doc = read(LOBE_SOURCE_DIR "/docs/language.md");
  ASSERT_FALSE(doc.empty());
  ASSERT_NE(doc.find(kLibraryDocsBegin), std::string::npos) << "docs/language.md lost its markers";
  std::string regenerated = doc;
  ASSERT_TRUE(replace_generated_section(regenerated));
  EXPECT_EQ(doc, regenerated)
      << "docs/language.md is out of date: run closure_docs --update docs/language.md";
}

TEST(ClosureDocs, LibraryRowsFollowTheTable) {
  std::string md = library_reference_markdown();
  // Written from the rows of library_calls.h, by hand.
  EXPECT_NE(md.find("| `int strlen(string)` | the length of the string in bytes |\n"),
            std::string::npos);
  EXPECT_NE(md.find("| `int getchar(string, int)` | "), std::string::npos);
  EXPECT_NE(md.find("| `float stof(string)` | "), std::string::npos);
}

TEST(ClosureDocs, MathRowsFollowTheTable) {
  std::string md = math_reference_markdown();
  // Written from the rows of math_functions.h, by hand.
  EXPECT_NE(md.find("| `sin` | `T(T)`, T: float, color, point, vector, normal | a = sin b |\n"),
            std::string::npos);
  EXPECT_NE(md.find("| `erf` | `T(T)`, T: float | a = erf b |\n"), std::string::npos);
  EXPECT_NE(md.find("| `atan2` | `T(T, T)`, T: float, color"), std::string::npos);
  std::string doc = read(LOBE_SOURCE_DIR "/docs/language.md");
  EXPECT_NE(doc.find(kMathDocsBegin), std::string::npos) << "docs/language.md lost its markers";
}

TEST(ClosureDocs, ReplaceNeedsBothMarkers) {
  std::string doc = "x\n" + std::string(kDocsBegin) + "\nold\n";
  EXPECT_FALSE(replace_generated_section(doc));
  doc += std::string(kDocsEnd) + "\nafter\n";
  ASSERT_TRUE(replace_generated_section(doc));
  EXPECT_EQ(doc, "x\n" + std::string(kDocsBegin) + "\n" + closure_reference_markdown() + kDocsEnd +
                     "\nafter\n");
}

} // namespace
} // namespace lobe::registry
