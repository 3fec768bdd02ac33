// The standalone check without a device: the blocks, the CPU reference and the host's batched
// apply in fp64 and fp32 (gpu/README.md). Exit status 1 when the host apply misses the reference.
#include <cstdio>
#include <exception>

#include "batched_dual.hpp"

int main(int argc, char** argv) {
  try {
    const gpucheck::Options o = gpucheck::parse(argc, argv);
    const gpucheck::Blocks b = gpucheck::load(o);
    gpucheck::describe(b);
    const std::vector<double> x = gpucheck::vectorFor(b);
    const std::vector<double> ref = gpucheck::reference(b, x);
    const bool ok = gpucheck::hostCheck(b, x, ref, o);
    std::printf("%s\n", ok ? "host check passed" : "host check FAILED");
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}
