#pragma once
// Whether what the ranks are about to allocate fits the machines they run on. Ranks on the same
// machine (a node: the same host name) share its memory, so their needs add up; a node offers
// MemAvailable of /proc/meminfo, what the kernel can hand out without swapping once everything
// the run holds so far is counted. FetiSolver asks before each large allocation of its set-up:
// the subdomain factors (their bytes told by the symbolic analyses), the Dirichlet
// preconditioner's interior factors, and the explicit dual operator's F_s (in 3D they take
// 1.5-2.8x the factors' bytes, docs/dual_operator.md). A run that cannot hold them stops with an
// error naming the parameters to change, instead of being killed by the kernel's OOM killer
// partway, with nothing written (FETI "Memory check" = false: no check).
//
// The environment variable TFETI_MEMINFO names another file to read instead of /proc/meminfo
// (the tests give one with little memory available).
#include <algorithm>
#include <functional>
#include <string>

#include "tfeti_Types.hpp"

namespace tfeti {

// Bytes of the "MemAvailable:" line (kB) of a meminfo file; negative where the file cannot be
// read or has no such line.
double availableBytesIn(const std::string& meminfoFile);
// availableBytesIn of /proc/meminfo, or of $TFETI_MEMINFO where set: then a file without the
// line is std::invalid_argument naming the variable (a test that would check nothing). Or what
// the source set below returns.
double availableNodeBytes();

// A process-wide source of the available bytes instead of the file, for tests whose node must
// change between two checks of one set-up (a file read by every check gives one value to all of
// them); an empty function restores the file.
void setAvailableBytesSource(std::function<double()> source);

struct NodeMemory {
  // Every rank read its node's available memory; where some could not, nothing is known and
  // everything fits.
  bool known = false;
  // On every node the ranks' needs together are within what the node has available.
  bool fits = true;
  // The node with the least room left (available minus need): its lowest rank, how many ranks
  // it has, their needs summed and its available bytes (the least any of its ranks read).
  int firstRank = 0;
  int ranks = 0;
  double needBytes = 0.0;
  double availableBytes = -1.0;
  // The same node's heldBytes summed (what stays allocated once the need's transients are gone).
  double heldBytes = 0.0;
};

// Collective: every rank gives the bytes it is about to allocate (less what it frees meanwhile);
// every rank returns the same answer, or throws CollectiveError where some rank's
// availableNodeBytes() did.
// heldBytes: what of the need stays allocated (summed per node alongside; for the report).
NodeMemory nodeMemory(const Comm& comm, double needBytes, double heldBytes = 0.0);

// "the 2 ranks on the node of rank 0 need 1.50 GiB and it has 980.2 MiB available
// (MemAvailable)": for errors.
std::string describe(const NodeMemory& m);
// "57.5 KiB" below a MiB, "980.2 MiB" below a GiB, "1.50 GiB" from there.
std::string bytesText(double bytes);

// A rank's need through a set-up that allocates piece by piece: the peak of what it holds
// beyond the start. make(): a piece that keeps `held` bytes, allocates `transient` more while it
// is made (freed when done) and then replaces `replaced` (counted until the new one is made: an
// upper bound where the old is freed first). release(): bytes freed.
struct RunningPeak {
  double running = 0.0, peak = 0.0;
  void make(double held, double transient, double replaced = 0.0) {
    peak = std::max(peak, running + held + transient);
    running += held - replaced;
  }
  void release(double bytes) { running -= bytes; }
};

}  // namespace tfeti
