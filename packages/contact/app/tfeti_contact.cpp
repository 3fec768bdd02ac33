// tfeti_contact --input=FILE.xml --output=DIR [--check]
//
// Reads a Teuchos ParameterList (XML), validates it (an unknown or mistyped parameter is an error
// naming it and listing the valid ones), runs the study and writes summary.json and VTU files
// into DIR. Exit codes: 0 success, 1 bad input or failure, 2 a solve did not converge (output is
// still written), 3 a nonlinear load step did not converge. --check is a dry run: the same
// set-up and checks up to the first solve (meshing, partitioning, contact search), a report of
// the problem and its estimated memory, nothing solved or written; exit code 0 or 1.
// --help (-h) prints this program's options; --kokkos-help the options Kokkos reads (threads,
// devices), which Kokkos would otherwise print first whenever it sees --help.
#include <Teuchos_CommandLineProcessor.hpp>
#include <Teuchos_DefaultComm.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>
#include <Tpetra_Core.hpp>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact_Driver.hpp"
#include "contact_RunSummary.hpp"
#include "tfeti_StrictParameters.hpp"

int main(int argc, char** argv) {
  // --help and -h are ours: Kokkos (initialized by the ScopeGuard) would print its own options
  // on --help before ours. --kokkos-help goes to Kokkos, which prints its options and removes it.
  bool help = false;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if (i > 0 && (a == "--help" || a == "-h"))
      help = true;
    else
      args.push_back(argv[i]);
  }
  bool kokkosHelp = false;
  for (char* a : args) kokkosHelp = kokkosHelp || std::string(a) == "--kokkos-help";
  int nargs = static_cast<int>(args.size());
  args.push_back(nullptr);
  char** argvLeft = args.data();
  Tpetra::ScopeGuard tpetra(&nargs, &argvLeft);
  auto comm = Tpetra::getDefaultComm();
  const bool root = comm->getRank() == 0;

  std::string input, output = "tfeti_output";
  std::string echo;
  bool printParameters = false, check = false;
  Teuchos::CommandLineProcessor clp(false, true);
  clp.setDocString(
      "Total FETI solver for the reference paper's problems and elastic, nonlinear and "
      "frictional contact: reads the ParameterList --input, writes summary.json and VTU files "
      "into --output. Kokkos' own options (threads, devices): --kokkos-help.");
  clp.setOption("input", &input, "ParameterList XML file");
  clp.setOption("output", &output, "output directory (created if missing)");
  clp.setOption("print-parameters", "no-print-parameters", &printParameters,
                "print every valid parameter with its default and documentation, then exit");
  clp.setOption("check", "no-check", &check,
                "dry run: validate, mesh, partition and report the problem without solving");
  clp.setOption("echo-parameters", &echo,
                "write the validated parameters (defaults filled in) as JSON to this file; "
                "summary.json holds them too");
  clp.recogniseAllOptions(true);
  clp.throwExceptions(false);
  const std::string program = std::filesystem::path(argv[0]).filename().string();
  if (help) {
    if (root) clp.printHelpMessage(program.c_str(), std::cout);
    return 0;
  }
  if (kokkosHelp) return 0;  // Kokkos has printed its options
  const auto parse = clp.parse(nargs, argvLeft);
  if (parse == Teuchos::CommandLineProcessor::PARSE_HELP_PRINTED) return 0;
  if (parse != Teuchos::CommandLineProcessor::PARSE_SUCCESSFUL) return 1;
  if (printParameters) {
    if (root)
      contact::validDriverParameters()->print(
          std::cout,
          Teuchos::ParameterList::PrintOptions().showDoc(true).indent(2).showTypes(true));
    return 0;
  }
  if (input.empty()) {
    if (root) std::cerr << "tfeti_contact: --input=FILE.xml is required\n";
    return 1;
  }

  int code = 1;
  try {
    if (!std::filesystem::exists(input)) throw std::runtime_error(input + ": no such file");
    // The raw text first: Teuchos converts numbers leniently ("1e-7e" -> 1e-7, "abc" -> 0).
    tfeti::strict::checkXmlNumbers(input, *contact::validDriverParameters());
    Teuchos::RCP<Teuchos::ParameterList> params;
    try {
      params = Teuchos::getParametersFromXmlFile(input);
    } catch (const std::exception& e) {
      throw std::runtime_error(input + ": not a valid ParameterList XML file: " + e.what());
    }
    contact::validateDriverParameters(*params, input);
    if (!echo.empty() && root) {
      std::ofstream file(echo);
      file << contact::parametersJson(*params).dump();
      if (!file) throw std::runtime_error("cannot write " + echo);
    }
    try {
      code = check ? contact::checkDriver(comm, *params, output, std::cout)
                   : contact::runDriver(comm, *params, output);
    } catch (const std::invalid_argument& e) {
      // Inconsistent parameters found while setting the problem up: name the input file.
      throw std::invalid_argument(input + ": " + e.what());
    }
  } catch (const std::exception& e) {
    if (root) std::cerr << "tfeti_contact: error: " << e.what() << "\n";
    return 1;
  }
  return code;
}
