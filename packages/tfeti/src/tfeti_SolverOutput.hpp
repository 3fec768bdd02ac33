#pragma once
// Where the iterative solvers (PCPG, MPRGP, SMALBE) print their progress: a stream the caller
// gives (e.g. a Teuchos::FancyOStream) or std::cout. Every line is formatted in a string stream
// of its own before it is written, so the format state of the target stream (precision, flags,
// width) is never changed: an application's std::cout stays as it set it.
#include <Teuchos_RCP.hpp>

#include <iostream>
#include <sstream>
#include <utility>

namespace tfeti {

class SolverOutput {
 public:
  // null: std::cout.
  void setStream(Teuchos::RCP<std::ostream> os) { os_ = std::move(os); }
  const Teuchos::RCP<std::ostream>& getStream() const { return os_; }
  std::ostream& stream() const { return os_.is_null() ? std::cout : *os_; }
  // A fresh formatter for one line; write() sends what it holds.
  static std::ostringstream line() { return std::ostringstream(); }
  void write(const std::ostringstream& text) const { stream() << text.str() << std::flush; }

 private:
  Teuchos::RCP<std::ostream> os_;
};

}  // namespace tfeti
