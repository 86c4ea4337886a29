// Typed access to a parsed JSON document with located errors: every failure throws a
// SceneError whose text is "file: /json/pointer: what was expected". Used by scene_json.cpp
// only (exceptions never leave the loader; load_json_scene turns them into an error value).
#pragma once

#include "transform.h"

#include "lobe/vec.h"

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <span>
#include <stdexcept>
#include <string>

namespace lobe::scene {

struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class JsonReader {
public:
  using json = nlohmann::ordered_json; // keeps file order (materials, params)
  explicit JsonReader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& ptr, const std::string& msg) const {
    throw SceneError(file_ + ": " + (ptr.empty() ? "/" : ptr) + ": " + msg);
  }
  const std::string& file() const { return file_; }

  // Rejects keys not in `allowed` (catches misspelt settings instead of ignoring them).
  void check_keys(const json& j, const std::string& ptr,
                  std::initializer_list<const char*> allowed) const {
    check_keys(j, ptr, std::span<const char* const>(allowed.begin(), allowed.size()));
  }
  void check_keys(const json& j, const std::string& ptr,
                  std::span<const char* const> allowed) const;
  const json& object(const json& j, const std::string& ptr) const;
  float number(const json& j, const std::string& ptr) const;
  int integer(const json& j, const std::string& ptr, int lo, int hi) const;
  std::string string(const json& j, const std::string& ptr) const;
  Vec3 vec3(const json& j, const std::string& ptr) const;
  // A colour: [r,g,b] or one number for grey.
  Vec3 color(const json& j, const std::string& ptr) const;
  // A colour or number scaling emitted light (a light's intensity and colour, an environment's
  // colour and intensity): each component >= 0 (light is never negative), else an error.
  Vec3 emission(const json& j, const std::string& ptr) const;
  float emission_scale(const json& j, const std::string& ptr) const;
  // {"translate":[x,y,z], "rotate":[deg,ax,ay,az], "scale":s|[x,y,z], "matrix":[16]} (applied
  // scale, then rotate, then translate, then matrix), or an array of those applied in order.
  Mat4 transform(const json& j, const std::string& ptr) const;

  // Optional members: fill `out` if `key` is present.
  template <class T, class F>
  void opt(const json& j, const std::string& ptr, const char* key, T& out, F read) const {
    if (j.contains(key)) out = (this->*read)(j.at(key), ptr + "/" + key);
  }

private:
  std::string file_;
};

} // namespace lobe::scene
