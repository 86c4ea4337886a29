// A C function type's shadeop signature string (shadeops.h: the return type, then the
// parameters; v void, i 32-bit integer, l 64-bit integer, f float, p any pointer), derived
// from the type so that it cannot disagree with the function it describes.
#pragma once

#include <type_traits>

namespace lobe::shadeops {

template <class T> constexpr char sig_letter() {
  if constexpr (std::is_void_v<T>)
    return 'v';
  else if constexpr (std::is_pointer_v<T>)
    return 'p';
  else if constexpr (std::is_same_v<T, float>)
    return 'f';
  else if constexpr (std::is_integral_v<T> && sizeof(T) == 4)
    return 'i';
  else if constexpr (std::is_integral_v<T> && sizeof(T) == 8)
    return 'l';
  else
    static_assert(sizeof(T) == 0, "no shadeop signature letter for this type");
}

template <class F> struct SigOf;
template <class R, class... A> struct SigOf<R(A...)> {
  static constexpr char value[] = {sig_letter<R>(), sig_letter<A>()..., '\0'};
};
template <class R, class... A> struct SigOf<R(A...) noexcept> : SigOf<R(A...)> {};
template <class R, class... A> struct SigOf<R (*)(A...)> : SigOf<R(A...)> {};
template <class R, class... A> struct SigOf<R (*)(A...) noexcept> : SigOf<R(A...)> {};

// The signature string of function (or function pointer) type F.
template <class F> inline constexpr const char* shadeop_sig = SigOf<F>::value;

} // namespace lobe::shadeops
