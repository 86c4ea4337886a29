// MERL measured BRDFs: loading, tabulating (for tests), interpolated look-up and the shared
// cache. See measured.h for the format.
#include "measured.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace lobe::closures {
namespace {

constexpr double kScale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};
constexpr float kHalfPi = 0.5f * kPi;

// Rusinkiewicz half/difference angles of a direction pair (isotropic: phi_h dropped).
void half_diff(const Vec3& wo, const Vec3& wi, float& th, float& td, float& pd) {
  Vec3 h = normalize(wo + wi);
  th = std::acos(clampf(h.z, -1.0f, 1.0f));
  float ph = std::atan2(h.y, h.x);
  // d = Ry(-theta_h) Rz(-phi_h) wi
  float c = std::cos(-ph), s = std::sin(-ph);
  Vec3 t{wi.x * c - wi.y * s, wi.x * s + wi.y * c, wi.z};
  float ct = std::cos(-th), st = std::sin(-th);
  Vec3 d{t.x * ct + t.z * st, t.y, -t.x * st + t.z * ct};
  td = std::acos(clampf(d.z, -1.0f, 1.0f));
  pd = std::atan2(d.y, d.x);
  if (pd < 0.0f) pd += kPi;
}

// Continuous cell coordinate (cell centres at integers) and the two neighbours.
void cell(float x, int n, bool wrap, int& i0, int& i1, float& t) {
  x -= 0.5f;
  float f = std::floor(x);
  t = x - f;
  i0 = static_cast<int>(f);
  i1 = i0 + 1;
  if (wrap) {
    i0 = ((i0 % n) + n) % n;
    i1 = ((i1 % n) + n) % n;
  } else {
    if (i0 < 0) i0 = 0, t = 0.0f;
    if (i1 > n - 1) i1 = n - 1;
    if (i0 > n - 1) i0 = n - 1;
  }
}

} // namespace

Vec3 MeasuredTable::lookup(const Vec3& wo, const Vec3& wi) const {
  float th, td, pd;
  half_diff(wo, wi, th, td, pd);
  int h0, h1, d0, d1, p0, p1;
  float th_t, td_t, pd_t;
  cell(std::sqrt(clampf(th / kHalfPi, 0.0f, 1.0f)) * kThetaH, kThetaH, false, h0, h1, th_t);
  cell(clampf(td / kHalfPi, 0.0f, 1.0f) * kThetaD, kThetaD, false, d0, d1, td_t);
  cell(pd / kPi * kPhiD, kPhiD, true, p0, p1, pd_t);
  Vec3 r;
  for (int c = 0; c < 3; ++c) {
    const float* ch = rgb.data() + static_cast<size_t>(c) * kCells;
    auto at = [&](int h, int d, int p) { return ch[p + kPhiD * d + kPhiD * kThetaD * h]; };
    auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
    auto plane = [&](int h) {
      return lerp(lerp(at(h, d0, p0), at(h, d0, p1), pd_t),
                  lerp(at(h, d1, p0), at(h, d1, p1), pd_t), td_t);
    };
    (&r.x)[c] = maxf(lerp(plane(h0), plane(h1), th_t), 0.0f);
  }
  return r;
}

bool load_merl(const std::string& path, MeasuredTable& table, std::string& error) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) return error = "cannot open measured BRDF '" + path + "'", false;
  int32_t dims[3];
  if (std::fread(dims, sizeof(int32_t), 3, f.get()) != 3)
    return error = "'" + path + "': truncated MERL header", false;
  if (dims[0] != MeasuredTable::kThetaH || dims[1] != MeasuredTable::kThetaD ||
      dims[2] != MeasuredTable::kPhiD)
    return error = "'" + path + "': not a MERL file (dimensions must be 90 90 180)", false;
  std::vector<double> buf(MeasuredTable::kCells);
  table.rgb.assign(3 * static_cast<size_t>(MeasuredTable::kCells), 0.0f);
  size_t valid = 0;
  for (int c = 0; c < 3; ++c) {
    size_t got = std::fread(buf.data(), sizeof(double), buf.size(), f.get());
    if (got != buf.size())
      return error = "'" + path + "': truncated MERL data (" + std::to_string(got) + " of " +
                     std::to_string(buf.size()) + " values in channel " + std::to_string(c) + ")",
             false;
    for (size_t i = 0; i < buf.size(); ++i) {
      if (!std::isfinite(buf[i]))
        return error = "'" + path + "': non-finite value (NaN or Inf) at cell " +
                       std::to_string(i) + " of channel " + std::to_string(c),
               false;
      double v = buf[i] * kScale[c]; // negative: no data, read as 0
      table.rgb[c * buf.size() + i] = v > 0.0 ? static_cast<float>(std::min(v, 1e30)) : 0.0f;
      valid += buf[i] >= 0.0;
    }
  }
  if (std::fgetc(f.get()) != EOF)
    return error = "'" + path + "': wrong size (trailing bytes after the MERL data)", false;
  if (valid == 0) return error = "'" + path + "': no valid cell (all negative)", false;
  table.sampler.build(table);
  return true;
}

bool write_merl(const std::string& path, BrdfFunction fn, void* user) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!f) return false;
  const int32_t dims[3] = {MeasuredTable::kThetaH, MeasuredTable::kThetaD, MeasuredTable::kPhiD};
  std::fwrite(dims, sizeof(int32_t), 3, f.get());
  std::vector<double> ch[3];
  for (auto& c : ch) c.assign(MeasuredTable::kCells, -1.0);
  for (int h = 0; h < MeasuredTable::kThetaH; ++h) {
    float u = (h + 0.5f) / MeasuredTable::kThetaH, th = u * u * kHalfPi;
    Vec3 hv{std::sin(th), 0.0f, std::cos(th)};
    for (int d = 0; d < MeasuredTable::kThetaD; ++d) {
      float td = (d + 0.5f) / MeasuredTable::kThetaD * kHalfPi;
      for (int p = 0; p < MeasuredTable::kPhiD; ++p) {
        float pd = (p + 0.5f) / MeasuredTable::kPhiD * kPi;
        Vec3 dv{std::sin(td) * std::cos(pd), std::sin(td) * std::sin(pd), std::cos(td)};
        Vec3 wi{dv.x * std::cos(th) + dv.z * std::sin(th), dv.y,
                -dv.x * std::sin(th) + dv.z * std::cos(th)};
        Vec3 wo = reflect(wi, hv);
        if (wi.z <= 0.0f || wo.z <= 0.0f) continue;
        Vec3 v = fn(wi, wo, user);
        size_t idx =
            p + MeasuredTable::kPhiD * d + MeasuredTable::kPhiD * MeasuredTable::kThetaD * h;
        for (int c = 0; c < 3; ++c) ch[c][idx] = (&v.x)[c] / kScale[c];
      }
    }
  }
  for (auto& c : ch)
    if (std::fwrite(c.data(), sizeof(double), c.size(), f.get()) != c.size()) return false;
  return true;
}

namespace {
// The one process-wide cache in the library: tables are immutable once loaded and shared by
// every thread, the way interned strings are; the files that failed, with why, beside them.
struct TableCache {
  std::mutex mutex;
  std::map<std::string, std::unique_ptr<MeasuredTable>> tables;
  std::vector<std::string> errors;
};
TableCache& table_cache() {
  static TableCache c;
  return c;
}
} // namespace

const MeasuredTable* measured_table(const char* path) {
  if (!path) return nullptr;
  TableCache& c = table_cache();
  std::lock_guard<std::mutex> lock(c.mutex);
  auto it = c.tables.find(path);
  if (it != c.tables.end()) return it->second.get();
  auto table = std::make_unique<MeasuredTable>();
  std::string error;
  if (!*path) {
    table.reset();
    c.errors.push_back("measured_bsdf: no file named (an empty filename)");
  } else if (!load_merl(path, *table, error)) {
    table.reset();
    c.errors.push_back("measured_bsdf: " + error); // the error names the file
  }
  return (c.tables[path] = std::move(table)).get();
}

} // namespace lobe::closures

std::vector<std::string> lobe::closure_data_errors() {
  closures::TableCache& c = closures::table_cache();
  std::lock_guard<std::mutex> lock(c.mutex);
  return c.errors;
}
