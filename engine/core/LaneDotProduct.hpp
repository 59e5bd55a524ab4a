#pragma once
// laneDotProduct: sum of a[i] * b[i] over n floats in eight independent partial sums. A single
// running sum is a chain of dependent additions the compiler may not reorder; eight lanes let it
// vectorise (the summation order, and so the last bits, differ from a plain loop).

namespace reftrack {

inline float laneDotProduct(const float* a, const float* b, int n) {
  float partial[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  int i = 0;
  for (; i + 8 <= n; i += 8)
    for (int j = 0; j < 8; ++j) partial[j] += a[i + j] * b[i + j];
  float sum = 0.0f;
  for (; i < n; ++i) sum += a[i] * b[i];
  for (float p : partial) sum += p;
  return sum;
}

}  // namespace reftrack
