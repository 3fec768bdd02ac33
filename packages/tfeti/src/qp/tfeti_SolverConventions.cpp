#include "tfeti_SolverConventions.hpp"

#include <Teuchos_TimeMonitor.hpp>

#include <sstream>
#include <stdexcept>

namespace tfeti {

std::vector<ParameterAlias> belosAliases(const std::string& maxIterationsName) {
  return {{"Convergence Tolerance", "Relative tolerance"},
          {"Maximum Iterations", maxIterationsName}};
}

namespace {

// The value of entry `name` as a string (for messages) and whether it equals `other`'s.
std::string show(const Teuchos::ParameterEntry& e) {
  std::ostringstream os;
  os.precision(15);
  e.leftshift(os, false);
  return os.str();
}

bool sameValue(const Teuchos::ParameterEntry& a, const Teuchos::ParameterEntry& b) {
  if (a.isType<double>() && b.isType<double>())
    return a.getValue<double>(nullptr) == b.getValue<double>(nullptr);
  if (a.isType<int>() && b.isType<int>())
    return a.getValue<int>(nullptr) == b.getValue<int>(nullptr);
  return false;
}

}  // namespace

void applyParameterAliases(Teuchos::ParameterList& pl, const std::string& solver,
                           const std::vector<ParameterAlias>& aliases) {
  for (const ParameterAlias& a : aliases) {
    if (!pl.isParameter(a.belosName)) continue;
    const Teuchos::ParameterEntry alias = pl.getEntry(a.belosName);
    // Belos's "Convergence Tolerance" is a magnitude (double), "Maximum Iterations" an int; an
    // int tolerance such as 0 is read as the double it means.
    Teuchos::ParameterEntry value = alias;
    if (a.ownName == "Relative tolerance" && alias.isType<int>())
      value.setValue<double>(alias.getValue<int>(nullptr));
    const bool wantDouble = a.ownName == "Relative tolerance";
    if (wantDouble ? !value.isType<double>() : !value.isType<int>()) {
      std::ostringstream msg;
      msg << solver << ": parameter \"" << a.belosName << "\" (the Belos name of \"" << a.ownName
          << "\") must be " << (wantDouble ? "a double" : "an int") << ", got "
          << alias.getAny(false).typeName();
      throw std::invalid_argument(msg.str());
    }
    if (pl.isParameter(a.ownName)) {
      const Teuchos::ParameterEntry& own = pl.getEntry(a.ownName);
      if (!sameValue(own, value)) {
        std::ostringstream msg;
        msg << solver << ": \"" << a.belosName << "\" = " << show(value) << " and \"" << a.ownName
            << "\" = " << show(own) << " are the same setting (\"" << a.belosName
            << "\" is the Belos name of \"" << a.ownName << "\") with different values; give one";
        throw std::invalid_argument(msg.str());
      }
    } else {
      pl.setEntry(a.ownName, value);
    }
    pl.remove(a.belosName);
  }
}

int verbosityMask(int verbosity, const std::string& solver) {
  if (verbosity < 0 || (verbosity & ~kAllMsgTypes) != 0) {
    std::ostringstream msg;
    msg << solver << ": parameter \"Verbosity\" = " << verbosity
        << " is neither a level (0 silent, 1 summary, 2 every step) nor a sum of Belos::MsgType "
           "values (Warnings 1, IterationDetails 2, OrthoDetails 4, FinalSummary 8, "
           "TimingDetails 16, StatusTestDetails 32, Debug 64)";
    throw std::invalid_argument(msg.str());
  }
  if (verbosity == 1) return Belos::Warnings | Belos::FinalSummary;
  if (verbosity == 2) return Belos::Warnings | Belos::FinalSummary | Belos::IterationDetails;
  return verbosity;
}

Teuchos::RCP<Teuchos::Time> solverTimer(const std::string& name) {
  return Teuchos::TimeMonitor::getNewCounter(name);
}

}  // namespace tfeti
