// The timing harness of the Pinocchio benchmarks (derivatives.cpp, task_space.cpp): the median
// over `rounds` rounds of the mean time of `batch` calls f(0), ..., f(batch - 1), in ns.
#pragma once
#include <algorithm>
#include <chrono>
#include <vector>

template <class F> double median_ns(F f, int batch, int rounds) {
  std::vector<double> t;
  for (int r = 0; r < rounds; ++r) {
    auto a = std::chrono::steady_clock::now();
    for (int i = 0; i < batch; ++i) f(i);
    auto b = std::chrono::steady_clock::now();
    t.push_back(std::chrono::duration<double, std::nano>(b - a).count() / batch);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}
