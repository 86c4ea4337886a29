// render_convergence: run time against error for the path tracer, and where the time goes.
//
//   ./build/bench/render/render_convergence [scene.json] [--out DIR] [--ref-spp N]
//       [--max-spp N] [--res W H] [--threads N] [--materials jit|native] [--closures jit|native]
//
// Materials are compiled as `lobe render` compiles them (MaterialBackend; default the JIT, with
// closures through the JIT closure kernels); `--materials native` / `--closures native` measure
// the native twins / the native closure library instead.
//
// 1. Renders a reference with MIS at --ref-spp (default 1024), cached in DIR/reference.exr.
// 2. For each strategy (mis, bsdf, light) renders at 1, 2, 4, ... --max-spp samples (another
//    seed than the reference), recording wall time and relMSE against the reference
//    (mean of (x-r)^2/(r^2+0.01), BSDF_NOTES.md). Writes DIR/convergence.csv and a log-log
//    plot DIR/convergence.png (gnuplot) of relMSE against seconds, and prints each strategy's
//    relMSE interpolated at equal time.
// 3. Throughput: the renderer's rays/s (closest-hit + shadow queries over render time) with
//    the share of time inside Material::shade + Bsdf::build, beside Embree's raw rate on the
//    same scene in the same run (the same number of camera and diffuse-bounce rays traced
//    with intersect only, no shading).
// Default scene: scenes/veach_mis.json (glossy plates and four spherical lights of very
// different sizes, where the strategies differ most).
#include "default_scene.h"
#include "image.h"
#include "material_backend.h"
#include "native_materials.h"
#include "renderer.h"
#include "sampling.h"
#include "scene.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace lobe;
using namespace lobe::render;

namespace {

struct Options {
  std::string scene = "scenes/veach_mis.json", out = "bench_out/render";
  std::string materials = "jit", closures = "jit"; // as `lobe render` uses them by default
  int ref_spp = 1024, max_spp = 64, width = 240, height = 135, threads = 0;
};

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto next = [&](int& v) { return i + 1 < argc && (v = std::atoi(argv[++i])) > 0; };
    if (a == "--out" && i + 1 < argc)
      o.out = argv[++i];
    else if (a == "--materials" && i + 1 < argc) {
      o.materials = argv[++i];
      if (o.materials != "jit" && o.materials != "native") return false;
    } else if (a == "--closures" && i + 1 < argc) {
      o.closures = argv[++i];
      if (o.closures != "jit" && o.closures != "native") return false;
    } else if (a == "--ref-spp") {
      if (!next(o.ref_spp)) return false;
    } else if (a == "--max-spp") {
      if (!next(o.max_spp)) return false;
    } else if (a == "--threads") {
      if (!next(o.threads)) return false;
    } else if (a == "--res") {
      if (!next(o.width) || !next(o.height)) return false;
    } else if (!a.empty() && a[0] != '-')
      o.scene = a;
    else
      return false;
  }
  return true;
}

struct Point {
  std::string strategy;
  int spp;
  double seconds, relmse;
};

const char* name_of(Strategy s) {
  return s == Strategy::Mis ? "mis" : s == Strategy::BsdfOnly ? "bsdf" : "light";
}

// relMSE at time t by log-log interpolation between measured points (-1 outside the range).
double error_at(const std::vector<Point>& pts, const std::string& strat, double t) {
  const Point* prev = nullptr;
  for (const Point& p : pts) {
    if (p.strategy != strat) continue;
    if (prev && prev->seconds <= t && p.seconds >= t) {
      double f = (std::log(t) - std::log(prev->seconds)) /
                 std::max(1e-12, std::log(p.seconds) - std::log(prev->seconds));
      return std::exp(std::log(prev->relmse) + f * (std::log(p.relmse) - std::log(prev->relmse)));
    }
    prev = &p;
  }
  return -1;
}

void write_plot(const Options& o) {
  std::ofstream gp(o.out + "/convergence.gp");
  gp << "set terminal pngcairo size 800,560 noenhanced\n"
     << "set output '" << o.out << "/convergence.png'\n"
     << "set logscale xy\nset grid\nset key bottom left\n"
     << "set xlabel 'render time (s)'\nset ylabel 'relMSE vs reference'\n"
     << "set title 'Error against time: " << o.scene << "'\n"
     << "set datafile separator ','\n"
     << "plot for [s in 'mis bsdf light'] '" << o.out
     << "/convergence.csv' using (strcol(1) eq s ? $3 : 1/0):4 with linespoints title s\n";
  gp.close();
  std::string cmd = "gnuplot '" + o.out + "/convergence.gp'";
  if (std::system(cmd.c_str()) != 0) std::fprintf(stderr, "gnuplot failed (plot skipped)\n");
}

} // namespace

int main(int argc, char** argv) {
  Options o;
  if (!parse(argc, argv, o)) {
    std::fprintf(stderr, "usage: render_convergence [scene.json] [--out DIR] [--ref-spp N] "
                         "[--max-spp N] [--res W H] [--threads N] [--materials jit|native] "
                         "[--closures jit|native]\n");
    return 2;
  }
  std::string err;
  auto desc = scene::load_scene(o.scene, err);
  if (!desc) {
    std::fprintf(stderr, "%s\n", err.c_str());
    return 1;
  }
  // The materials as the renderer compiles them (MaterialBackend: the JIT by default, shaders
  // next to the scene first), and their closures through JIT kernels or the native library.
  MaterialBackend backend(o.materials, {std::filesystem::absolute(o.scene).parent_path().string()},
                          native_compiler());
  RenderScene s;
  s.set_kernel_mode(o.closures == "jit" ? KernelMode::AtSetup : KernelMode::Native);
  if (std::string e = s.setup(*desc, backend.compiler(), o.width, o.height); !e.empty()) {
    std::fprintf(stderr, "%s\n", e.c_str());
    return 1;
  }
  std::printf("materials: %s (%d compiled, %d with closure kernels), closures: %s\n",
              backend.name().c_str(), s.stats().materials_compiled, s.stats().closure_kernels,
              o.closures.c_str());
  std::filesystem::create_directories(o.out);
  RenderOptions opt;
  opt.max_depth = desc->settings.max_depth;
  opt.threads = o.threads;
  opt.aovs = false;

  // 1. Reference (cached: it is the expensive part).
  image::Image ref;
  std::string ref_path = o.out + "/reference.exr";
  if (!image::read_image(ref_path, ref).empty() || ref.width != o.width || ref.height != o.height) {
    opt.spp = o.ref_spp;
    opt.seed = 7777;
    RenderStats st;
    ref = render_image(s, o.width, o.height, opt, nullptr, nullptr, &st);
    image::write_image(ref_path, ref);
    std::printf("reference: %d spp in %.1f s -> %s\n", o.ref_spp, st.seconds, ref_path.c_str());
  }

  // 2. Convergence per strategy.
  std::vector<Point> pts;
  std::ofstream csv(o.out + "/convergence.csv");
  csv << "strategy,spp,seconds,relmse\n";
  for (Strategy strat : {Strategy::Mis, Strategy::BsdfOnly, Strategy::LightOnly}) {
    for (int spp = 1; spp <= o.max_spp; spp *= 2) {
      opt.spp = spp;
      opt.seed = 1;
      opt.strategy = strat;
      RenderStats st;
      image::Image img = render_image(s, o.width, o.height, opt, nullptr, nullptr, &st);
      Point p{name_of(strat), spp, st.seconds, rel_mse(img, ref)};
      pts.push_back(p);
      csv << p.strategy << "," << spp << "," << p.seconds << "," << p.relmse << "\n";
      std::printf("%-5s %5d spp  %8.3f s  relMSE %.5f\n", p.strategy.c_str(), spp, p.seconds,
                  p.relmse);
    }
  }
  csv.close();
  write_plot(o);
  double t_eq = 0;
  for (const Point& p : pts)
    if (p.strategy == "mis" && p.spp == o.max_spp / 2) t_eq = p.seconds;
  std::printf("\nat equal time %.3f s: relMSE mis %.5f  bsdf %.5f  light %.5f\n", t_eq,
              error_at(pts, "mis", t_eq), error_at(pts, "bsdf", t_eq),
              error_at(pts, "light", t_eq));

  // 3. Throughput and shading share.
  opt.spp = 16;
  opt.strategy = Strategy::Mis;
  opt.time_shading = true;
  RenderStats st;
  render_image(s, o.width, o.height, opt, nullptr, nullptr, &st);
  uint64_t rays = st.counters.rays + st.counters.shadow_rays;
  int threads = opt.threads > 0 ? opt.threads : tbb::this_task_arena::max_concurrency();
  double shade_share = st.counters.shade_seconds / (st.seconds * threads);
  uint64_t raw_rays = 0;
  double raw = raw_traversal_rate(s, o.width, o.height, 16, opt.threads, raw_rays);
  std::printf("renderer: %.2f Mrays/s (%llu rays, %llu shades in %.2f s on %d threads), "
              "shading %.0f%% of thread time\n",
              double(rays) / st.seconds / 1e6, (unsigned long long)rays,
              (unsigned long long)st.counters.shades, st.seconds, threads, 100 * shade_share);
  std::printf("embree raw traversal: %.2f Mrays/s (%llu camera + bounce rays)\n", raw / 1e6,
              (unsigned long long)raw_rays);
  std::printf("wrote %s/convergence.csv and %s/convergence.png\n", o.out.c_str(), o.out.c_str());
  return 0;
}
