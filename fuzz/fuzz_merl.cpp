// MERL measured-BRDF files (measured_bsdf). A real file is 3 int32 + 3 x 1458000 doubles
// (35 MB), far beyond what a fuzzer writes, so the first byte chooses how the input is used:
//   even: the rest is the file, byte for byte (header, truncation and size checks);
//   odd:  the rest is a 12-byte header and a pattern of doubles repeated to fill exactly a
//         file's size (the value checks, the scaling and the sampler's tables), then the
//         table is looked up and sampled in a few directions.
#include "fuzz_util.h"
#include "measured.h"

#include <cstring>
#include <vector>

using lobe::closures::MeasuredTable;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  bool expand = data[0] & 1;
  ++data, --size;
  std::vector<uint8_t> file(data, data + size);
  if (expand) {
    if (size < 12 + sizeof(double)) return 0;
    size_t total = 12 + 3 * sizeof(double) * static_cast<size_t>(MeasuredTable::kCells);
    file.resize(total);
    size_t pattern = size - 12;
    for (size_t i = size; i < total; ++i) file[i] = data[12 + (i - 12) % pattern];
  }
  MeasuredTable table;
  std::string error;
  if (!lobe::closures::load_merl(lobe::fuzz::temp_file(".merl", file.data(), file.size()), table,
                                 error))
    return 0;
  const lobe::Vec3 dirs[] = {{0, 0, 1}, {0.6f, 0, 0.8f}, {0, -0.99f, 0.141f}};
  for (const auto& wo : dirs)
    for (const auto& wi : dirs) {
      (void)table.lookup(wo, wi);
      (void)table.sampler.pdf(wo, wi);
      lobe::Vec3 s;
      if (table.sampler.sample(wo, 0.3f, 0.7f, s)) (void)table.sampler.pdf(wo, s);
    }
  return 0;
}
