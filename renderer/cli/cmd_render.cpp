// `lobe render`: renders a scene (JSON or OSL testrender XML; with no file, the built-in
// material preview) to EXR (linear, with albedo/normal/depth AOVs) or PNG (tone-mapped sRGB).
// Scene settings are defaults that the flags override. Progress on stderr; Ctrl-C stops the
// render and writes what is finished.
#include "command.h"

#include "default_scene.h"
#include "image.h"
#include "material_backend.h"
#include "memory_check.h"
#include "native_materials.h"
#include "renderer.h"
#include "scene.h"

#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <unistd.h>

namespace {

// The one piece of process-global state: what a signal handler may touch.
std::atomic<bool> g_cancel{false};
extern "C" void on_sigint(int) { g_cancel.store(true); }

// Prints a progress line at most every 0.25 s: percentage, samples/s and time left.
class ProgressBar {
public:
  explicit ProgressBar(bool enabled) : enabled_(enabled), t0_(clock::now()) {}
  void update(uint64_t done, uint64_t total) {
    if (!enabled_) return;
    std::lock_guard<std::mutex> lock(mu_);
    auto now = clock::now();
    if (done < total && now - last_ < std::chrono::milliseconds(250)) return;
    last_ = now;
    double el = std::chrono::duration<double>(now - t0_).count();
    double rate = el > 0 ? double(done) / el : 0;
    double left = rate > 0 ? double(total - done) / rate : 0;
    int width = 30, fill = total ? int(width * double(done) / double(total)) : width;
    std::fprintf(stderr, "\r[%s%s] %5.1f%%  %.2f Msamples/s  %.1fs left   ",
                 std::string(fill, '#').c_str(), std::string(width - fill, '.').c_str(),
                 total ? 100.0 * double(done) / double(total) : 100.0, rate / 1e6, left);
    std::fflush(stderr);
  }
  void finish() {
    if (enabled_) std::fprintf(stderr, "\n");
  }

private:
  using clock = std::chrono::steady_clock;
  bool enabled_;
  clock::time_point t0_, last_{};
  std::mutex mu_;
};

struct Args {
  std::string scene, output, backend = "auto", strategy = "mis", closures = "jit";
  std::string colorspace = "Rec709";
  std::vector<int> res;
  int spp = 0, threads = 0, max_depth = 0;
  long long seed = -1;
  long long max_loop_iterations = 100000000;
  float exposure = 0;
  bool quiet = false;
};

lobe::render::Strategy parse_strategy(const std::string& s) {
  if (s == "bsdf") return lobe::render::Strategy::BsdfOnly;
  if (s == "light") return lobe::render::Strategy::LightOnly;
  return lobe::render::Strategy::Mis;
}

int run_render(int argc, char** argv) {
  CLI::App app{"Render a scene with the path tracer", "lobe render"};
  Args a;
  app.add_option("scene", a.scene, "scene file (.json or .xml); default: the built-in preview");
  app.add_option("-o,--output", a.output, "output image (.exr with AOVs, or .png)");
  app.add_option("--spp", a.spp, "samples per pixel")->check(CLI::Range(1, 1 << 20));
  app.add_option("--res", a.res, "resolution: W H")->expected(2)->check(CLI::Range(1, 16384));
  app.add_option("--threads", a.threads, "worker threads (0: all cores)")
      ->check(CLI::Range(0, 1024));
  app.add_option("--seed", a.seed, "random seed")->check(CLI::Range(0LL, 1LL << 40));
  app.add_option("--max-depth", a.max_depth, "maximum bounces")->check(CLI::Range(1, 1024));
  app.add_option("--exposure", a.exposure, "exposure in stops for PNG output");
  app.add_option("--materials", a.backend, "material backend: auto, jit or native")
      ->check(CLI::IsMember({"auto", "jit", "native"}));
  app.add_option("--closures", a.closures,
                 "closure evaluation for JIT materials: jit (kernels compiled from the closure "
                 "library's bitcode, inlined per material) or native")
      ->check(CLI::IsMember({"jit", "native"}));
  app.add_option("--strategy", a.strategy, "light transport: mis, bsdf or light")
      ->check(CLI::IsMember({"mis", "bsdf", "light"}));
  app.add_option("--colorspace", a.colorspace,
                 "RGB space of shader colours (Rec709, sRGB, NTSC, EBU, PAL, SECAM, SMPTE, HDTV, "
                 "CIE, AdobeRGB, ACEScg): transformc, luminance, blackbody, wavelength_color");
  app.add_option("--max-loop-iterations", a.max_loop_iterations,
                 "stop a shade whose loops run more than this many iterations, with an error "
                 "(0: unlimited, -1: no checks)")
      ->check(CLI::Range(-1LL, 1LL << 62));
  app.add_flag("-q,--quiet", a.quiet, "no progress or summary");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }

  std::string err;
  lobe::scene::SceneDesc desc;
  if (a.scene.empty()) {
    desc = lobe::render::default_scene();
  } else {
    auto s = lobe::scene::load_scene(a.scene, err);
    if (!s) {
      std::fprintf(stderr, "lobe render: %s\n", err.c_str());
      return 1;
    }
    desc = std::move(*s);
  }
  for (const std::string& w : desc.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  lobe::scene::Settings& st = desc.settings;
  if (a.res.size() == 2) st.width = a.res[0], st.height = a.res[1];
  if (a.spp) st.spp = a.spp;
  if (a.max_depth) st.max_depth = a.max_depth;
  if (a.seed >= 0) st.seed = uint64_t(a.seed);
  if (app.count("--exposure")) st.exposure = a.exposure;
  std::string out = !a.output.empty() ? a.output : (!st.output.empty() ? st.output : "lobe.png");
  // A bad output path is found now, not after a long render.
  if (std::string e = lobe::image::check_writable(out); !e.empty()) {
    std::fprintf(stderr, "lobe render: %s\n", e.c_str());
    return 1;
  }

  // The image's cost, checked before anything is allocated: per pixel the accumulator (44
  // bytes), the resolved image and the writer's copy (4 bytes a channel each).
  {
    double channels = lobe::image::keeps_all_channels(out) ? 10 : 3;
    double bytes = double(st.width) * double(st.height) * (44 + 2 * 4 * channels);
    std::string setting = (a.res.size() == 2 ? "--res " : "resolution ") +
                          std::to_string(st.width) + " " + std::to_string(st.height);
    if (std::string e = lobe::cli::check_memory(setting, bytes, "the image and its samples");
        !e.empty()) {
      std::fprintf(stderr, "lobe render: %s\n", e.c_str());
      return 1;
    }
  }

  // Shaders are found next to the scene file (whatever the working directory), then in
  // stdlib_shaders/.
  std::vector<std::string> shader_dirs;
  if (!a.scene.empty())
    shader_dirs.push_back(std::filesystem::absolute(a.scene).parent_path().string());
  lobe::render::MaterialBackend backend(a.backend, shader_dirs, lobe::render::native_compiler());
  // An unknown colour space is reported and Rec709 used, as testshade does.
  if (std::string e = backend.set_colorspace(a.colorspace); !e.empty())
    std::fprintf(stderr, "ERROR: %s\n", e.c_str());
  backend.set_max_loop_iterations(a.max_loop_iterations);
  lobe::render::RenderScene scene;
  scene.use_closure_kernels(a.closures == "jit");
  scene.set_cancel(&g_cancel);
  // Ctrl-C from here on stops at the next stage (or loop check) and says where.
  std::signal(SIGINT, on_sigint);
  auto t0 = std::chrono::steady_clock::now();
  if (std::string e = scene.setup(desc, backend.compiler(), st.width, st.height); !e.empty()) {
    std::signal(SIGINT, SIG_DFL);
    std::fprintf(stderr, "lobe render: %s\n", e.c_str());
    return g_cancel.load() ? 130 : 1;
  }
  double setup_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const std::string& w : backend.warnings()) std::fprintf(stderr, "warning: %s\n", w.c_str());
  for (const std::string& w : scene.stats().warnings)
    std::fprintf(stderr, "warning: %s\n", w.c_str());

  lobe::render::RenderOptions opt;
  opt.spp = st.spp;
  opt.max_depth = st.max_depth;
  opt.seed = st.seed;
  opt.threads = a.threads;
  opt.strategy = parse_strategy(a.strategy);
  opt.aovs = lobe::image::keeps_all_channels(out); // AOV channels only where they are kept
  ProgressBar bar(!a.quiet && isatty(STDERR_FILENO));
  lobe::render::RenderStats stats;
  lobe::image::Image img = lobe::render::render_image(
      scene, st.width, st.height, opt, &g_cancel, [&](uint64_t d, uint64_t t) { bar.update(d, t); },
      &stats);
  std::signal(SIGINT, SIG_DFL);
  bar.finish();

  // Shader run-time messages (a texture that cannot be read, error()...), once each with a
  // count, after the progress bar.
  lobe::render::ShaderMessages messages = scene.stats().messages;
  lobe::render::merge_messages(stats.counters.messages, messages);
  for (const std::string& m : scene.describe(messages))
    std::fprintf(stderr, "warning: %s\n", m.c_str());
  if (!stats.stopped.empty()) { // a runaway shader: an error, no image
    std::fprintf(stderr, "lobe render: %s; rendering stopped, no image written\n",
                 stats.stopped.c_str());
    return 1;
  }

  lobe::image::WriteOptions wo;
  wo.exposure = st.exposure;
  wo.tonemap = lobe::image::ToneMap::Filmic;
  if (std::string e = lobe::image::write_image(out, img, wo); !e.empty()) {
    std::fprintf(stderr, "lobe render: %s\n", e.c_str());
    return 1;
  }
  if (!a.quiet || stats.cancelled) { // an interrupted render always says so
    uint64_t rays = stats.counters.rays + stats.counters.shadow_rays;
    // Interrupted: how many samples per pixel finished (pixels of the last, partial pass have
    // one more), e.g. "8.4 of 32 spp".
    char spp[64];
    if (stats.cancelled)
      std::snprintf(spp, sizeof spp, "%.1f of %d spp",
                    double(stats.samples) / (double(st.width) * st.height), st.spp);
    else
      std::snprintf(spp, sizeof spp, "%d spp", st.spp);
    std::fprintf(stderr,
                 "%s%s: %dx%d, %s, %s materials (%d compiled in %.2fs, %d with closure "
                 "kernels, %d from the cache, setup %.2fs), render %.2fs, %.2f Mrays/s\n",
                 stats.cancelled ? "interrupted: wrote the finished samples to " : "wrote ",
                 out.c_str(), st.width, st.height, spp, backend.name().c_str(),
                 scene.stats().materials_compiled, scene.stats().compile_seconds,
                 scene.stats().closure_kernels, scene.stats().closure_kernels_cached, setup_s,
                 stats.seconds, stats.seconds > 0 ? double(rays) / stats.seconds / 1e6 : 0.0);
  }
  return stats.cancelled ? 130 : 0;
}

} // namespace

LOBE_COMMAND(render, "render a scene (or the built-in material preview) to EXR/PNG", run_render);
