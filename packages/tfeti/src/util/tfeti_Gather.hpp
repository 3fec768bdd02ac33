#pragma once
// Concatenation of every rank's array on every rank (rank order), for the small global
// descriptions every rank derives the same result from: subdomain boundaries for the tearing,
// the coarse matrix G G^T.
#include <vector>

#include "tfeti_Types.hpp"

namespace tfeti {

std::vector<long long> allGather(const Comm& comm, const std::vector<long long>& mine);
std::vector<double> allGather(const Comm& comm, const std::vector<double>& mine);

}  // namespace tfeti
