// The computation of bench/jit_math.osl written in C++ (float, libm), the reference for
// BM_MathShader. Compiled with -O2 (the comparison the JIT is held to), not the build's -O3.
#include <cmath>

float lobe_math_native(float u, float v) {
  float x = u * 3.7f + v;
  float acc = 0;
  for (int i = 0; i < 16; ++i) {
    float fi = float(i);
    acc += std::sin(x * fi) * std::exp(-0.1f * fi) + std::sqrt(std::fabs(x - fi)) * 0.25f;
    acc += std::pow(std::fabs(std::cos(x + fi)), 1.5f) / (1 + fi * fi);
    x = x * 1.01f + 0.1f;
  }
  return acc;
}
