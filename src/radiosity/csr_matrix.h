// Compressed sparse rows: the form-factor matrix F and its transpose. Values are float (the
// matrix is the large object); every product accumulates in double.
#pragma once
#include <cstdint>
#include <vector>

namespace dualight {

struct CsrMatrix {
  uint32_t n = 0;                 // square: n x n
  std::vector<uint64_t> indptr;   // n + 1 row starts
  std::vector<uint32_t> indices;  // column of each entry, ascending within a row
  std::vector<float> values;

  uint64_t nonzeros() const { return values.size(); }
  double row_sum(uint32_t i) const {
    double s = 0.0;
    for (uint64_t k = indptr[i]; k < indptr[i + 1]; ++k) s += values[k];
    return s;
  }
  CsrMatrix transpose() const {
    CsrMatrix t;
    t.n = n;
    t.indptr.assign(n + 1, 0);
    for (const uint32_t j : indices) ++t.indptr[j + 1];
    for (uint32_t i = 0; i < n; ++i) t.indptr[i + 1] += t.indptr[i];
    t.indices.resize(indices.size());
    t.values.resize(values.size());
    std::vector<uint64_t> next(t.indptr.begin(), t.indptr.end() - 1);
    for (uint32_t i = 0; i < n; ++i) {  // rows in order, so transposed rows stay sorted
      for (uint64_t k = indptr[i]; k < indptr[i + 1]; ++k) {
        const uint64_t dst = next[indices[k]]++;
        t.indices[dst] = i;
        t.values[dst] = values[k];
      }
    }
    return t;
  }
};

}  // namespace dualight
