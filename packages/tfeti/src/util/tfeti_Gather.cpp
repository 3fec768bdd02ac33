#include "tfeti_Gather.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>

namespace tfeti {

namespace {
// Each rank places its data at its offset in a zero buffer; a sum over ranks concatenates.
template <class T>
std::vector<T> gatherBySum(const Comm& comm, const std::vector<T>& mine) {
  const int P = comm.getSize(), me = comm.getRank();
  std::vector<long long> counts(P, 0), all(P, 0);
  counts[me] = static_cast<long long>(mine.size());
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, P, counts.data(), all.data());
  long long total = 0, offset = 0;
  for (int r = 0; r < P; ++r) {
    if (r < me) offset += all[r];
    total += all[r];
  }
  std::vector<T> buf(total, T(0)), out(total, T(0));
  std::copy(mine.begin(), mine.end(), buf.begin() + offset);
  if (total > 0)
    Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, static_cast<int>(total), buf.data(), out.data());
  return out;
}
}  // namespace

std::vector<long long> allGather(const Comm& comm, const std::vector<long long>& mine) {
  return gatherBySum(comm, mine);
}

std::vector<double> allGather(const Comm& comm, const std::vector<double>& mine) {
  return gatherBySum(comm, mine);
}

}  // namespace tfeti
