// dual_assembly_check_cuda: the assembly of the explicit local dual operators on a CUDA device
// (gpu/README.md, "Assembly"; issue 29 asks whether F_s should be assembled on the GPU or the
// CPU). Per subdomain, K_reg crosses to the device as sparse rows (what the CPU assembles
// anyway), is scattered into a dense matrix, factorized by cuSOLVER (potrf), and
// F_s = B_s K⁺ B_sᵀ = Yᵀ Y with Y = L⁻¹ E by cuBLAS (trsm, syrk) straight into the batched
// storage that the apply reads, so F_s never crosses. E holds B_sᵀ's unit columns; with the
// boundary-last ordering they live in the trailing block of L alone, which cuts the trsm and
// the syrk to m³ each.
// Printed per ordering: each phase's time for one subdomain, the batch over several streams
// (seconds, per subdomain, TFLOP/s), and the error of the first and last F_s against the band
// Cholesky reference in long double.
#include <cublas_v2.h>
#include <cuda_runtime.h>
#include <cusolverDn.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "cuda_status.cuh"
#include "dual_assembly_reference.hpp"

namespace {

using gpucheck::cuda;
void cublas(cublasStatus_t s, const char* what) {
  if (s != CUBLAS_STATUS_SUCCESS)
    throw std::runtime_error(std::string(what) + ": cuBLAS status " + std::to_string(s));
}
void cusolver(cusolverStatus_t s, const char* what) {
  if (s != CUSOLVER_STATUS_SUCCESS)
    throw std::runtime_error(std::string(what) + ": cuSOLVER status " + std::to_string(s));
}

struct Options {
  int elements = 8, count = 512, streams = 4, phases = 8, checkStride = 16;
  bool requireDevice = false;  // no device is an error, not a skip
};

Options parse(int argc, char** argv) {
  Options o;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--require-device") {
      o.requireDevice = true;
      continue;
    }
    const auto value = [&](const char* name, int& out) {
      const std::string p = std::string(name) + "=";
      if (a.rfind(p, 0) != 0) return false;
      out = std::stoi(a.substr(p.size()));
      return true;
    };
    if (!value("--elements", o.elements) && !value("--count", o.count) &&
        !value("--streams", o.streams) && !value("--phases", o.phases) &&
        !value("--check-stride", o.checkStride))
      throw std::invalid_argument("unknown option " + a +
                                  " (--elements=NE --count=N --streams=S --phases=P "
                                  "--check-stride=C --require-device)");
  }
  if (o.count < 1 || o.streams < 1 || o.phases < 1 || o.checkStride < 1)
    throw std::invalid_argument("--count, --streams, --phases and --check-stride must be >= 1");
  return o;
}

// A[i, col] = val for the sparse rows (A zeroed before), column-major n × n.
__global__ void scatterRows(int n, const int* rowPtr, const int* col, const double* val,
                            double* A) {
  for (int i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += gridDim.x * blockDim.x)
    for (int e = rowPtr[i]; e < rowPtr[i + 1]; ++e)
      A[i + static_cast<long long>(col[e]) * n] = val[e];
}

// Y (rows × m, zeroed before) gets E's ones: column k at row unit[k] - first, none where -1.
__global__ void unitColumns(int m, int rows, int first, const int* unit, double* Y) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k < m && unit[k] >= 0) Y[unit[k] - first + static_cast<long long>(k) * rows] = 1.0;
}

// The strict lower triangle of F (m × m, column-major) from its upper one, by 32 × 32 tiles
// through shared memory so that reads and writes both run along columns.
__global__ void mirrorUpper(int m, double* F) {
  __shared__ double tile[32][33];
  const int bi = blockIdx.x, bj = blockIdx.y;  // the lower tile (bi, bj) from the upper (bj, bi)
  if (bi < bj) return;
  for (int y = threadIdx.y; y < 32; y += blockDim.y) {
    const int r = bj * 32 + threadIdx.x, c = bi * 32 + y;
    if (r < m && c < m) tile[y][threadIdx.x] = F[r + static_cast<long long>(c) * m];
  }
  __syncthreads();
  for (int y = threadIdx.y; y < 32; y += blockDim.y) {
    const int i = bi * 32 + threadIdx.x, j = bj * 32 + y;
    if (i < m && j < m && i > j) F[i + static_cast<long long>(j) * m] = tile[threadIdx.x][y];
  }
}

// One stream's handles and workspace: one subdomain in flight per lane.
struct Lane {
  cudaStream_t stream = nullptr;
  cublasHandle_t blas = nullptr;
  cusolverDnHandle_t solver = nullptr;
  double *A = nullptr, *Y = nullptr, *work = nullptr, *val = nullptr;
  int *rowPtr = nullptr, *col = nullptr;
  int lwork = 0;
};

// The subdomain's sparse K_reg in pinned host memory (as the CPU hands it over), E's positions
// and the sizes, for one ordering.
struct Problem {
  int n = 0, m = 0, first = 0, rows = 0;  // Y's rows: the trailing n - first of L
  std::size_t nnz = 0;
  int *hRowPtr = nullptr, *hCol = nullptr, *dUnit = nullptr;
  double* hVal = nullptr;
  double flops() const {  // potrf, trsm, syrk
    return static_cast<double>(n) * n * n / 3.0 + static_cast<double>(rows) * rows * m +
           static_cast<double>(m) * m * rows;
  }
};

enum Phase { Upload, Densify, Potrf, Trsm, Syrk, PhaseCount };
const char* const kPhaseName[PhaseCount] = {"upload", "densify", "potrf", "trsm", "syrk+mirror"};

// Enqueues the assembly of one F_s on the lane; `marks`, where given, gets an event after each
// phase.
void enqueue(const Problem& p, Lane& l, double* F, int* info, cudaEvent_t* marks) {
  const auto mark = [&](Phase ph) {
    if (marks) cuda(cudaEventRecord(marks[ph], l.stream), "cudaEventRecord");
  };
  cuda(cudaMemcpyAsync(l.rowPtr, p.hRowPtr, (p.n + 1) * sizeof(int), cudaMemcpyHostToDevice,
                       l.stream),
       "upload rows");
  cuda(cudaMemcpyAsync(l.col, p.hCol, p.nnz * sizeof(int), cudaMemcpyHostToDevice, l.stream),
       "upload columns");
  cuda(cudaMemcpyAsync(l.val, p.hVal, p.nnz * sizeof(double), cudaMemcpyHostToDevice, l.stream),
       "upload values");
  mark(Upload);
  cuda(cudaMemsetAsync(l.A, 0, static_cast<std::size_t>(p.n) * p.n * sizeof(double), l.stream),
       "zero K");
  scatterRows<<<(p.n + 127) / 128, 128, 0, l.stream>>>(p.n, l.rowPtr, l.col, l.val, l.A);
  mark(Densify);
  cusolver(cusolverDnDpotrf(l.solver, CUBLAS_FILL_MODE_LOWER, p.n, l.A, p.n, l.work, l.lwork, info),
           "cusolverDnDpotrf");
  mark(Potrf);
  cuda(cudaMemsetAsync(l.Y, 0, static_cast<std::size_t>(p.rows) * p.m * sizeof(double), l.stream),
       "zero Y");
  unitColumns<<<(p.m + 127) / 128, 128, 0, l.stream>>>(p.m, p.rows, p.first, p.dUnit, l.Y);
  const double one = 1.0, zero = 0.0;
  const double* Lbb = l.A + p.first + static_cast<std::size_t>(p.first) * p.n;
  cublas(cublasDtrsm(l.blas, CUBLAS_SIDE_LEFT, CUBLAS_FILL_MODE_LOWER, CUBLAS_OP_N,
                     CUBLAS_DIAG_NON_UNIT, p.rows, p.m, &one, Lbb, p.n, l.Y, p.rows),
         "cublasDtrsm");
  mark(Trsm);
  cublas(cublasDsyrk(l.blas, CUBLAS_FILL_MODE_UPPER, CUBLAS_OP_T, p.m, p.rows, &one, l.Y, p.rows,
                     &zero, F, p.m),
         "cublasDsyrk");
  const dim3 tiles((p.m + 31) / 32, (p.m + 31) / 32);
  mirrorUpper<<<tiles, dim3(32, 8), 0, l.stream>>>(p.m, F);
  cuda(cudaGetLastError(), "kernel launch");
  mark(Syrk);
}

bool runOrdering(const gpucheck::Hex8Subdomain& s, gpucheck::Ordering o, const Options& opt,
                 const std::vector<int>& cols, const std::vector<long double>& ref) {
  Problem p;
  p.n = s.n;
  p.m = s.dualRows();
  p.first = o == gpucheck::Ordering::Natural ? 0 : p.n - p.m;
  p.rows = p.n - p.first;
  const std::vector<int> pos = gpucheck::positions(s, o);
  const gpucheck::Csr a = gpucheck::permuted(s.Kreg, pos);
  const std::vector<int> unit = gpucheck::unitPositions(s, pos);
  p.nnz = a.nnz();
  cuda(cudaMallocHost(&p.hRowPtr, (p.n + 1) * sizeof(int)), "cudaMallocHost");
  cuda(cudaMallocHost(&p.hCol, p.nnz * sizeof(int)), "cudaMallocHost");
  cuda(cudaMallocHost(&p.hVal, p.nnz * sizeof(double)), "cudaMallocHost");
  std::copy(a.rowPtr.begin(), a.rowPtr.end(), p.hRowPtr);
  std::copy(a.col.begin(), a.col.end(), p.hCol);
  std::copy(a.val.begin(), a.val.end(), p.hVal);
  cuda(cudaMalloc(&p.dUnit, p.m * sizeof(int)), "cudaMalloc");
  cuda(cudaMemcpy(p.dUnit, unit.data(), p.m * sizeof(int), cudaMemcpyHostToDevice), "upload E");

  // Every F_s stays on the device, where the batched apply reads it.
  const std::size_t block = static_cast<std::size_t>(p.m) * p.m;
  std::size_t freeBytes = 0, totalBytes = 0;
  cuda(cudaMemGetInfo(&freeBytes, &totalBytes), "cudaMemGetInfo");
  const std::size_t laneBytes =
      (static_cast<std::size_t>(p.n) * p.n + static_cast<std::size_t>(p.rows) * p.m) * 8;
  int count = opt.count;
  const double room = 0.8 * freeBytes - static_cast<double>(opt.streams) * laneBytes * 1.2;
  if (room < static_cast<double>(count) * block * 8)
    count = std::max(1, static_cast<int>(room / (block * 8.0)));
  double* F = nullptr;
  int* info = nullptr;
  cuda(cudaMalloc(&F, static_cast<std::size_t>(count) * block * sizeof(double)), "cudaMalloc F");
  cuda(cudaMalloc(&info, count * sizeof(int)), "cudaMalloc info");

  std::vector<Lane> lanes(opt.streams);
  for (Lane& l : lanes) {
    cuda(cudaStreamCreateWithFlags(&l.stream, cudaStreamNonBlocking), "cudaStreamCreate");
    cublas(cublasCreate(&l.blas), "cublasCreate");
    cublas(cublasSetStream(l.blas, l.stream), "cublasSetStream");
    cusolver(cusolverDnCreate(&l.solver), "cusolverDnCreate");
    cusolver(cusolverDnSetStream(l.solver, l.stream), "cusolverDnSetStream");
    cuda(cudaMalloc(&l.A, static_cast<std::size_t>(p.n) * p.n * sizeof(double)), "cudaMalloc K");
    cuda(cudaMalloc(&l.Y, static_cast<std::size_t>(p.rows) * p.m * sizeof(double)), "cudaMalloc Y");
    cuda(cudaMalloc(&l.rowPtr, (p.n + 1) * sizeof(int)), "cudaMalloc");
    cuda(cudaMalloc(&l.col, p.nnz * sizeof(int)), "cudaMalloc");
    cuda(cudaMalloc(&l.val, p.nnz * sizeof(double)), "cudaMalloc");
    cusolver(cusolverDnDpotrf_bufferSize(l.solver, CUBLAS_FILL_MODE_LOWER, p.n, l.A, p.n, &l.lwork),
             "cusolverDnDpotrf_bufferSize");
    cuda(cudaMalloc(&l.work, static_cast<std::size_t>(l.lwork) * sizeof(double)),
         "cudaMalloc work");
  }

  // The phases of one subdomain, on one stream (after a warm-up), mean over opt.phases.
  cudaEvent_t marks[PhaseCount + 1];
  for (auto& e : marks) cuda(cudaEventCreate(&e), "cudaEventCreate");
  enqueue(p, lanes[0], F, info, nullptr);
  std::vector<double> phaseMs(PhaseCount, 0.0);
  for (int r = 0; r < opt.phases; ++r) {
    cuda(cudaEventRecord(marks[PhaseCount], lanes[0].stream), "cudaEventRecord");
    enqueue(p, lanes[0], F + (r % count) * block, info + r % count, marks);
    cuda(cudaEventSynchronize(marks[Syrk]), "cudaEventSynchronize");
    float ms = 0.0f;
    cuda(cudaEventElapsedTime(&ms, marks[PhaseCount], marks[Upload]), "elapsed");
    phaseMs[Upload] += ms;
    for (int ph = Densify; ph < PhaseCount; ++ph) {
      cuda(cudaEventElapsedTime(&ms, marks[ph - 1], marks[ph]), "elapsed");
      phaseMs[ph] += ms;
    }
  }
  double oneMs = 0.0;
  std::printf("  %-13s one F_s:", gpucheck::name(o));
  for (int ph = 0; ph < PhaseCount; ++ph) {
    phaseMs[ph] /= opt.phases;
    oneMs += phaseMs[ph];
    std::printf(" %s %.3f,", kPhaseName[ph], phaseMs[ph]);
  }
  std::printf(" total %.3f ms (%.2f TFLOP/s, %.1f GFLOP)\n", oneMs,
              p.flops() / (oneMs * 1e-3) / 1e12, p.flops() / 1e9);

  // The batch: every subdomain once, round robin over the streams.
  cuda(cudaDeviceSynchronize(), "cudaDeviceSynchronize");
  const auto t0 = std::chrono::steady_clock::now();
  for (int sd = 0; sd < count; ++sd)
    enqueue(p, lanes[sd % opt.streams], F + sd * block, info + sd, nullptr);
  cuda(cudaDeviceSynchronize(), "cudaDeviceSynchronize");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::vector<int> hInfo(count);
  cuda(cudaMemcpy(hInfo.data(), info, count * sizeof(int), cudaMemcpyDeviceToHost), "info");
  int failed = 0;
  for (int v : hInfo) failed += v != 0;
  std::printf(
      "  %-13s batch of %d on %d streams: %.3f s, %.3f ms per F_s, %.2f TFLOP/s, F_s "
      "%.2f GiB on the device%s\n",
      gpucheck::name(o), count, opt.streams, seconds, 1e3 * seconds / count,
      p.flops() * count / seconds / 1e12, count * block * 8.0 / 1073741824.0,
      count < opt.count ? " (fewer than asked: device memory)" : "");

  // The first and the last F_s against the reference.
  bool ok = failed == 0;
  if (failed) std::printf("  potrf failed on %d subdomains  FAILED\n", failed);
  std::vector<double> h(block);
  for (int sd : {0, count - 1}) {
    cuda(cudaMemcpy(h.data(), F + static_cast<std::size_t>(sd) * block, block * sizeof(double),
                    cudaMemcpyDeviceToHost),
         "download F_s");
    const double err = gpucheck::columnsError(h.data(), p.m, cols, ref);
    double asym = 0.0;
    for (int j = 0; j < p.m; ++j)
      for (int i = 0; i < j; ++i)
        asym = std::max(asym, std::abs(h[i + static_cast<std::size_t>(j) * p.m] -
                                       h[j + static_cast<std::size_t>(i) * p.m]));
    const bool good = err <= 1e-11 && asym == 0.0;
    ok = ok && good;
    std::printf("  %-13s F_s %d: error %.2e in %zu columns (limit 1e-11), symmetric %s%s\n",
                gpucheck::name(o), sd, err, cols.size(), asym == 0.0 ? "yes" : "NO",
                good ? "" : "  FAILED");
  }

  for (auto& e : marks) cudaEventDestroy(e);
  for (Lane& l : lanes) {
    cudaFree(l.A);
    cudaFree(l.Y);
    cudaFree(l.work);
    cudaFree(l.rowPtr);
    cudaFree(l.col);
    cudaFree(l.val);
    cublasDestroy(l.blas);
    cusolverDnDestroy(l.solver);
    cudaStreamDestroy(l.stream);
  }
  cudaFree(F);
  cudaFree(info);
  cudaFree(p.dUnit);
  cudaFreeHost(p.hRowPtr);
  cudaFreeHost(p.hCol);
  cudaFreeHost(p.hVal);
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options opt = parse(argc, argv);
    cudaDeviceProp prop{};
    if (!gpucheck::visibleDevice(prop, opt.requireDevice)) return 0;
    const gpucheck::Hex8Subdomain s = gpucheck::hex8Subdomain(opt.elements);
    const auto t0 = std::chrono::steady_clock::now();
    const gpucheck::BandCholesky c(s.Kreg);
    bool ok = gpucheck::subdomainChecks(s, c);
    std::vector<int> cols;
    for (int l = 0; l < s.dualRows(); l += opt.checkStride) cols.push_back(l);
    if (cols.back() != s.dualRows() - 1) cols.push_back(s.dualRows() - 1);
    const std::vector<long double> ref = gpucheck::referenceColumns(s, c, cols);
    std::printf(
        "device: %s; F_s assembly of %d subdomains of %d³ Hex8 (%d dofs, %d dual rows, "
        "K_reg %zu nonzeros); host reference %.2f s\n",
        prop.name, opt.count, opt.elements, s.n, s.dualRows(), s.Kreg.nnz(),
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    for (gpucheck::Ordering o : {gpucheck::Ordering::Natural, gpucheck::Ordering::BoundaryLast})
      ok = runOrdering(s, o, opt, cols, ref) && ok;
    std::printf("%s\n", ok ? "device assembly check passed" : "device assembly check FAILED");
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}
