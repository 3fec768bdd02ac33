#pragma once
// Pieces every study of the driver shares: timings and summary output, memory, the VTU piece of
// a solved FETI problem.
#include <string>

#include "contact_Json.hpp"
#include "contact_VtuWriter.hpp"
#include "tfeti_FetiSolver.hpp"

namespace contact {

Json timingsJson(const tfeti::FetiTimings& t, int iterations);
// Rank 0 writes dir/summary.json.
void writeSummary(const tfeti::Comm& comm, const std::string& dir, const Json& summary);
// Largest resident set size over the ranks, in MiB.
double peakRssMb(const tfeti::Comm& comm);
// The solved subdomains of this rank: u (or displacement) per node, subdomain id per cell.
VtuPiece vtuPiece(const tfeti::FetiSolver& solver);

}  // namespace contact
