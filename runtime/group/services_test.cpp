// The shader's view of the world around it: user data bound to `lockgeom = 0` parameters,
// getattribute (Lobe's own attributes and the renderer's), and setmessage/getmessage between
// layers. Every case runs with specialisation off (-O0) and on (-O2), which must agree.
#include "grid.h"
#include "lobe/renderer_services.h"
#include "lobe/shadingsys.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <unistd.h>

namespace fs = std::filesystem;
using lobe::DataType;
using B = lobe::DataType::Base;

namespace {

// A renderer with a few user data and attributes, recording what it was asked.
class TestServices final : public lobe::RendererServices {
public:
  mutable std::vector<std::string> asked; // "name:type:derivs"

  bool get_userdata(const lobe::ShaderGlobals& sg, std::string_view name, DataType type,
                    bool derivatives, void* val) const override {
    asked.push_back(std::string(name) + ":" + type.str() + ":" + (derivatives ? "d" : "-"));
    std::strcpy(buf_, "overwritten"); // a string handed out earlier is not ours to keep
    auto* f = static_cast<float*>(val);
    if (name == "Kd" && type == DataType{B::Float, 0}) {
      f[0] = 10 * sg.u; // d/dx = 10 dudx, d/dy = 10 dudy
      if (derivatives) {
        f[1] = 10 * sg.dudx;
        f[2] = 10 * sg.dudy;
      }
      return true;
    }
    if (name == "tint" && type.is_triple() && type.arraylen == 0) {
      f[0] = 0.25f, f[1] = 0.5f, f[2] = 0.75f;
      return true;
    }
    if (name == "label" && type == DataType{B::String, 0}) { // valid until the next call
      std::strcpy(buf_, "from the renderer");
      *static_cast<const char**>(val) = buf_;
      return true;
    }
    if (name == "ids" && type == DataType{B::Int, 3}) {
      int32_t v[3] = {7, 8, 9};
      std::memcpy(val, v, sizeof(v));
      return true;
    }
    if (name == "refuse") { // writes, then says no: the shader must not see the write
      f[0] = 99;
      return false;
    }
    return false;
  }

  bool get_attribute(const lobe::ShaderGlobals& sg, std::string_view object, std::string_view name,
                     int index, DataType type, bool derivatives, void* val) const override {
    (void)sg, (void)derivatives;
    asked.push_back("attr " + std::string(object) + "/" + std::string(name) + "[" +
                    std::to_string(index) + "]:" + type.str());
    auto* f = static_cast<float*>(val);
    if (object.empty() && name == "camera:clip" && index < 0 && type == DataType{B::Float, 2}) {
      f[0] = 0.5f, f[1] = 1000;
      return true;
    }
    if (object.empty() && name == "camera:clip" && index == 1 && type == DataType{B::Float, 0}) {
      f[0] = 1000;
      return true;
    }
    if (object == "light1" && name == "position" && type.is_triple()) {
      f[0] = 1, f[1] = 2, f[2] = 3;
      return true;
    }
    if (name == "scribble") {
      f[0] = 42;
      return false;
    }
    return false;
  }

  bool trace(const lobe::ShaderGlobals& sg, const lobe::TraceOptions& opt, const lobe::Vec3& P,
             const lobe::Vec3& dPdx, const lobe::Vec3& dPdy, const lobe::Vec3& R,
             const lobe::Vec3& dRdx, const lobe::Vec3& dRdy, lobe::TraceHit& hit) const override {
    (void)sg, (void)dPdy, (void)dRdy;
    asked.push_back("trace " + std::to_string(opt.mindist) + " " + std::to_string(opt.maxdist) +
                    " " + std::to_string(opt.shade) + " '" + opt.traceset + "' dPdx.x " +
                    std::to_string(dPdx.x) + " dRdx.x " + std::to_string(dRdx.x));
    if (R.z <= 0) return false; // a ceiling at z = P.z + 2
    hit.hitdist = 2 * lobe::length(R) / R.z;
    hit.P = P + R * (2 / R.z);
    hit.N = hit.Ng = {0, 0, -1};
    hit.u = 0.25f;
    hit.v = 0.75f;
    return true;
  }

private:
  mutable char buf_[32] = {};
};

class Services : public ::testing::TestWithParam<int> {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lobe_services_" + std::to_string(::getpid()) + "_" + std::to_string(GetParam()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    fs::path p = dir_ / (name + ".osl");
    std::ofstream(p) << text;
    return p.string();
  }

  // Compiles `g` (layers named by shader file stem) and shades a W x 1 grid; returns the
  // printed output (source paths shortened to file names).
  std::string shade(lobe::ShaderGroup g, int w, const lobe::RendererServices* rs) {
    lobe::ShadingSystem ss;
    ss.options().opt_level = GetParam();
    ss.options().specialize = GetParam() > 0;
    lobe::DiagnosticList diags;
    auto mat = ss.compile(g, diags);
    std::string err;
    for (auto& d : diags) err += d.text + "\n";
    EXPECT_TRUE(mat) << err;
    if (!mat) return "";
    lobe::ShadingContext ctx;
    ctx.renderer = rs;
    lobe::group::GridSpec grid{w, 1, false, lobe::kRayCamera};
    for (int x = 0; x < w; ++x) {
      ctx.reset();
      lobe::ShaderGlobals sg = lobe::group::grid_globals(grid, x, 0, &ctx);
      mat->shade(sg);
    }
    std::string out = ctx.output, prefix = dir_.string() + "/";
    for (size_t at; (at = out.find(prefix)) != std::string::npos;) out.erase(at, prefix.size());
    return out;
  }

  // Layers "up" then "down", with up.out connected to down.in.
  static lobe::ShaderGroup chain(const std::string& up, const std::string& down) {
    lobe::ShaderGroup g;
    g.layers.push_back({up, "up", {}});
    g.layers.push_back({down, "down", {}});
    g.connections.push_back({"up", "out", "down", "in"});
    return g;
  }

  lobe::ShaderGroup one(const std::string& path, std::vector<lobe::InstanceValue> values = {}) {
    lobe::ShaderGroup g;
    g.layers.push_back({path, fs::path(path).stem().string(), std::move(values)});
    return g;
  }

  fs::path dir_;
};

const char* kUserData = R"(
surface ud(float Kd = 0.5 [[ int lockgeom = 0 ]],
           color tint = 1 [[ int lockgeom = 0 ]],
           string label = "default" [[ int lockgeom = 0 ]],
           int ids[3] = {1, 2, 3} [[ int lockgeom = 0 ]],
           float refuse = 5 [[ int lockgeom = 0 ]],
           float locked = 6,
           float twice = 2 * Kd [[ int lockgeom = 0 ]]) {
  printf("Kd %g dx %g dy %g | tint %g | %s | ids %d %d %d | refuse %g locked %g twice %g\n",
         Kd, Dx(Kd), Dy(Kd), tint, label, ids[0], ids[1], ids[2], refuse, locked, twice);
}
)";

TEST_P(Services, UserDataOverridesInstanceValuesAndDefaults) {
  std::string f = write("ud", kUserData);
  TestServices rs;
  // u = 0 and 1 on a 2 x 1 grid, dudx = 1: Kd = 10u with d/dx 10.
  EXPECT_EQ(shade(one(f, {{"float", "Kd", "0.125"}, {"float", "locked", "7"}}), 2, &rs),
            "Kd 0 dx 10 dy 0 | tint 0.25 0.5 0.75 | from the renderer | ids 7 8 9 | refuse 5 "
            "locked 7 twice 0\n"
            "Kd 10 dx 10 dy 0 | tint 0.25 0.5 0.75 | from the renderer | ids 7 8 9 | refuse 5 "
            "locked 7 twice 20\n");
  // `locked` has no lockgeom = 0: never asked. `twice` was asked, refused, and its computed
  // default then read the user data of Kd (2 * 10u).
  for (const std::string& a : rs.asked) EXPECT_EQ(a.find("locked"), std::string::npos) << a;
  EXPECT_NE(std::find(rs.asked.begin(), rs.asked.end(), "twice:float:-"), rs.asked.end());
  EXPECT_NE(std::find(rs.asked.begin(), rs.asked.end(), "Kd:float:d"), rs.asked.end());
}

TEST_P(Services, WithoutUserDataTheInstanceValueOrDefaultStays) {
  std::string f = write("ud", kUserData);
  std::string expected = "Kd 0.125 dx 0 dy 0 | tint 1 1 1 | default | ids 1 2 3 | refuse 5 "
                         "locked 6 twice 0.25\n";
  EXPECT_EQ(shade(one(f, {{"float", "Kd", "0.125"}}), 1, nullptr), expected); // no renderer
  lobe::RendererServices none;                                                // knows nothing
  EXPECT_EQ(shade(one(f, {{"float", "Kd", "0.125"}}), 1, &none), expected);
}

TEST_P(Services, InstanceLockgeomTurnsBindingOnAndOff) {
  std::string f = write("ud", kUserData);
  TestServices rs;
  lobe::InstanceValue kd{"float", "Kd", "0.125", 1}; // locked by the instance
  lobe::InstanceValue locked{"float", "locked", "3", 0};
  EXPECT_EQ(shade(one(f, {kd, locked}), 1, &rs),
            "Kd 0.125 dx 0 dy 0 | tint 0.25 0.5 0.75 | from the renderer | ids 7 8 9 | refuse 5 "
            "locked 3 twice 0.25\n");
  EXPECT_NE(std::find(rs.asked.begin(), rs.asked.end(), "locked:float:-"), rs.asked.end());
  for (const std::string& a : rs.asked) EXPECT_NE(a.rfind("Kd:", 0), 0u) << a;
}

TEST_P(Services, ConnectionBeatsUserData) {
  std::string up = write("up", "shader up(output float out = 0.75) { out = 0.75; }\n");
  std::string ud = write("ud", kUserData);
  lobe::ShaderGroup g;
  g.layers.push_back({up, "up", {}});
  g.layers.push_back({ud, "ud", {}});
  g.connections.push_back({"up", "out", "ud", "Kd"});
  TestServices rs;
  std::string out = shade(g, 1, &rs);
  EXPECT_EQ(out.substr(0, out.find('|')), "Kd 0.75 dx 0 dy 0 ");
  for (const std::string& a : rs.asked) EXPECT_NE(a.rfind("Kd:", 0), 0u) << a;
}

TEST_P(Services, GroupTextCarriesLockgeom) {
  std::string f = write("ud", kUserData);
  lobe::ShadingSystem ss;
  lobe::DiagnosticList diags;
  auto g = ss.parse_group("param float Kd 0.125 [[ int lockgeom = 1 ]] ;\n"
                          "param float locked 4 [[int lockgeom=0]] ;\n"
                          "shader \"" +
                              f + "\" ud ;",
                          "group", diags);
  ASSERT_TRUE(g);
  ASSERT_EQ(g->layers[0].values.size(), 2u);
  // lockgeom = 1 locks nothing (OSL 1.13.12: the shader's lockgeom = 0 Kd still takes the
  // user data); lockgeom = 0 unlocks.
  EXPECT_EQ(g->layers[0].values[0].lockgeom, -1);
  EXPECT_EQ(g->layers[0].values[0].value, "0.125");
  EXPECT_EQ(g->layers[0].values[1].lockgeom, 0);
  TestServices rs;
  std::string out = shade(*g, 1, &rs);
  EXPECT_EQ(out.substr(0, out.find('|')), "Kd 5 dx 10 dy 0 ");
}

TEST_P(Services, GetAttribute) {
  std::string f = write("attrs", R"(
surface attrs() {
  int ver = 0; string sn = "?", ln = "?", gn = "?";
  float clip[2] = {-1, -1}, far = -1, untouched = -7, s = -8;
  point lp = 0; int wrong = -9;
  int a = getattribute("osl:version", ver);
  int b = getattribute("shader:shadername", sn) + getattribute("shader:layername", ln) +
          getattribute("shader:groupname", gn);
  int c = getattribute("camera:clip", clip);
  int d = getattribute("camera:clip", 1, far);
  int e = getattribute("light1", "position", lp);
  int g = getattribute("scribble", untouched) + getattribute("nothing", s) +
          getattribute("shader:shadername", wrong);
  printf("%d %d %s %s '%s' | %d %g %g | %d %g | %d %g | %d %g %g %d | %d\n", a, ver == OSL_VERSION,
         sn, ln, gn, c, clip[0], clip[1], d, far, e, lp, g, untouched, s, wrong, b);
}
)");
  TestServices rs;
  lobe::ShaderGroup g = one(f);
  g.name = "grp";
  g.layers[0].name = "L1";
  EXPECT_EQ(shade(g, 1, &rs),
            "1 1 attrs L1 'grp' | 1 0.5 1000 | 1 1000 | 1 1 2 3 | 0 -7 -8 -9 | 3\n");
  EXPECT_NE(std::find(rs.asked.begin(), rs.asked.end(), "attr /camera:clip[1]:float"),
            rs.asked.end());
  EXPECT_NE(std::find(rs.asked.begin(), rs.asked.end(), "attr light1/position[-1]:point"),
            rs.asked.end());
  // Lobe's own attributes never reach the renderer.
  for (const std::string& a : rs.asked) EXPECT_EQ(a.find("osl:"), std::string::npos) << a;
  // Without a renderer, only Lobe's own attributes answer.
  EXPECT_EQ(shade(g, 1, nullptr),
            "1 1 attrs L1 'grp' | 0 -1 -1 | 0 -1 | 0 0 0 0 | 0 -7 -8 -9 | 3\n");
}

TEST_P(Services, MessagesBetweenLayers) {
  std::string up = write("up", R"(
shader up(float k = 0.25, output float out = 0) {
  setmessage("weight", k * 2);
  setmessage("tint", color(1, 0.5, 0.25));
  string nm[2] = {"a", "b"};
  setmessage("names", nm);
  if (u > 0.5) setmessage("right", 1);
  if (u < 2) out = k;
}
)");
  std::string down = write("down", R"(
surface down(float in = 0) {
  float w = -1, x = in; color c = 0; vector vv = 0; string n[2]; int i = -1, r = -1;
  int a = getmessage("weight", w);
  int b = getmessage("tint", c);
  int d = getmessage("names", n);
  int e = getmessage("tint", vv);
  int f = getmessage("trace", "weight", x);
  int g = getmessage("right", r);
  printf("%g | %d %g | %d %g | %d %s %s | %d %g | %d | %d %d\n", in, a, w, b, c, d, n[0], n[1],
         e, vv, f, g, r);
  setmessage("tint", color(0));
}
)");
  lobe::ShaderGroup g = chain(up, down);
  // u = 0, then 1: "right" exists only at the second point, so messages do not leak from one
  // shade to the next. (`out` is written in a branch: were it an unconditional constant copy, OSL
  // -O2 would pass the value on and not run `up` at all, its messages with it, as Lobe does.)
  EXPECT_EQ(shade(g, 2, nullptr),
            "ERROR: type mismatch for message \"tint\" (created as color here: up.osl:4) cannot "
            "fetch as vector from down.osl:7\n"
            "0.25 | 1 0.5 | 1 1 0.5 0.25 | 1 a b | 0 0 0 0 | 0 | 0 -1\n"
            "ERROR: message \"tint\" already exists (created here: up.osl:4) cannot set again "
            "from down.osl:12\n"
            "ERROR: type mismatch for message \"tint\" (created as color here: up.osl:4) cannot "
            "fetch as vector from down.osl:7\n"
            "0.25 | 1 0.5 | 1 1 0.5 0.25 | 1 a b | 0 0 0 0 | 0 | 1 1\n"
            "ERROR: message \"tint\" already exists (created here: up.osl:4) cannot set again "
            "from down.osl:12\n");
}

TEST_P(Services, MessageQueriedBeforeItIsSet) {
  std::string up = write("up", "shader up(output float out = 0) { setmessage(\"m\", 2.0); "
                               "out = 1; }\n");
  std::string down = write("down", R"(
surface down(float in = 0) {
  float m = -1;
  int early = getmessage("m", m);
  float x = in;
  int late = getmessage("m", m);
  printf("%d %d %g %g\n", early, late, m, x);
}
)");
  lobe::ShaderGroup g = chain(up, down);
  // The upstream layer runs lazily, when `in` is first read: after the first query. At -O2 its
  // output is a known constant, so it does not run at all, and its setmessage does not happen
  // (as OSL 1.13.12: `testshade -O2 -layer A up -layer B down -connect A out B in` prints no
  // error, -O0 prints it).
  EXPECT_EQ(shade(g, 1, nullptr),
            std::string(GetParam() >= 2
                            ? ""
                            : "ERROR: message \"m\" was queried before being set (queried here: "
                              "down.osl:4) setting it now (up.osl:1) would lead to inconsistent "
                              "results\n") +
                "0 0 -1 1\n");
}

INSTANTIATE_TEST_SUITE_P(Opt, Services, ::testing::Values(0, 2),
                         [](const ::testing::TestParamInfo<int>& i) {
                           return "O" + std::to_string(i.param);
                         });

} // namespace

namespace {

// A UDIM name looks up the tile at (s, t) (OpenImageIO resolves it per lookup: u in [0, 1) is
// tile 1001, [1, 2) tile 1002); a tile that does not exist is a lookup of nothing.
TEST_P(Services, TextureLooksUpUdimTiles) {
  std::ofstream(dir_ / "t.1001.ppm") << "P3\n1 1\n255\n255 0 0\n";
  std::ofstream(dir_ / "t.1002.ppm") << "P3\n1 1\n255\n0 255 0\n";
  std::string f = write("udim", R"(
surface udim(string file = "") {
  color a = texture(file, 0.5, 0.5, "wrap", "clamp", "interp", "closest");
  color b = texture(file, 1.5, 0.5, "wrap", "clamp", "interp", "closest");
  printf("%g | %g\n", a, b);
}
)");
  std::string out =
      shade(one(f, {{"string", "file", (dir_ / "t.<UDIM>.ppm").string()}}), 1, nullptr);
  EXPECT_EQ(out, "1 0 0 | 0 1 0\n");
}

TEST_P(Services, GetTextureInfo) {
  // A 4 x 2 RGB image in the plain-text PPM format, which OpenImageIO reads.
  fs::path img = dir_ / "tex.ppm";
  std::ofstream(img) << "P3\n4 2\n255\n"
                        "255 0 0  0 255 0  0 0 255  255 255 255\n"
                        "0 0 0  10 20 30  40 50 60  70 80 90\n";
  std::string f = write("info", R"(
surface info(string file = "", string missing = "") {
  int res[2] = {-1, -1}, ch = -1, e1 = -1, e2 = -1, bad[2] = {-5, -5};
  int a = gettextureinfo(file, "resolution", res);
  int b = gettextureinfo(file, "channels", ch);
  int c = gettextureinfo(file, "exists", e1);
  int d = gettextureinfo(missing, "exists", e2);
  printf("%d %d %d | %d %d | %d %d | %d %d\n", a, res[0], res[1], b, ch, c, e1, d, e2);
  int g = gettextureinfo(missing, "resolution", bad);
  printf("%d %d %d\n", g, bad[0], bad[1]);
}
)");
  std::string missing = (dir_ / "no_such.exr").string();
  std::string out =
      shade(one(f, {{"string", "file", img.string()}, {"string", "missing", missing}}), 1, nullptr);
  // The error text is OpenImageIO's; its first line names the file.
  EXPECT_EQ(out.substr(0, out.find('\n') + 1), "1 4 2 | 1 3 | 1 1 | 1 0\n") << out;
  // OSL 1.13.12 words it by how it looks the file up: a name constant at -O2 (here an
  // instance value) is the shader's error, otherwise the renderer's (testshade -O0 / -O2 on
  // gettextureinfo of a missing file).
  EXPECT_NE(out.find(GetParam() >= 2 ? "ERROR: Shader error [info]: Invalid image file "
                                     : "ERROR: [RendererServices::get_texture_info] "),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("no_such.exr"), std::string::npos) << out;
  EXPECT_EQ(out.substr(out.rfind('\n', out.size() - 2) + 1), "0 -5 -5\n") << out;
}

} // namespace

namespace {

TEST_P(Services, TraceAndItsMessages) {
  std::string f = write("tr", R"(
surface tr() {
  float d = -1, hu = -1; point p = 0; normal n = 0; int h = -1;
  int before = getmessage("trace", "hit", h);
  int up = trace(P, vector(0, 0, 1), "mindist", 0.5, "maxdist", 10, "traceset", "walls");
  int a = getmessage("trace", "hit", h) + getmessage("trace", "hitdist", d) +
          getmessage("trace", "P", p) + getmessage("trace", "N", n) + getmessage("trace", "u", hu);
  printf("%d | %d %d %d %g %g | %g %g\n", before, up, a, h, d, p, n, hu);
  int down = trace(P, vector(0, 0, -1), "shade", 1);
  int b = getmessage("trace", "hit", h) + getmessage("trace", "hitdist", d);
  printf("%d %d %d %g\n", down, b, h, d);
}
)");
  TestServices rs;
  // Grid point 0 of 1 x 1: P = (0.5, 0.5, 1), dPdx = (1, 0, 0).
  EXPECT_EQ(shade(one(f), 1, &rs), "0 | 1 5 1 2 0.5 0.5 3 | 0 0 -1 0.25\n0 1 0 2\n");
  ASSERT_EQ(rs.asked.size(), 2u);
  EXPECT_EQ(rs.asked[0], "trace 0.500000 10.000000 0 'walls' dPdx.x 1.000000 dRdx.x 0.000000");
  EXPECT_EQ(rs.asked[1], "trace 0.000000 1000000015047466219876688855040.000000 1 '' dPdx.x "
                         "1.000000 dRdx.x 0.000000");
  // Without a renderer nothing is hit, and "hit" says so.
  EXPECT_EQ(shade(one(f), 1, nullptr), "0 | 0 1 0 -1 0 0 0 | 0 0 0 -1\n0 1 0 -1\n");
}

} // namespace

namespace {

// Queries whose results go unused still happen, at every -O level: getmessage is remembered
// (so the later setmessage is an error) and gettextureinfo reports its error.
TEST_P(Services, UnusedQueriesStillCount) {
  std::string up = write("up", "shader up(output float out = 0) { setmessage(\"m\", 2.0); "
                               "out = 1; }\n");
  std::string down = write("down", R"(
surface down(float in = 0) {
  float m = -1;
  getmessage("m", m);
  int r[2];
  gettextureinfo("/nonexistent/lobe_no_such.exr", "resolution", r);
  float x = in;
}
)");
  lobe::ShaderGroup g = chain(up, down);
  std::string out = shade(g, 1, nullptr);
  EXPECT_NE(out.find(GetParam() >= 2 ? "ERROR: Shader error [down]: Invalid image file "
                                     : "ERROR: [RendererServices::get_texture_info] "),
            std::string::npos)
      << out;
  // At -O2 the upstream layer (a constant output) does not run, so nothing sets the message
  // (OSL 1.13.12's testshade -O2 likewise reports only the texture error).
  EXPECT_EQ(out.find("ERROR: message \"m\" was queried before being set (queried here: "
                     "down.osl:4) setting it now (up.osl:1)") != std::string::npos,
            GetParam() < 2)
      << out;
}

// A message set by a later layer (which ran first, lazily) is not handed to an earlier one.
TEST_P(Services, MessagesOnlyFlowDownstream) {
  std::string up = write("up", R"(
shader up(output float out = 0) {
  float m = -1;
  int got = getmessage("m", m);
  printf("upstream got %d %g\n", got, m);
  out = 1;
}
)");
  std::string down = write("down", R"(
surface down(float in = 0) {
  setmessage("m", 2.0);
  float x = in;
}
)");
  lobe::ShaderGroup g = chain(up, down);
  // At -O2 the upstream layer (a constant output) does not run at all, as in OSL 1.13.12
  // (`testshade -O2` of the same group prints nothing).
  EXPECT_EQ(shade(g, 1, nullptr),
            GetParam() >= 2 ? ""
                            : "ERROR: message \"m\" was set by layer #3 (down.osl:3) but is being "
                              "queried by layer #2 (up.osl:4) - messages may only be transferred "
                              "from nodes that appear earlier in the shading network\nupstream "
                              "got 0 -1\n");
}

// An index the shader gives is an element number: a negative one finds nothing (and is not
// taken for "no index").
TEST_P(Services, NegativeAttributeIndexFindsNothing) {
  std::string f = write("neg", R"(
surface neg(int i = -1) {
  float far = -3;
  int a = getattribute("camera:clip", i, far);
  int b = getattribute("camera:clip", 1, far);
  printf("%d %d %g\n", a, b, far);
}
)");
  TestServices rs;
  EXPECT_EQ(shade(one(f), 1, &rs), "0 1 1000\n");
  for (const std::string& a : rs.asked) EXPECT_EQ(a.find("[-1]"), std::string::npos) << a;
}

} // namespace

TEST(DataType, ParseIsTheReverseOfStr) {
  for (const char* s : {"int", "float", "color", "point", "vector", "normal", "matrix", "string",
                        "float[2]", "color[10]", "string[3]"}) {
    std::optional<DataType> t = DataType::parse(s);
    ASSERT_TRUE(t) << s;
    EXPECT_EQ(t->str(), s);
  }
  EXPECT_EQ(DataType::parse("int[2]"), (DataType{B::Int, 2}));
  for (const char* s : {"", "closure color", "floats", "float[0]", "float[", "float[2", "S"})
    EXPECT_FALSE(DataType::parse(s)) << s;
}
