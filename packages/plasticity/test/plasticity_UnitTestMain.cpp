// main() of the plasticity unit tests: MPI, then Kokkos through Tpetra's scope guard (the element
// kernels are Kokkos parallel_for's), then the Teuchos unit test repository.
#include <Teuchos_GlobalMPISession.hpp>
#include <Teuchos_UnitTestRepository.hpp>
#include <Tpetra_Core.hpp>

int main(int argc, char* argv[]) {
  Teuchos::GlobalMPISession mpiSession(&argc, &argv);
  Tpetra::ScopeGuard tpetraScope(&argc, &argv);
  Teuchos::UnitTestRepository::setGloballyReduceTestResult(true);
  return Teuchos::UnitTestRepository::runUnitTestsFromMain(argc, argv);
}
