// Stress checks of one lobe against the "finite, >= 0, pdf > 0 for samples" contract.
#include "stress.h"

#include "rng.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

namespace lobe::verify {
namespace {

std::string vec_str(const Vec3& v) {
  std::ostringstream os;
  os.precision(9);
  os << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return os.str();
}

void note(StressResult& out, uint64_t& counter, const std::string& what) {
  ++counter;
  if (out.first_failure.empty()) out.first_failure = what;
}

// Directions at the extreme cosines of the notes, for a few azimuths. z may exceed 1
// (nextafter(1, 2)): the vector is then slightly unnormalised, as a shader might pass it.
std::vector<Vec3> extreme_directions() {
  const float cosines[] = {0.0f,
                           -0.0f,
                           1e-8f,
                           -1e-8f,
                           1e-4f,
                           -1e-4f,
                           0.5f,
                           -0.5f,
                           1 - 1e-7f,
                           1.0f,
                           std::nextafter(1.0f, 2.0f),
                           -1.0f};
  const float phis[] = {0.0f, 1.3f, 3.14159265f};
  std::vector<Vec3> dirs;
  for (float c : cosines)
    for (float phi : phis) {
      float s = std::sqrt(std::fmax(0.0f, 1.0f - c * c));
      dirs.push_back({s * std::cos(phi), s * std::sin(phi), c});
    }
  return dirs;
}

Vec3 mirror(const Vec3& w) { return {-w.x, -w.y, w.z}; }

// Refraction of w (above, pointing away) into the side below with relative IOR eta.
Vec3 refraction(const Vec3& w, double eta) {
  double c = w.z, s2 = (1.0 - c * c) / (eta * eta);
  if (s2 >= 1.0) return mirror(w);
  double ct = std::sqrt(1.0 - s2);
  return {static_cast<float>(-w.x / eta), static_cast<float>(-w.y / eta),
          static_cast<float>(c >= 0 ? -ct : ct)};
}

} // namespace

void StressResult::merge(const StressResult& o) {
  calls += o.calls;
  invalid_outputs += o.invalid_outputs;
  invalid_inputs += o.invalid_inputs;
  unsampled_mass += o.unsampled_mass;
  if (first_failure.empty()) first_failure = o.first_failure;
}

void stress_eval(const LobeView& lobe, const Vec3& wo, const Vec3& wi, StressResult& out) {
  BsdfEval e = lobe.eval(wo, wi, Transport::Radiance);
  BsdfEval ei = lobe.eval(wo, wi, Transport::Importance);
  float p = lobe.pdf(wo, wi);
  out.calls += 3;
  if (!finite_nonneg(e.value) || !finite_nonneg(e.pdf) || !finite_nonneg(p) ||
      !finite_nonneg(ei.value) || !finite_nonneg(ei.pdf))
    note(out, out.invalid_outputs,
         "eval/pdf " + vec_str(wo) + " " + vec_str(wi) + " -> " + vec_str(e.value) + " pdf " +
             std::to_string(p));
  else if (p == 0 && max_component(e.value) > 0 && !(lobe.flags() & kLobeSpecular))
    ++out.unsampled_mass;
}

void stress_sample(const LobeView& lobe, const Vec3& wo, const Vec3& u, StressResult& out) {
  for (Transport mode : {Transport::Radiance, Transport::Importance}) {
    auto s = lobe.sample(wo, u, mode);
    ++out.calls;
    if (!s) continue;
    bool good = finite_nonneg(s->weight) && std::isfinite(s->pdf) && s->pdf > 0 &&
                is_finite(s->wi) && !is_zero(s->wi) && std::isfinite(s->eta) && s->eta > 0;
    if (!good)
      note(out, out.invalid_outputs,
           "sample wo " + vec_str(wo) + " u " + vec_str(u) + " -> wi " + vec_str(s->wi) +
               " weight " + vec_str(s->weight) + " pdf " + std::to_string(s->pdf));
  }
}

void stress_grid(const LobeView& lobe, double eta_below, StressResult& out) {
  std::vector<Vec3> dirs = extreme_directions();
  const float us[] = {0.0f, 0.5f, 1.0f - 0x1p-24f};
  for (const Vec3& wo : dirs) {
    for (const Vec3& wi : dirs) stress_eval(lobe, wo, wi, out);
    stress_eval(lobe, wo, mirror(wo), out);
    stress_eval(lobe, wo, refraction(wo, eta_below), out);
    stress_eval(lobe, wo, wo, out);
    for (float a : us)
      for (float b : us)
        for (float c : us) stress_sample(lobe, wo, {a, b, c}, out);
  }
}

void stress_invalid_inputs(const LobeView& lobe, StressResult& out) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const Vec3 bad[] = {{nan, nan, nan}, {0, 0, nan}, {0, 0, 0}, {inf, 0, 1}};
  const Vec3 good = normalize(Vec3{0.3f, 0.2f, 0.9f});
  const Vec3 good_below = normalize(Vec3{-0.3f, 0.1f, -0.9f});
  auto zero_eval = [&](const Vec3& wo, const Vec3& wi) {
    for (Transport m : {Transport::Radiance, Transport::Importance}) {
      BsdfEval e = lobe.eval(wo, wi, m);
      float p = lobe.pdf(wo, wi);
      out.calls += 2;
      if (!is_zero(e.value) || e.pdf != 0 || p != 0)
        note(out, out.invalid_inputs,
             "invalid input gave a value: " + vec_str(wo) + " " + vec_str(wi) + " -> " +
                 vec_str(e.value) + " pdf " + std::to_string(p));
    }
  };
  for (const Vec3& b : bad) {
    zero_eval(b, good);
    zero_eval(good, b);
    zero_eval(b, good_below);
    zero_eval(b, b);
    for (Transport m : {Transport::Radiance, Transport::Importance}) {
      ++out.calls;
      if (lobe.sample(b, {0.3f, 0.6f, 0.2f}, m))
        note(out, out.invalid_inputs, "invalid wo " + vec_str(b) + " gave a sample");
    }
  }
}

void stress_random(const LobeView& lobe, uint64_t n, uint64_t seed, StressResult& out) {
  Pcg32 rng(seed);
  for (uint64_t k = 0; k < n; ++k) {
    Vec3 wo = uniform_sphere(rng.next_double(), rng.next_double());
    Vec3 wi = uniform_sphere(rng.next_double(), rng.next_double());
    stress_eval(lobe, wo, wi, out);
    stress_sample(lobe, wo, rng.next_vec3(), out);
  }
}

} // namespace lobe::verify
