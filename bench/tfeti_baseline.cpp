// Primal baseline for the FETI benchmarks: the same Q1 problems as the FETI solver (2D
// rectangles, 3D boxes clamped on the face x = 0), assembled into one distributed Tpetra matrix and
// solved by MueLu-preconditioned CG and by a distributed KLU2 direct solve, so that both can be
// timed against FETI in the same run. Prints one JSON object per solver on rank 0.
#include <mpi.h>
#include <sys/resource.h>

#include <Amesos2.hpp>
#include <BelosLinearProblem.hpp>
#include <BelosPseudoBlockCGSolMgr.hpp>
#include <BelosTpetraAdapter.hpp>
#include <MueLu_CreateTpetraPreconditioner.hpp>
#include <Teuchos_CommandLineProcessor.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <functional>
#include <iostream>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "plasticity_Q1Assembly.hpp"
#include "tfeti_CsrMatrix.hpp"
#include "tfeti_StructuredMesh.hpp"

namespace {

using Teuchos::RCP;
using Teuchos::rcp;
using SC = double;
using LO = int;
using GO = long long;
using Node = Tpetra::Map<LO, GO>::node_type;
using Map = Tpetra::Map<LO, GO, Node>;
using Matrix = Tpetra::CrsMatrix<SC, LO, GO, Node>;
using MV = Tpetra::MultiVector<SC, LO, GO, Node>;
using Vector = Tpetra::Vector<SC, LO, GO, Node>;
using Operator = Tpetra::Operator<SC, LO, GO, Node>;
using Comm = Teuchos::Comm<int>;

struct Problem {
  std::string name;
  int dim = 2;
  int n[3] = {0, 0, 1};     // cells per axis (n[2] = 1 in 2D)
  double l[3] = {0, 0, 0};  // domain lengths
  plasticity::Field field = plasticity::Field::Scalar;
  plasticity::ElasticLaw law;
  double source[3] = {0, 0, 0};

  int dofsPerNode() const { return plasticity::dofsPerNode(field, dim); }
  GO numNodes() const { return GO(n[0] + 1) * (n[1] + 1) * (dim == 3 ? n[2] + 1 : 1); }
  GO numDofs() const { return GO(dofsPerNode()) * numNodes(); }
  // Nodes per layer of the last axis (a row in 2D, a plane in 3D): ranks own slabs of layers.
  GO layerNodes() const { return dim == 2 ? GO(n[0] + 1) : GO(n[0] + 1) * (n[1] + 1); }
  int layers() const { return n[dim - 1]; }
  bool isDirichlet(GO dof) const { return (dof / dofsPerNode()) % (n[0] + 1) == 0; }
  void position(GO node, double x[3]) const {
    const GO i = node % (n[0] + 1), j = (node / (n[0] + 1)) % (n[1] + 1),
             k = node / (GO(n[0] + 1) * (n[1] + 1));
    x[0] = i * l[0] / n[0];
    x[1] = j * l[1] / n[1];
    x[2] = dim == 3 ? k * l[2] / n[2] : 0.0;
  }
};

struct System {
  RCP<Matrix> A;
  RCP<Vector> b;
};

// Each rank assembles a slab of cell layers (rows in 2D, planes in 3D) with the project's
// element kernels, so the matrix is the one the FETI subdomains are built from; shared node
// rows are summed by the export.
System assemble(const Problem& p, const RCP<const Comm>& comm) {
  const int P = comm->getSize(), rank = comm->getRank();
  const int k0 = static_cast<int>(GO(rank) * p.layers() / P);
  const int k1 = static_cast<int>(GO(rank + 1) * p.layers() / P);
  const int dpn = p.dofsPerNode();
  const GO layerNodes = p.layerNodes();

  plasticity::Q1Mesh mesh;
  mesh.dim = p.dim;
  if (k1 > k0) {
    std::vector<int> cells(p.n, p.n + p.dim);
    cells[p.dim - 1] = k1 - k0;
    mesh.cells = tfeti::StructuredMesh::cells(cells);
    for (GO node = k0 * layerNodes; node < (k1 + 1) * layerNodes; ++node) {
      double x[3];
      p.position(node, x);
      mesh.coords.insert(mesh.coords.end(), x, x + p.dim);
    }
  }
  tfeti::CsrMatrix K = plasticity::assembleStiffness(mesh, p.field, p.law);
  std::vector<double> f = plasticity::assembleBodyLoad(mesh, p.field, p.source);

  // Local node numbering is the global one shifted by the slab's first node layer.
  const GO offset = GO(dpn) * k0 * layerNodes;
  std::vector<GO> gids(K.rows);
  std::iota(gids.begin(), gids.end(), offset);

  // Dirichlet rows and columns become the identity so that the matrix stays symmetric for CG;
  // the prescribed values are zero, so dropping the columns needs no correction of the rhs.
  // Node layers on a slab boundary belong to two slabs; only the slab whose cell range starts
  // at that layer puts the 1 on the diagonal, so that the export sums to exactly 1.
  auto putsDiagonal = [&](int l) {
    const GO k = k0 + l / (dpn * layerNodes);
    return k < k1 || k == p.layers();
  };
  for (int l = 0; l < K.rows; ++l) {
    const bool rowFixed = p.isDirichlet(gids[l]);
    if (rowFixed) f[l] = 0.0;
    for (int k = K.rowPtr[l]; k < K.rowPtr[l + 1]; ++k) {
      const int c = K.colInd[k];
      if (rowFixed || p.isDirichlet(gids[c]))
        K.values[k] = (rowFixed && c == l && putsDiagonal(l)) ? 1.0 : 0.0;
    }
  }

  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  auto overlapMap = rcp(new Map(invalid, Teuchos::ArrayView<const GO>(gids), 0, comm));
  // Balanced by nodes rather than dofs: MueLu needs a node's dofs on one rank.
  const GO numNodes = p.numNodes();
  const GO ownedNodes = numNodes / P + (rank < numNodes % P ? 1 : 0);
  auto ownedMap = rcp(new Map(static_cast<Tpetra::global_size_t>(p.numDofs()),
                              static_cast<size_t>(dpn * ownedNodes), 0, comm));

  Teuchos::ArrayRCP<size_t> rowPtr(K.rowPtr.size());
  std::copy(K.rowPtr.begin(), K.rowPtr.end(), rowPtr.begin());
  Teuchos::ArrayRCP<LO> colInd(K.colInd.size());
  std::copy(K.colInd.begin(), K.colInd.end(), colInd.begin());
  Teuchos::ArrayRCP<SC> values(K.values.size());
  std::copy(K.values.begin(), K.values.end(), values.begin());
  K = tfeti::CsrMatrix();
  auto Aover = rcp(new Matrix(overlapMap, overlapMap, rowPtr, colInd, values));
  Aover->fillComplete(ownedMap, ownedMap);

  Vector bOver(overlapMap);
  {
    auto data = bOver.getDataNonConst();
    std::copy(f.begin(), f.end(), data.begin());
  }

  Tpetra::Export<LO, GO, Node> exporter(overlapMap, ownedMap);
  System s;
  s.A = rcp(new Matrix(ownedMap, (p.dim == 2 ? 9 : 27) * dpn));
  s.A->doExport(*Aover, exporter, Tpetra::ADD);
  s.A->fillComplete();
  s.b = rcp(new Vector(ownedMap));
  s.b->doExport(bOver, exporter, Tpetra::ADD);
  return s;
}

// Node coordinates on the node map matching dofMap (whose nodes' dofs are contiguous).
RCP<MV> nodeCoordinates(const Problem& p, const RCP<const Map>& dofMap) {
  const int dpn = p.dofsPerNode();
  auto nodeMap = rcp(new Map(dofMap->getGlobalNumElements() / dpn,
                             dofMap->getNodeNumElements() / dpn, 0, dofMap->getComm()));
  auto coords = rcp(new MV(nodeMap, p.dim));
  for (size_t l = 0; l < nodeMap->getNodeNumElements(); ++l) {
    double x[3];
    p.position(nodeMap->getGlobalElement(static_cast<LO>(l)), x);
    for (int d = 0; d < p.dim; ++d) coords->replaceLocalValue(static_cast<LO>(l), d, x[d]);
  }
  return coords;
}

// Translations and rotations (about the domain's centre, for conditioning): 3 modes in 2D (the
// in-plane rotation), 6 in 3D.
RCP<MV> rigidBodyModes(const Problem& p, const RCP<const Map>& map) {
  const int dim = p.dim, numModes = dim == 2 ? 3 : 6;
  auto modes = rcp(new MV(map, numModes));
  for (size_t l = 0; l < map->getNodeNumElements(); ++l) {
    const GO dof = map->getGlobalElement(static_cast<LO>(l));
    double x[3];
    p.position(dof / dim, x);
    for (int d = 0; d < dim; ++d) x[d] -= 0.5 * p.l[d];
    const int c = static_cast<int>(dof % dim);
    for (int d = 0; d < dim; ++d)
      modes->replaceLocalValue(static_cast<LO>(l), d, c == d ? 1.0 : 0.0);
    // Rotation about axis a moves component c by (e_a x x)_c.
    const int firstAxis = dim == 2 ? 2 : 0;
    for (int a = firstAxis; a < 3; ++a) {
      const int b = (a + 1) % 3, e = (a + 2) % 3;  // (e_a x x) = x_b e_e - x_e e_b
      const double v = c == e ? x[b] : (c == b ? -x[e] : 0.0);
      modes->replaceLocalValue(static_cast<LO>(l), dim + a - firstAxis, v);
    }
  }
  return modes;
}

struct Result {
  std::string solver;
  double setup = 0, solve = 0;
  int iterations = -1;  // -1: direct solver
  double relativeResidual = 0, normU = 0, maxAbsU = 0, peakRssMb = 0;
  bool converged = false;
};

// Wall time of f, maximum over ranks: the slowest rank is what the user waits for.
double timed(const Comm& comm, const std::function<void()>& f) {
  comm.barrier();
  const auto start = std::chrono::steady_clock::now();
  f();
  const double local =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double global = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, local, Teuchos::outArg(global));
  return global;
}

double peakRssMb(const Comm& comm) {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double local = usage.ru_maxrss / 1024.0;  // ru_maxrss is in KiB on Linux
  double global = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, local, Teuchos::outArg(global));
  return global;
}

// The residual is recomputed from scratch rather than trusted from the solver, which for CG only
// knows its recursively updated residual and for KLU2 nothing at all.
void finish(Result& r, const System& s, const Vector& x, double tolerance) {
  Vector res(*s.b, Teuchos::Copy);
  s.A->apply(x, res, Teuchos::NO_TRANS, -1.0, 1.0);
  r.relativeResidual = res.norm2() / s.b->norm2();
  r.normU = x.norm2();
  r.maxAbsU = x.normInf();
  r.peakRssMb = peakRssMb(*s.A->getComm());
  r.converged = r.relativeResidual <= tolerance;
}

Result solveMueLuCg(const Problem& p, const System& s, double rtol) {
  Teuchos::ParameterList params;
  params.set("verbosity", "none");
  params.set("multigrid algorithm", "sa");
  params.set("smoother: type", "CHEBYSHEV");
  // Degree 2 over a 7:1 eigenvalue range rather than MueLu's coarsening-based 20:1: the fastest
  // CG solve on both problems among the settings measured (degree 2 to 4, ratio 5 to 30).
  Teuchos::ParameterList& smoother = params.sublist("smoother: params");
  smoother.set("chebyshev: degree", 2);
  smoother.set("chebyshev: ratio eigenvalue", 7.0);
  // MueLu's coarse solver is KLU2 through Amesos2, which gives wrong answers in this Trilinos
  // for a matrix spread over more than one rank (see the pitfalls notes) and takes no "Trans"
  // parameter from MueLu. So the hierarchy gathers a level onto one rank as soon as some rank
  // holds fewer than 2000 of its rows (never for balance, always into a single part): the coarse
  // matrix then lives on a one-rank subcommunicator, where Amesos2's KLU2 path is correct, and
  // the coarse solve stays exact.
  params.set("repartition: enable", true);
  params.set("repartition: start level", 1);
  params.set("repartition: min rows per proc", 2000);
  params.set("repartition: target rows per proc", 1000000000);
  params.set("repartition: max imbalance", 1e9);
  // At least one coarsening, or a small enough problem would be its own coarse level and be
  // factored where it lies, spread over all ranks.
  params.set("coarse: max size", static_cast<int>(std::min<GO>(2000, p.numDofs() - 1)));
  // Zoltan2 never runs for a single part, but the repartitioning setup requires its input.
  params.sublist("user data").set("Coordinates", nodeCoordinates(p, s.A->getRowMap()));
  if (p.field == plasticity::Field::Elasticity) {
    params.set("number of equations", p.dim);
    params.sublist("user data").set("Nullspace", rigidBodyModes(p, s.A->getRowMap()));
  }

  Result r;
  r.solver = "muelu_cg";
  const Comm& comm = *s.A->getComm();
  RCP<Operator> M;
  r.setup = timed(comm, [&] { M = MueLu::CreateTpetraPreconditioner(RCP<Operator>(s.A), params); });

  auto x = rcp(new Vector(s.A->getDomainMap()));
  auto problem = rcp(new Belos::LinearProblem<SC, MV, Operator>(s.A, x, s.b));
  problem->setLeftPrec(M);
  problem->setProblem();
  auto belosParams = rcp(new Teuchos::ParameterList);
  belosParams->set("Convergence Tolerance", rtol);
  belosParams->set("Maximum Iterations", 2000);
  Belos::PseudoBlockCGSolMgr<SC, MV, Operator> cg(problem, belosParams);
  r.solve = timed(comm, [&] { cg.solve(); });
  r.iterations = cg.getNumIters();
  finish(r, s, *x, 10 * rtol);
  return r;
}

Result solveKlu2(const System& s) {
  Result r;
  r.solver = "klu2";
  const Comm& comm = *s.A->getComm();
  auto x = rcp(new Vector(s.A->getDomainMap()));
  RCP<Amesos2::Solver<Matrix, MV>> solver;
  r.setup = timed(comm, [&] {
    solver = Amesos2::create<Matrix, MV>("KLU2", s.A, x, s.b);
    // KLU2's non-transposed solve routine is miscompiled. On one rank Amesos2 already calls the
    // transposed routine (it passes the CRS arrays as the CSC of the transpose); on more ranks
    // it gathers the matrix and calls the broken one unless asked to transpose, which gives the
    // same answer since the matrix is symmetric.
    if (comm.getSize() > 1) {
      auto params = rcp(new Teuchos::ParameterList("Amesos2"));
      params->sublist("KLU2").set("Trans", "TRANS");
      solver->setParameters(params);
    }
    solver->symbolicFactorization();
    solver->numericFactorization();
  });
  r.solve = timed(comm, [&] { solver->solve(); });
  finish(r, s, *x, 1e-8);
  return r;
}

void printJson(const Result& r, const Problem& p, int ranks) {
  std::string line = "{\"solver\":\"" + r.solver + "\",\"problem\":\"" + p.name +
                     "\",\"dimension\":" + std::to_string(p.dim) +
                     ",\"nx\":" + std::to_string(p.n[0]) + ",\"ny\":" + std::to_string(p.n[1]) +
                     (p.dim == 3 ? ",\"nz\":" + std::to_string(p.n[2]) : std::string()) +
                     ",\"dofs\":" + std::to_string(p.numDofs()) +
                     ",\"ranks\":" + std::to_string(ranks);
  char buf[512];
  std::snprintf(buf, sizeof buf, ",\"setup_s\":%.4f,\"solve_s\":%.4f", r.setup, r.solve);
  line += buf;
  if (r.iterations >= 0) line += ",\"iterations\":" + std::to_string(r.iterations);
  std::snprintf(buf, sizeof buf,
                ",\"relative_residual\":%.3e,\"norm_u\":%.12e,\"max_abs_u\":%.12e,"
                "\"peak_rss_mb\":%.1f,\"converged\":%s}",
                r.relativeResidual, r.normU, r.maxAbsU, r.peakRssMb,
                r.converged ? "true" : "false");
  line += buf;
  std::cout << line << std::endl;
}

int run(int argc, char* argv[], const RCP<const Comm>& comm) {
  Teuchos::CommandLineProcessor clp(false, true);
  std::string problemName = "poisson", solverName = "both";
  int nx = 100, ny = 50, nz = 0;
  double lx = 2, ly = 1, lz = 1, rtol = 1e-6, E = 1, nu = 0.3, bx = 0, by = -1, bz = 0;
  clp.setDocString("Primal baseline (MueLu+CG, KLU2) for the TFETI benchmark problems.");
  clp.setOption("problem", &problemName, "poisson | elasticity");
  clp.setOption("solver", &solverName, "muelu | klu2 | both");
  clp.setOption("nx", &nx, "cells in x");
  clp.setOption("ny", &ny, "cells in y");
  clp.setOption("nz", &nz, "cells in z (0: a 2D problem)");
  clp.setOption("lx", &lx, "domain length in x");
  clp.setOption("ly", &ly, "domain length in y");
  clp.setOption("lz", &lz, "domain length in z (3D)");
  clp.setOption("rtol", &rtol, "CG relative residual tolerance");
  clp.setOption("E", &E, "Young's modulus (elasticity)");
  clp.setOption("nu", &nu, "Poisson's ratio (elasticity)");
  clp.setOption("bx", &bx, "body force x (elasticity)");
  clp.setOption("by", &by, "body force y (elasticity)");
  clp.setOption("bz", &bz, "body force z (3D elasticity)");
  switch (clp.parse(argc, argv)) {
    case Teuchos::CommandLineProcessor::PARSE_SUCCESSFUL:
      break;
    case Teuchos::CommandLineProcessor::PARSE_HELP_PRINTED:
      return 0;
    default:
      return 2;
  }
  if (problemName != "poisson" && problemName != "elasticity")
    throw std::invalid_argument("--problem must be poisson or elasticity, got " + problemName);
  if (solverName != "muelu" && solverName != "klu2" && solverName != "both")
    throw std::invalid_argument("--solver must be muelu, klu2 or both, got " + solverName);
  if (nx < 1 || ny < 1 || nz < 0 || !(lx > 0) || !(ly > 0) || !(lz > 0) || !(rtol > 0))
    throw std::invalid_argument(
        "--nx, --ny, --lx, --ly, --lz and --rtol must be positive, --nz non-negative");

  Problem p;
  p.name = problemName;
  p.dim = nz > 0 ? 3 : 2;
  p.n[0] = nx, p.n[1] = ny, p.n[2] = nz > 0 ? nz : 1;
  p.l[0] = lx, p.l[1] = ly, p.l[2] = lz;
  if (problemName == "poisson") {
    p.source[0] = 1.0;
  } else {
    p.field = plasticity::Field::Elasticity;
    p.law = plasticity::ElasticLaw(E, nu);
    p.source[0] = bx;
    p.source[1] = by;
    p.source[2] = bz;
  }

  const System s = assemble(p, comm);
  bool allConverged = true;
  auto report = [&](const Result& r) {
    if (comm->getRank() == 0) printJson(r, p, comm->getSize());
    allConverged = allConverged && r.converged;
  };
  if (solverName != "klu2") report(solveMueLuCg(p, s, rtol));
  if (solverName != "muelu") report(solveKlu2(s));
  return allConverged ? 0 : 1;
}

}  // namespace

int main(int argc, char* argv[]) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  try {
    return run(argc, argv, Tpetra::getDefaultComm());
  } catch (const std::exception& e) {
    std::cerr << "tfeti_baseline: " << e.what() << std::endl;
    // A failure on one rank would leave the others waiting in a collective forever.
    MPI_Abort(MPI_COMM_WORLD, 3);
  }
  return 3;
}
