#pragma once
// Where the iterative solvers (PCPG, MPRGP, SMALBE) print their progress: a stream the caller
// gives (e.g. a Teuchos::FancyOStream) or std::cout, and which Belos::MsgType kinds of message
// are wanted (the mask of tfeti_SolverConventions.hpp's verbosityMask). Every line is formatted
// in a string stream of its own before it is written, so the format state of the target stream
// (precision, flags, width) is never changed: an application's std::cout stays as it set it.
#include <BelosTypes.hpp>
#include <Teuchos_RCP.hpp>

#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace tfeti {

class SolverOutput {
 public:
  // null: std::cout.
  void setStream(Teuchos::RCP<std::ostream> os) { os_ = std::move(os); }
  const Teuchos::RCP<std::ostream>& getStream() const { return os_; }
  std::ostream& stream() const { return os_.is_null() ? std::cout : *os_; }
  // The Belos::MsgType mask of the wanted messages (0: none).
  void setMask(int mask) { mask_ = mask; }
  int mask() const { return mask_; }
  // Whether messages of this type are wanted. Errors (0) are thrown as exceptions; they are
  // also written whenever any other output is wanted.
  bool wants(Belos::MsgType type) const {
    return type == Belos::Errors ? mask_ != 0 : (mask_ & type) != 0;
  }
  // A fresh formatter for one line; write() sends what it holds.
  static std::ostringstream line() { return std::ostringstream(); }
  void write(const std::ostringstream& text) const { stream() << text.str() << std::flush; }
  void write(const std::string& text) const { stream() << text << std::flush; }
  // Returns solve(); an exception it throws is rethrown after its text is written as
  // "<solver>: error: ..." (Belos::Errors, when wanted and `root`).
  template <class Solve>
  auto reportingErrors(const char* solver, bool root, Solve&& solve) const -> decltype(solve()) {
    try {
      return solve();
    } catch (const std::exception& e) {
      if (wants(Belos::Errors) && root) write(std::string(solver) + ": error: " + e.what() + "\n");
      throw;
    }
  }

 private:
  Teuchos::RCP<std::ostream> os_;
  int mask_ = 0;
};

}  // namespace tfeti
