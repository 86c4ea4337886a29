// Values of any shader type passed to shadeops by address, and their type codes.
//
// A type travels as one int code, base | arraylen << 8 (LayerEmitter::type_code), with base
// the IR's BaseType: Int, Float, Color, Point, Vector, Normal, Matrix, String (DataType::Base,
// in the same order), then Closure. A value is a symbol's storage: the value plane, then the
// d/dx and d/dy planes when the symbol carries derivatives.
#pragma once

#include "env.h"
#include "lobe/renderer_services.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace lobe::shadeops {

inline constexpr int kClosureBase = 8;

inline int code_base(int code) { return code & 0xff; }
inline int code_arraylen(int code) { return code >> 8; }
inline DataType code_type(int code) {
  return DataType{DataType::Base(code_base(code)), code_arraylen(code)};
}

// Bytes of one plane of a value of type `code`.
inline size_t plane_bytes(int code) {
  if (code_base(code) == kClosureBase)
    return size_t(std::max(1, code_arraylen(code))) * sizeof(void*);
  return code_type(code).bytes();
}

// The strings of a value of type `code` at `value` (its value plane), replaced by interned
// copies (a null pointer by ""); other types are left alone.
inline void intern_strings(RuntimeEnv* env, int code, void* value) {
  if (code_base(code) != int(DataType::Base::String)) return;
  auto* p = static_cast<unsigned char*>(value);
  for (size_t i = 0; i < plane_bytes(code) / sizeof(const char*); ++i) {
    const char* s;
    std::memcpy(&s, p + i * sizeof(s), sizeof(s));
    s = env->strings.intern(s ? s : "");
    std::memcpy(p + i * sizeof(s), &s, sizeof(s));
  }
}

// Asks `ask(scratch)` for a value of type `code` (not a closure) and copies it to `dest` only
// on success, so a source that writes part of a value and then says no leaves the shader's
// variable as it was. Derivative planes (`derivs`) start zeroed; strings are interned, so the
// source's pointers need only live through the call.
template <class Ask> int fetch_value(RuntimeEnv* env, int code, int derivs, void* dest, Ask ask) {
  size_t plane = plane_bytes(code);
  size_t total = plane * (derivs ? 3 : 1);
  unsigned char local[512];
  std::vector<unsigned char> heap;
  unsigned char* scratch = local;
  if (total > sizeof(local)) {
    heap.assign(total, 0);
    scratch = heap.data();
  } else {
    std::memset(local, 0, total);
  }
  if (!ask(static_cast<void*>(scratch))) return 0;
  intern_strings(env, code, scratch);
  std::memcpy(dest, scratch, total);
  return 1;
}

} // namespace lobe::shadeops
