#include "contact_NonlinearHistory.hpp"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace contact {

namespace {

constexpr const char* kStateHeader = "tfeti_contact nonlinear restart 1";
constexpr std::uint64_t kSubdomainMagic = 0x7466657469727331ULL;  // "tfetirs1"

std::ofstream openForWriting(const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << std::setprecision(17);
  return out;
}

void writeVector(std::ostream& out, const std::vector<double>& v) {
  out << v.size();
  for (double x : v) out << " " << x;
  out << "\n";
}

std::vector<double> readVector(std::istream& in) {
  std::size_t n = 0;
  in >> n;
  std::vector<double> v(n);
  for (auto& x : v) in >> x;
  return v;
}

}  // namespace

Json stepsJson(const NonlinearHistory& history) {
  Json steps = Json::array();
  for (const auto& r : history.steps) {
    Json j = Json::object();
    j["step"] = r.step;
    j["load_factor"] = r.loadFactor;
    j["outer_iterations"] = r.outerIterations;
    j["mprgp_iterations"] = r.mprgpIterations;
    j["hessian_multiplications"] = r.hessianMultiplications;
    j["cutbacks"] = r.cutbacks;
    Json res = Json::array(), inc = Json::array();
    for (double v : r.residuals) res.push(v);
    for (double v : r.increments) inc.push(v);
    j["residuals"] = std::move(res);
    j["increments"] = std::move(inc);
    j["p_max"] = r.pMax;
    j["max_von_mises"] = r.maxVonMises;
    j["max_plastic_strain"] = r.maxPlasticStrain;
    j["contact_extent"] = r.contactExtent;
    j["contact_force"] = r.contactForce;
    steps.push(std::move(j));
  }
  return steps;
}

IterationTotals iterationTotals(const NonlinearHistory& history) {
  IterationTotals t;
  for (const auto& r : history.iterations) {
    ++t.iterations;
    t.rejected += r.accepted ? 0 : 1;
    t.mprgpIterations += r.mprgpIterations;
    t.hessianMultiplications += r.hessianMultiplications;
  }
  return t;
}

void writeRestartState(const std::string& restartDir, const NonlinearHistory& h) {
  const std::string path = restartDir + "/state.txt", tmp = path + ".tmp";
  {
    std::ofstream out = openForWriting(tmp);
    out << kStateHeader << "\n"
        << h.step << " " << h.loadFactor << " " << h.stepSize << "\n"
        << h.steps.size() << "\n";
    for (const auto& s : h.steps) {
      out << s.step << " " << s.loadFactor << " " << s.outerIterations << " " << s.mprgpIterations
          << " " << s.hessianMultiplications << " " << s.cutbacks << " " << s.pMax << " "
          << s.maxVonMises << " " << s.maxPlasticStrain << " " << s.contactExtent << " "
          << s.contactForce << "\n";
      writeVector(out, s.residuals);
      writeVector(out, s.increments);
    }
    out << h.iterations.size() << "\n";
    for (const auto& r : h.iterations)
      out << r.step << " " << r.loadFactor << " " << r.iteration << " " << r.relativeResidual << " "
          << r.relativeIncrement << " " << r.solutionNorm << " " << r.mprgpIterations << " "
          << r.hessianMultiplications << " " << (r.accepted ? 1 : 0) << "\n";
    // Added later: read back when present (older restart files end above).
    out << "iteration_extras " << h.iterations.size() << "\n";
    for (const auto& r : h.iterations)
      out << r.qpToleranceFactor << " " << r.lineSearchStep << "\n";
    if (!out) throw std::runtime_error("cannot write " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

NonlinearHistory readRestartState(const std::string& restartDir) {
  const std::string path = restartDir + "/state.txt";
  std::ifstream in(path);
  if (!in)
    throw std::runtime_error(path +
                             ": no restart state (a run writes it at every converged load step)");
  std::string header;
  std::getline(in, header);
  if (header != kStateHeader)
    throw std::runtime_error(path + ": not a tfeti_contact restart file (header \"" + header +
                             "\")");
  NonlinearHistory h;
  std::size_t n = 0;
  in >> h.step >> h.loadFactor >> h.stepSize >> n;
  h.steps.resize(n);
  for (auto& s : h.steps) {
    in >> s.step >> s.loadFactor >> s.outerIterations >> s.mprgpIterations >>
        s.hessianMultiplications >> s.cutbacks >> s.pMax >> s.maxVonMises >> s.maxPlasticStrain >>
        s.contactExtent >> s.contactForce;
    s.residuals = readVector(in);
    s.increments = readVector(in);
  }
  in >> n;
  h.iterations.resize(n);
  for (auto& r : h.iterations) {
    int accepted = 0;
    in >> r.step >> r.loadFactor >> r.iteration >> r.relativeResidual >> r.relativeIncrement >>
        r.solutionNorm >> r.mprgpIterations >> r.hessianMultiplications >> accepted;
    r.accepted = accepted != 0;
  }
  if (!in) throw std::runtime_error(path + ": truncated or malformed restart state");
  std::string extras;
  if (in >> extras) {
    if (extras != "iteration_extras" || !(in >> n) || n != h.iterations.size())
      throw std::runtime_error(path + ": malformed iteration_extras section");
    for (auto& r : h.iterations) in >> r.qpToleranceFactor >> r.lineSearchStep;
    if (!in) throw std::runtime_error(path + ": truncated iteration_extras section");
  }
  return h;
}

void writeIterationsCsv(const std::string& path, const NonlinearHistory& h) {
  std::ofstream out = openForWriting(path);
  out << "step,load_factor,iteration,relative_residual,relative_increment,solution_norm,"
         "mprgp_iterations,hessian_multiplications,accepted,qp_tolerance_factor,"
         "line_search_step\n";
  for (const auto& r : h.iterations)
    out << r.step << "," << r.loadFactor << "," << r.iteration << "," << r.relativeResidual << ","
        << r.relativeIncrement << "," << r.solutionNorm << "," << r.mprgpIterations << ","
        << r.hessianMultiplications << "," << (r.accepted ? 1 : 0) << "," << r.qpToleranceFactor
        << "," << r.lineSearchStep << "\n";
}

void writeStepsCsv(const std::string& path, const NonlinearHistory& h) {
  std::ofstream out = openForWriting(path);
  out << "step,load_factor,outer_iterations,mprgp_iterations,p_max,max_von_mises,"
         "max_plastic_strain,contact_extent\n";
  for (const auto& s : h.steps)
    out << s.step << "," << s.loadFactor << "," << s.outerIterations << "," << s.mprgpIterations
        << "," << s.pMax << "," << s.maxVonMises << "," << s.maxPlasticStrain << ","
        << s.contactExtent << "\n";
}

std::string restartStepDirectory(const std::string& restartDir, int step) {
  std::ostringstream s;
  s << restartDir << "/step_" << std::setw(4) << std::setfill('0') << step;
  return s.str();
}

void writeSubdomainRestart(const std::string& stepDir, const SubdomainRestart& state) {
  const std::string path = stepDir + "/subdomain_" + std::to_string(state.id) + ".bin";
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write " + path);
  const std::uint64_t header[4] = {kSubdomainMagic, static_cast<std::uint64_t>(state.id),
                                   state.displacement.size(), state.history.size()};
  out.write(reinterpret_cast<const char*>(header), sizeof(header));
  out.write(reinterpret_cast<const char*>(state.displacement.data()),
            static_cast<std::streamsize>(state.displacement.size() * sizeof(double)));
  out.write(reinterpret_cast<const char*>(state.history.data()),
            static_cast<std::streamsize>(state.history.size() * sizeof(double)));
  if (!out) throw std::runtime_error("cannot write " + path);
}

SubdomainRestart readSubdomainRestart(const std::string& stepDir, int id) {
  const std::string path = stepDir + "/subdomain_" + std::to_string(id) + ".bin";
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error(path + ": missing restart file of subdomain " + std::to_string(id));
  std::uint64_t header[4];
  in.read(reinterpret_cast<char*>(header), sizeof(header));
  if (!in || header[0] != kSubdomainMagic || header[1] != static_cast<std::uint64_t>(id))
    throw std::runtime_error(path + ": not the restart file of subdomain " + std::to_string(id));
  SubdomainRestart s;
  s.id = id;
  s.displacement.resize(header[2]);
  s.history.resize(header[3]);
  in.read(reinterpret_cast<char*>(s.displacement.data()),
          static_cast<std::streamsize>(s.displacement.size() * sizeof(double)));
  in.read(reinterpret_cast<char*>(s.history.data()),
          static_cast<std::streamsize>(s.history.size() * sizeof(double)));
  if (!in) throw std::runtime_error(path + ": truncated restart file");
  return s;
}

}  // namespace contact
