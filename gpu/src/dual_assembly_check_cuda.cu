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

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "check_options.hpp"
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
    if (a == "--require-device")
      o.requireDevice = true;
    else if (!gpucheck::intOption(a, "--elements", 1, o.elements) &&
             !gpucheck::intOption(a, "--count", 1, o.count) &&
             !gpucheck::intOption(a, "--streams", 1, o.streams) &&
             !gpucheck::intOption(a, "--phases", 1, o.phases) &&
             !gpucheck::intOption(a, "--check-stride", 1, o.checkStride))
      throw std::invalid_argument("unknown option " + a +
                                  " (--elements=NE --count=N --streams=S --phases=P "
                                  "--check-stride=C --require-device)");
  }
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

// The subdomain's sparse K_reg in pinned host memory (as the CPU hands it over), E's positions
// on the device and the sizes, for one ordering.
struct Problem {
  gpucheck::Ordering ordering;
  int n = 0, m = 0, first = 0, rows = 0;  // Y's rows: the trailing n - first of L
  std::size_t nnz = 0;
  int *hRowPtr = nullptr, *hCol = nullptr, *dUnit = nullptr;
  double* hVal = nullptr;

  Problem(const gpucheck::Hex8Subdomain& s, gpucheck::Ordering o)
      : ordering(o), n(s.n), m(s.dualRows()) {
    first = o == gpucheck::Ordering::Natural ? 0 : n - m;
    rows = n - first;
    const std::vector<int> pos = gpucheck::positions(s, o);
    const gpucheck::Csr a = gpucheck::permuted(s.Kreg, pos);
    const std::vector<int> unit = gpucheck::unitPositions(s, pos);
    nnz = a.nnz();
    cuda(cudaMallocHost(&hRowPtr, (n + 1) * sizeof(int)), "cudaMallocHost");
    cuda(cudaMallocHost(&hCol, nnz * sizeof(int)), "cudaMallocHost");
    cuda(cudaMallocHost(&hVal, nnz * sizeof(double)), "cudaMallocHost");
    std::copy(a.rowPtr.begin(), a.rowPtr.end(), hRowPtr);
    std::copy(a.col.begin(), a.col.end(), hCol);
    std::copy(a.val.begin(), a.val.end(), hVal);
    cuda(cudaMalloc(&dUnit, m * sizeof(int)), "cudaMalloc");
    cuda(cudaMemcpy(dUnit, unit.data(), m * sizeof(int), cudaMemcpyHostToDevice), "upload E");
  }
  ~Problem() {
    cudaFree(dUnit);
    cudaFreeHost(hRowPtr);
    cudaFreeHost(hCol);
    cudaFreeHost(hVal);
  }
  Problem(const Problem&) = delete;
  Problem& operator=(const Problem&) = delete;

  const char* name() const { return gpucheck::name(ordering); }
  std::size_t blockValues() const { return static_cast<std::size_t>(m) * m; }
  double flops() const {  // potrf, trsm, syrk
    return static_cast<double>(n) * n * n / 3.0 + static_cast<double>(rows) * rows * m +
           static_cast<double>(m) * m * rows;
  }
};

// One stream's handles and workspace: one subdomain in flight per lane.
struct Lane {
  cudaStream_t stream = nullptr;
  cublasHandle_t blas = nullptr;
  cusolverDnHandle_t solver = nullptr;
  double *A = nullptr, *Y = nullptr, *work = nullptr, *val = nullptr;
  int *rowPtr = nullptr, *col = nullptr;
  int lwork = 0;

  explicit Lane(const Problem& p) {
    cuda(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking), "cudaStreamCreate");
    cublas(cublasCreate(&blas), "cublasCreate");
    cublas(cublasSetStream(blas, stream), "cublasSetStream");
    cusolver(cusolverDnCreate(&solver), "cusolverDnCreate");
    cusolver(cusolverDnSetStream(solver, stream), "cusolverDnSetStream");
    cuda(cudaMalloc(&A, static_cast<std::size_t>(p.n) * p.n * sizeof(double)), "cudaMalloc K");
    cuda(cudaMalloc(&Y, static_cast<std::size_t>(p.rows) * p.m * sizeof(double)), "cudaMalloc Y");
    cuda(cudaMalloc(&rowPtr, (p.n + 1) * sizeof(int)), "cudaMalloc");
    cuda(cudaMalloc(&col, p.nnz * sizeof(int)), "cudaMalloc");
    cuda(cudaMalloc(&val, p.nnz * sizeof(double)), "cudaMalloc");
    cusolver(cusolverDnDpotrf_bufferSize(solver, CUBLAS_FILL_MODE_LOWER, p.n, A, p.n, &lwork),
             "cusolverDnDpotrf_bufferSize");
    cuda(cudaMalloc(&work, static_cast<std::size_t>(lwork) * sizeof(double)), "cudaMalloc work");
  }
  ~Lane() {
    cudaFree(A);
    cudaFree(Y);
    cudaFree(work);
    cudaFree(rowPtr);
    cudaFree(col);
    cudaFree(val);
    if (blas) cublasDestroy(blas);
    if (solver) cusolverDnDestroy(solver);
    if (stream) cudaStreamDestroy(stream);
  }
  Lane(const Lane&) = delete;
  Lane& operator=(const Lane&) = delete;

  // The workspace of one lane, in bytes (the dense K and Y).
  static double bytes(const Problem& p) {
    return (static_cast<double>(p.n) * p.n + static_cast<double>(p.rows) * p.m) * sizeof(double);
  }
};

// Every F_s of the batch, kept on the device where the batched apply reads it, and potrf's info
// per subdomain. Fewer than asked where the device cannot hold them beside the lanes.
struct Batch {
  int count = 0;
  double* F = nullptr;
  int* info = nullptr;

  Batch(const Problem& p, int asked, int streams) : count(asked) {
    std::size_t freeBytes = 0, totalBytes = 0;
    cuda(cudaMemGetInfo(&freeBytes, &totalBytes), "cudaMemGetInfo");
    const double block = p.blockValues() * sizeof(double);
    const double room = 0.8 * freeBytes - 1.2 * streams * Lane::bytes(p);
    if (room < count * block) count = std::max(1, static_cast<int>(room / block));
    cuda(cudaMalloc(&F, count * p.blockValues() * sizeof(double)), "cudaMalloc F");
    cuda(cudaMalloc(&info, count * sizeof(int)), "cudaMalloc info");
  }
  ~Batch() {
    cudaFree(F);
    cudaFree(info);
  }
  Batch(const Batch&) = delete;
  Batch& operator=(const Batch&) = delete;
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

// The phases of one subdomain on one stream (after a warm-up), mean over `repeats`, printed.
void timePhases(const Problem& p, Lane& lane, const Batch& batch, int repeats) {
  cudaEvent_t marks[PhaseCount + 1];  // one after each phase, then the start
  for (auto& e : marks) cuda(cudaEventCreate(&e), "cudaEventCreate");
  enqueue(p, lane, batch.F, batch.info, nullptr);
  std::vector<double> phaseMs(PhaseCount, 0.0);
  for (int r = 0; r < repeats; ++r) {
    const int sd = r % batch.count;
    cuda(cudaEventRecord(marks[PhaseCount], lane.stream), "cudaEventRecord");
    enqueue(p, lane, batch.F + sd * p.blockValues(), batch.info + sd, marks);
    cuda(cudaEventSynchronize(marks[Syrk]), "cudaEventSynchronize");
    for (int ph = 0; ph < PhaseCount; ++ph) {
      float ms = 0.0f;
      cuda(cudaEventElapsedTime(&ms, marks[ph == 0 ? PhaseCount : ph - 1], marks[ph]), "elapsed");
      phaseMs[ph] += ms;
    }
  }
  for (auto& e : marks) cudaEventDestroy(e);
  double oneMs = 0.0;
  std::printf("  %-13s one F_s:", p.name());
  for (int ph = 0; ph < PhaseCount; ++ph) {
    phaseMs[ph] /= repeats;
    oneMs += phaseMs[ph];
    std::printf(" %s %.3f,", kPhaseName[ph], phaseMs[ph]);
  }
  std::printf(" total %.3f ms (%.2f TFLOP/s, %.1f GFLOP)\n", oneMs,
              p.flops() / (oneMs * 1e-3) / 1e12, p.flops() / 1e9);
}

// Every subdomain of the batch once, round robin over the lanes, timed and printed; false where
// potrf failed on any.
bool timeBatch(const Problem& p, std::vector<std::unique_ptr<Lane>>& lanes, const Batch& batch,
               int asked) {
  cuda(cudaDeviceSynchronize(), "cudaDeviceSynchronize");
  const auto t0 = std::chrono::steady_clock::now();
  for (int sd = 0; sd < batch.count; ++sd)
    enqueue(p, *lanes[sd % lanes.size()], batch.F + sd * p.blockValues(), batch.info + sd, nullptr);
  cuda(cudaDeviceSynchronize(), "cudaDeviceSynchronize");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf(
      "  %-13s batch of %d on %zu streams: %.3f s, %.3f ms per F_s, %.2f TFLOP/s, F_s "
      "%.2f GiB on the device%s\n",
      p.name(), batch.count, lanes.size(), seconds, 1e3 * seconds / batch.count,
      p.flops() * batch.count / seconds / 1e12, batch.count * p.blockValues() * 8.0 / 1073741824.0,
      batch.count < asked ? " (fewer than asked: device memory)" : "");
  std::vector<int> info(batch.count);
  cuda(cudaMemcpy(info.data(), batch.info, batch.count * sizeof(int), cudaMemcpyDeviceToHost),
       "info");
  const int failed =
      static_cast<int>(std::count_if(info.begin(), info.end(), [](int v) { return v != 0; }));
  if (failed) std::printf("  potrf failed on %d subdomains  FAILED\n", failed);
  return failed == 0;
}

// The first and the last F_s: exactly symmetric, and the columns `cols` against the reference
// to 1e-11.
bool checkBlocks(const Problem& p, const Batch& batch, const std::vector<int>& cols,
                 const std::vector<long double>& ref) {
  bool ok = true;
  std::vector<double> h(p.blockValues());
  for (int sd : {0, batch.count - 1}) {
    cuda(cudaMemcpy(h.data(), batch.F + sd * p.blockValues(), h.size() * sizeof(double),
                    cudaMemcpyDeviceToHost),
         "download F_s");
    const double err = gpucheck::columnsError(h.data(), p.m, cols, ref);
    bool symmetric = true;
    for (int j = 0; j < p.m; ++j)
      for (int i = 0; i < j; ++i)
        symmetric = symmetric && h[i + static_cast<std::size_t>(j) * p.m] ==
                                     h[j + static_cast<std::size_t>(i) * p.m];
    const bool good = err <= 1e-11 && symmetric;
    ok = ok && good;
    std::printf("  %-13s F_s %d: error %.2e in %zu columns (limit 1e-11), symmetric %s%s\n",
                p.name(), sd, err, cols.size(), symmetric ? "yes" : "NO", good ? "" : "  FAILED");
  }
  return ok;
}

// One ordering: the problem, the batch's storage and the lanes, then the phases, the batch and
// the check.
bool runOrdering(const gpucheck::Hex8Subdomain& s, gpucheck::Ordering o, const Options& opt,
                 const std::vector<int>& cols, const std::vector<long double>& ref) {
  const Problem p(s, o);
  const Batch batch(p, opt.count, opt.streams);
  std::vector<std::unique_ptr<Lane>> lanes;
  for (int k = 0; k < opt.streams; ++k) lanes.push_back(std::make_unique<Lane>(p));
  timePhases(p, *lanes[0], batch, opt.phases);
  const bool factorized = timeBatch(p, lanes, batch, opt.count);
  return checkBlocks(p, batch, cols, ref) && factorized;
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
