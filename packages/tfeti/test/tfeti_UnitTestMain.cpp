// main() of the tfeti unit test executables: MPI, then Kokkos through Tpetra's scope guard, then
// the Teuchos unit test repository. Pass/fail is reduced over all ranks, so every rank of an MPI
// test reports the same verdict.
#include <Teuchos_GlobalMPISession.hpp>
#include <Teuchos_UnitTestRepository.hpp>
#include <Tpetra_Core.hpp>

int main(int argc, char* argv[]) {
  Teuchos::GlobalMPISession mpiSession(&argc, &argv);
  Tpetra::ScopeGuard tpetraScope(&argc, &argv);
  Teuchos::UnitTestRepository::setGloballyReduceTestResult(true);
  return Teuchos::UnitTestRepository::runUnitTestsFromMain(argc, argv);
}
