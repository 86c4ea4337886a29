// `lobe render`: renders a scene (JSON or OSL testrender XML; with no file, the built-in
// material preview) to EXR (linear, with albedo/normal/depth AOVs) or PNG (tone-mapped sRGB).
// Scene settings are defaults that the flags override. Progress on stderr; Ctrl-C stops the
// render and writes what is finished.
#include "command.h"

#include "default_scene.h"
#include "image.h"
#include "lobe/bsdf.h"
#include "lobe/memory.h"
#include "material_backend.h"
#include "native_materials.h"
#include "renderer.h"
#include "scene.h"

#include <CLI/CLI.hpp>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <thread>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <unistd.h>

namespace {

// The one piece of process-global state: what a signal handler may touch.
std::atomic<bool> g_cancel{false};
extern "C" void on_sigint(int) { g_cancel.store(true); }

// Progress on stderr. Bar: one line redrawn at most every 0.25 s (percentage, samples/s, time
// left). Lines: a line at each further 10% (for logs, where a redrawn line is noise).
class ProgressBar {
public:
  enum class Mode { None, Bar, Lines };
  explicit ProgressBar(Mode mode) : mode_(mode), t0_(clock::now()) {}
  void update(uint64_t done, uint64_t total) {
    if (mode_ == Mode::None) return;
    std::lock_guard<std::mutex> lock(mu_);
    auto now = clock::now();
    double frac = total ? double(done) / double(total) : 1.0;
    double el = std::chrono::duration<double>(now - t0_).count();
    double rate = el > 0 ? double(done) / el : 0;
    double left = rate > 0 ? double(total - done) / rate : 0;
    if (mode_ == Mode::Lines) {
      int tenth = int(frac * 10 + 1e-9);
      if (tenth <= last_tenth_) return;
      last_tenth_ = tenth;
      std::fprintf(stderr, "render: %3d%%  %.1fs elapsed, %.1fs left\n", tenth * 10, el, left);
      std::fflush(stderr);
      return;
    }
    if (done < total && now - last_ < std::chrono::milliseconds(250)) return;
    last_ = now;
    int width = 30, fill = int(width * frac);
    std::fprintf(stderr, "\r[%s%s] %5.1f%%  %.2f Msamples/s  %.1fs left   ",
                 std::string(fill, '#').c_str(), std::string(width - fill, '.').c_str(),
                 100.0 * frac, rate / 1e6, left);
    std::fflush(stderr);
  }
  void finish() {
    if (mode_ == Mode::Bar) std::fprintf(stderr, "\n");
  }

private:
  using clock = std::chrono::steady_clock;
  Mode mode_;
  clock::time_point t0_, last_{};
  int last_tenth_ = 0;
  std::mutex mu_;
};

struct Args {
  std::string scene, output, backend = "auto", strategy = "mis", closures = "jit";
  std::string colorspace = "Rec709";
  std::string filter; // "": the scene's
  std::vector<int> res;
  int spp = 0, threads = 0, max_depth = 0;
  long long seed = -1;
  long long max_loop_iterations = 100000000;
  float exposure = 0, clamp = -1, light_paths = 0.1f;
  bool quiet = false, stats = false, no_aovs = false;
  std::string progress = "auto";
};

lobe::render::Strategy parse_strategy(const std::string& s) {
  if (s == "bsdf") return lobe::render::Strategy::BsdfOnly;
  if (s == "light") return lobe::render::Strategy::LightOnly;
  return lobe::render::Strategy::Mis;
}

// --stats: where the time went, set-up by stage and the render by phase, with the rates.
void print_stats(const lobe::render::RenderScene& scene, const lobe::scene::SceneDesc& desc,
                 double load_s, double setup_s, const lobe::render::RenderStats& stats,
                 const lobe::scene::Settings& st, int threads_opt) {
  const lobe::render::SetupStats& ss = scene.stats();
  size_t triangles = 0;
  for (const auto& sh : desc.shapes) triangles += sh.mesh.indices.size() / 3;
  std::fprintf(stderr,
               "stats: set-up %.2fs: scene file %.2fs (%zu mesh triangles), Embree build %.2fs, "
               "materials %.2fs, environment %.2fs, lights %.2fs\n",
               load_s + setup_s, load_s, triangles, ss.geometry_seconds, ss.compile_seconds,
               ss.environment_seconds, ss.lights_seconds);
  const lobe::render::PhaseTicks& p = stats.counters.phases;
  double total = double(p.total());
  int threads = threads_opt > 0 ? threads_opt : tbb::this_task_arena::max_concurrency();
  uint64_t rays = stats.counters.rays + stats.counters.shadow_rays;
  if (total > 0) {
    auto pc = [&](uint64_t t) { return 100.0 * double(t) / total; };
    std::fprintf(stderr,
                 "stats: render %.2fs on %d threads: traversal %.0f%%, hit data %.0f%%, shading "
                 "%.0f%%, BSDF %.0f%%, lights %.0f%%, integrator %.0f%% (of path time, 1 path "
                 "in %d timed)\n",
                 stats.seconds, threads, pc(p.traverse), pc(p.hit), pc(p.shade), pc(p.bsdf),
                 pc(p.lights), pc(p.other), lobe::render::kProfileEvery);
    // Embree's rate inside the render: the rays over the thread time spent traversing.
    double trav_s = stats.seconds * threads * double(p.traverse) / total;
    std::fprintf(
        stderr,
        "stats: %.2f Mrays/s (%llu closest-hit + %llu shadow rays, %llu shades); "
        "traversal alone in the render %.2f Mrays/s\n",
        stats.seconds > 0 ? double(rays) / stats.seconds / 1e6 : 0.0,
        (unsigned long long)stats.counters.rays, (unsigned long long)stats.counters.shadow_rays,
        (unsigned long long)stats.counters.shades, trav_s > 0 ? double(rays) / trav_s / 1e6 : 0.0);
  }
  if (stats.counters.light_paths)
    std::fprintf(
        stderr,
        "stats: %llu light paths for caustics of the environment (%llu camera "
        "connections), %.0f%% of the render's thread time\n",
        (unsigned long long)stats.counters.light_paths, (unsigned long long)stats.counters.splats,
        stats.seconds > 0 ? 100.0 * stats.counters.light_seconds / (stats.seconds * threads) : 0.0);
  uint64_t raw_rays = 0;
  double raw = lobe::render::raw_traversal_rate(scene, st.width, st.height, std::min(st.spp, 4),
                                                threads_opt, raw_rays);
  std::fprintf(stderr,
               "stats: Embree raw traversal %.2f Mrays/s (%llu camera + diffuse-bounce "
               "closest-hit rays, no shading, %d threads)\n",
               raw / 1e6, (unsigned long long)raw_rays, threads);
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
  app.add_option("--clamp", a.clamp,
                 "luminance cap on each indirect contribution (light reaching a path after its "
                 "first bounce), against fireflies from caustics; biased; 0: none (default: the "
                 "scene's settings.clamp)")
      ->check(CLI::Range(0.0f, 3.4e38f));
  app.add_option("--filter", a.filter,
                 "pixel filter: box (one pixel) or tent (two pixels wide, testrender's) "
                 "(default: the scene's settings.pixel_filter; box, or tent for .xml scenes)")
      ->check(CLI::IsMember({"box", "tent"}));
  app.add_option("--materials", a.backend, "material backend: auto, jit or native")
      ->check(CLI::IsMember({"auto", "jit", "native"}));
  app.add_option("--closures", a.closures,
                 "closure evaluation for JIT materials: jit (kernels compiled from the closure "
                 "library's bitcode, inlined per material, on a background thread while the "
                 "render starts on the native library: same bits), jit-setup (kernels compiled "
                 "before rendering) or native")
      ->check(CLI::IsMember({"jit", "jit-setup", "native"}));
  app.add_option("--strategy", a.strategy, "light transport: mis, bsdf or light")
      ->check(CLI::IsMember({"mis", "bsdf", "light"}));
  app.add_option("--light-paths", a.light_paths,
                 "light paths from the environment per camera sample, for caustics seen through "
                 "glass and mirrors (0: none; only with an environment, a pinhole camera and "
                 "mis; not clamped by --clamp; default: the scene's settings.light_paths, "
                 "else 0.1; docs/renderer.md)")
      ->check(CLI::Range(0.0f, 64.0f));
  app.add_option("--colorspace", a.colorspace,
                 "RGB space of shader colours (Rec709, sRGB, NTSC, EBU, PAL, SECAM, SMPTE, HDTV, "
                 "CIE, AdobeRGB, ACEScg, ACES2065-1, XYZ): transformc, luminance, blackbody, "
                 "wavelength_color");
  app.add_option("--max-loop-iterations", a.max_loop_iterations,
                 "stop a shade whose loops run more than this many iterations, with an error "
                 "(0: unlimited, -1: no checks)")
      ->check(CLI::Range(-1LL, 1LL << 62));
  app.add_flag("-q,--quiet", a.quiet, "no progress or summary");
  app.add_flag("--no-aovs", a.no_aovs,
               "an .exr holds R, G, B only (no albedo, normal, depth: not computed either)");
  app.add_flag("--stats", a.stats,
               "after the summary: set-up times by stage, the render's time split (traversal, "
               "hit data, shading, BSDF, lights; sampled on one path in 8) and Embree's raw "
               "traversal rate on this scene, measured after the render");
  app.add_option("--progress", a.progress,
                 "progress on stderr: auto (a bar when stderr is a terminal), bar, lines (a "
                 "line every 10%, for logs) or none")
      ->check(CLI::IsMember({"auto", "bar", "lines", "none"}));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }

  // OpenImageIO, needed to write the image (and by textures), loads on a thread of its own
  // meanwhile, from here on: reading a scene (a large mesh is parsed on one core) leaves the
  // other core free for it. Joined on every return. Its dlopen holds the loader's locks for
  // about half a second, and this thread would wait for them wherever it loads a library or
  // starts a thread: oneTBB's allocator and thread server, which its first arena dlopens, and
  // its worker threads are made first (Embree's device and its first build would otherwise
  // wait; the JIT needs neither, jit.cpp).
  {
    tbb::task_arena first;
    first.initialize();
    first.execute([] { tbb::parallel_for(0, 1024, [](int) { std::this_thread::yield(); }); });
  }
  std::jthread image_io = lobe::image::prefetch_image_io();

  std::string err;
  lobe::scene::SceneDesc desc;
  auto t_load = std::chrono::steady_clock::now();
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
  double load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_load).count();
  for (const std::string& w : desc.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  lobe::scene::Settings& st = desc.settings;
  if (a.res.size() == 2) st.width = a.res[0], st.height = a.res[1];
  if (a.spp) st.spp = a.spp;
  if (a.max_depth) st.max_depth = a.max_depth;
  if (a.seed >= 0) st.seed = uint64_t(a.seed);
  if (app.count("--exposure")) st.exposure = a.exposure;
  if (app.count("--clamp")) st.clamp = a.clamp;
  if (app.count("--light-paths")) st.light_paths = a.light_paths;
  if (!a.filter.empty()) lobe::scene::pixel_filter_named(a.filter, st.pixel_filter); // CLI-checked
  std::string out = !a.output.empty() ? a.output : (!st.output.empty() ? st.output : "lobe.png");
  // A bad output path is found now, not after a long render. The format of a common extension
  // is confirmed once the scene is set up (OpenImageIO is loading meanwhile), before anything is
  // rendered, any other (.pfm, .xyz) at once.
  std::string e_out = lobe::image::check_output_path(out);
  if (e_out.empty() && !lobe::image::is_common_output(out))
    e_out = lobe::image::check_output_format(out);
  if (!e_out.empty()) {
    std::fprintf(stderr, "lobe render: %s\n", e_out.c_str());
    return 1;
  }

  // The image's cost, checked before anything is allocated: per pixel the accumulator (44
  // bytes), the light paths' film (24, when they may run), the resolved image and the writer's
  // copy (4 bytes a channel each).
  {
    double channels = lobe::image::keeps_all_channels(out) ? 10 : 3;
    double film = st.light_paths > 0 ? 24 : 0;
    double bytes = double(st.width) * double(st.height) * (44 + film + 2 * 4 * channels);
    std::string setting = (a.res.size() == 2 ? "--res " : "resolution ") +
                          std::to_string(st.width) + " " + std::to_string(st.height);
    if (std::string e = lobe::check_memory(setting, bytes, "the image and its samples");
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
  scene.set_kernel_mode(a.closures == "native"      ? lobe::render::KernelMode::Native
                        : a.closures == "jit-setup" ? lobe::render::KernelMode::AtSetup
                                                    : lobe::render::KernelMode::Background);
  scene.set_cancel(&g_cancel);
  // Ctrl-C from here on stops at the next stage (or loop check) and says where.
  std::signal(SIGINT, on_sigint);
  auto t0 = std::chrono::steady_clock::now();
  if (std::string e = scene.setup(std::move(desc), backend.compiler(), st.width, st.height);
      !e.empty()) {
    std::signal(SIGINT, SIG_DFL);
    std::fprintf(stderr, "lobe render: %s\n", e.c_str());
    return g_cancel.load() ? 130 : 1;
  }
  if (std::string e = lobe::image::check_output_format(out); !e.empty()) {
    std::signal(SIGINT, SIG_DFL);
    std::fprintf(stderr, "lobe render: %s\n", e.c_str());
    return 1;
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
  opt.light_paths = st.light_paths;
  // AOV channels only where they are kept, and not when declined.
  opt.aovs = lobe::image::keeps_all_channels(out) && !a.no_aovs;
  opt.profile = a.stats;
  opt.clamp = st.clamp;
  opt.pixel_filter = st.pixel_filter;
  ProgressBar::Mode mode = ProgressBar::Mode::None;
  if (!a.quiet) {
    if (a.progress == "bar" || (a.progress == "auto" && isatty(STDERR_FILENO)))
      mode = ProgressBar::Mode::Bar;
    else if (a.progress == "lines")
      mode = ProgressBar::Mode::Lines;
  }
  ProgressBar bar(mode);
  lobe::render::RenderStats stats;
  lobe::image::Image img = lobe::render::render_image(
      scene, st.width, st.height, opt, &g_cancel, [&](uint64_t d, uint64_t t) { bar.update(d, t); },
      &stats);
  std::signal(SIGINT, SIG_DFL);
  bar.finish();
  // The stats below count the kernels that came into use.
  for (const std::string& w : scene.finish_kernels())
    std::fprintf(stderr, "warning: %s\n", w.c_str());

  // Shader run-time messages (a texture that cannot be read, error()...), once each with a
  // count, after the progress bar.
  lobe::render::ShaderMessages messages = scene.stats().messages;
  lobe::render::merge_messages(stats.counters.messages, messages);
  for (const std::string& m : scene.describe(messages))
    std::fprintf(stderr, "warning: %s\n", m.c_str());
  for (const std::string& e : lobe::closure_data_errors())
    std::fprintf(stderr, "warning: %s; its lobes are black\n", e.c_str());
  if (!stats.stopped.empty()) { // a runaway shader: an error, no image
    std::fprintf(stderr, "lobe render: %s; rendering stopped, no image written\n",
                 stats.stopped.c_str());
    return 1;
  }

  lobe::image::WriteOptions wo;
  wo.exposure = st.exposure;
  wo.tonemap = lobe::image::ToneMap::Filmic;
  // Strings past their memory: the image is written (nothing finished is lost) but may be wrong.
  std::string strings_error = backend.strings_error();
  if (!strings_error.empty()) std::fprintf(stderr, "lobe render: %s\n", strings_error.c_str());
  if (std::string e = lobe::image::write_image(out, img, wo); !e.empty()) {
    std::fprintf(stderr, "lobe render: %s\n", e.c_str());
    return 1;
  }
  if (!a.quiet || stats.cancelled) { // an interrupted render always says so
    uint64_t rays = stats.counters.rays + stats.counters.shadow_rays;
    // Interrupted: how many samples per pixel finished (pixels of the last, partial pass have
    // one more), e.g. "8.4 of 32 spp".
    char spp[128];
    if (stats.cancelled)
      std::snprintf(spp, sizeof spp, "%.1f of %d spp",
                    double(stats.samples) / (double(st.width) * st.height), st.spp);
    else
      std::snprintf(spp, sizeof spp, "%d spp", st.spp);
    if (st.clamp > 0) // biased: always said
      std::snprintf(spp + std::strlen(spp), sizeof spp - std::strlen(spp),
                    ", indirect light clamped at %g", st.clamp);
    if (stats.counters.light_paths)
      std::snprintf(spp + std::strlen(spp), sizeof spp - std::strlen(spp),
                    ", %g light paths a sample for caustics", st.light_paths);
    // When the kernels came into use: "" (at set-up or not at all), else after how long.
    char ready[96] = "";
    double rs = scene.stats().kernels_ready_seconds;
    if (rs > 0)
      std::snprintf(ready, sizeof ready, ", in use %.2fs into the render", rs);
    else if (rs < 0)
      std::snprintf(ready, sizeof ready, ", the render ended before all were compiled");
    std::fprintf(stderr,
                 "%s%s: %dx%d, %s, %s materials (%d compiled in %.2fs, %d from the cache, %d "
                 "with closure kernels%s, %d from the cache, setup %.2fs), render %.2fs, %.2f "
                 "Mrays/s\n",
                 stats.cancelled ? "interrupted: wrote the finished samples to " : "wrote ",
                 out.c_str(), st.width, st.height, spp, backend.name().c_str(),
                 scene.stats().materials_compiled, scene.stats().compile_seconds,
                 scene.stats().materials_cached, scene.stats().closure_kernels, ready,
                 scene.stats().closure_kernels_cached, setup_s, stats.seconds,
                 stats.seconds > 0 ? double(rays) / stats.seconds / 1e6 : 0.0);
  }
  if (a.stats) print_stats(scene, scene.desc(), load_s, setup_s, stats, st, a.threads);
  return stats.cancelled ? 130 : strings_error.empty() ? 0 : 1;
}

} // namespace

LOBE_COMMAND(render, "render a scene (or the built-in material preview) to EXR/PNG", run_render);
