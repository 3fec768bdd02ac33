// dual_assembly_check_cpu: the host part of the assembly check (gpu/README.md, "Assembly"),
// which builds and runs everywhere. On subdomains of 2³, 3³ and 4³ Hex8 elements it checks the
// subdomain (rigid modes, patch test, K K⁺ K = K) and the device's algorithm carried out on the
// host in both orderings (dense Cholesky, Y = L⁻¹ E, F_s = Yᵀ Y) against the band Cholesky
// reference in long double, every column.
#include <cstdio>
#include <exception>
#include <numeric>

#include "dual_assembly_reference.hpp"

int main() {
  try {
    bool ok = true;
    for (int elements : {2, 3, 4}) {
      const gpucheck::Hex8Subdomain s = gpucheck::hex8Subdomain(elements);
      const gpucheck::BandCholesky c(s.Kreg);
      ok = gpucheck::subdomainChecks(s, c) && ok;
      const int m = s.dualRows();
      std::vector<int> all(m);
      std::iota(all.begin(), all.end(), 0);
      const std::vector<long double> ref = gpucheck::referenceColumns(s, c, all);
      for (gpucheck::Ordering o : {gpucheck::Ordering::Natural, gpucheck::Ordering::BoundaryLast}) {
        const std::vector<double> F = gpucheck::denseDualBlock(s, o);
        const double err = gpucheck::columnsError(F.data(), m, all, ref);
        const bool good = err <= 1e-12;
        ok = ok && good;
        std::printf("  host F_s, %-13s: error %.2e against the band reference (limit 1e-12)%s\n",
                    gpucheck::name(o), err, good ? "" : "  FAILED");
      }
    }
    std::printf("%s\n", ok ? "host assembly check passed" : "host assembly check FAILED");
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}
