#include "tfeti_CollectiveError.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <vector>

namespace tfeti {

void throwIfAnyRankFailed(const Comm& comm, const std::string& localError) {
  const int size = comm.getSize(), me = comm.getRank();
  int mine[2] = {localError.empty() ? size : me, localError.empty() ? 0 : 1};
  int first = size, failed = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MIN, 1, &mine[0], &first);
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &mine[1], &failed);
  if (failed == 0) return;
  int length = me == first ? static_cast<int>(localError.size()) : 0;
  Teuchos::broadcast(comm, first, 1, &length);
  std::vector<char> text(localError.begin(), localError.end());
  text.resize(length);
  if (length > 0) Teuchos::broadcast(comm, first, length, text.data());
  std::string message(text.begin(), text.end());
  if (failed > 1)
    message += " (and errors on " + std::to_string(failed - 1) + " other rank" +
               (failed > 2 ? "s" : "") + ")";
  throw CollectiveError(message);
}

}  // namespace tfeti
