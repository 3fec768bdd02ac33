#pragma once
// Belos conventions shared by the iterative solvers (PCPG, MPRGP, SMALBE), so that a Belos user
// configures them as a Belos solver manager:
//  - Belos's parameter names as aliases of the package's own: "Convergence Tolerance" for
//    "Relative tolerance", "Maximum Iterations" for "Maximum iterations" (SMALBE: "Maximum outer
//    iterations"). Both given with different values is an error naming both; the alias is then
//    replaced by the package's name, so getCurrentParameters() shows one name per setting.
//  - "Verbosity" as the package's level 0 (silent), 1 (summary), 2 (every step), or as a bitmask
//    of Belos::MsgType (Warnings | IterationDetails | FinalSummary | TimingDetails |
//    StatusTestDetails ...). 1 and 2 read as levels (a Belos mask of Warnings alone, or of
//    IterationDetails alone, is therefore read as level 1 or 2, which prints what those types ask
//    for and the summary); any other value as a mask. Level 1 is Warnings | FinalSummary, level
//    2 adds IterationDetails.
//  - Teuchos::TimeMonitor timers named "tfeti: ..." (solverTimer), which a caller reads with
//    TimeMonitor::summarize() or lookupCounter().
#include <BelosTypes.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_Time.hpp>

#include <string>
#include <vector>

namespace tfeti {

struct ParameterAlias {
  std::string belosName;  // e.g. "Convergence Tolerance"
  std::string ownName;    // e.g. "Relative tolerance"
};

// The Belos aliases of a solver whose iteration limit is called maxIterationsName.
std::vector<ParameterAlias> belosAliases(const std::string& maxIterationsName);

// Replaces each alias present in pl by its own name. Throws std::invalid_argument naming the
// solver and both names when both are given with different values (or the alias has a type the
// own parameter cannot take).
void applyParameterAliases(Teuchos::ParameterList& pl, const std::string& solver,
                           const std::vector<ParameterAlias>& aliases);

// Every Belos::MsgType bit the solvers accept in "Verbosity".
constexpr int kAllMsgTypes = Belos::Warnings | Belos::IterationDetails | Belos::OrthoDetails |
                             Belos::FinalSummary | Belos::TimingDetails | Belos::StatusTestDetails |
                             Belos::Debug;

// The Belos::MsgType mask of a "Verbosity" value (see above); throws std::invalid_argument naming
// the solver for a negative value or unknown bits.
int verbosityMask(int verbosity, const std::string& solver);

// The timer of this name in Teuchos::TimeMonitor's registry (created on first use).
Teuchos::RCP<Teuchos::Time> solverTimer(const std::string& name);

}  // namespace tfeti
