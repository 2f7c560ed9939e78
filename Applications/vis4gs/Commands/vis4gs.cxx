// SPDX-License-Identifier: BSD-3-Clause
// The vis4gs program: one binary, subcommands registered by the vis4gs*Command.cxx files.
#include "Vis4GSCommand.h"
#include "Vis4GSProcessTuning.h"
#include "vtkGaussianOutputWindow.h"

#include <omp.h>

#include <iostream>
#include <stdexcept>

namespace
{
void PrintUsage(std::ostream& os)
{
  os << "Usage: vis4gs <command> [arguments] [options]\n\n"
        "Vis4GS diagnoses 3D Gaussian Splatting reconstructions Gaussian by Gaussian.\n\n"
        "Commands:\n";
  for (const auto& c : Vis4GSRegisteredCommands())
  {
    os << "  " << c.Name << std::string(c.Name[0] ? 12 - std::string(c.Name).size() : 0, ' ')
       << c.Summary << "\n";
  }
  os << "\nRun 'vis4gs <command> --help' for the options of a command.\n"
        "Options every command takes: --threads=N (default: all cores), --verbose, --help.\n";
}
}

int main(int argc, char* argv[])
{
  Vis4GSTuneProcess(argc, argv);
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h" ||
    std::string(argv[1]) == "help")
  {
    PrintUsage(std::cout);
    return argc < 2 ? 1 : 0;
  }
  if (std::string(argv[1]) == "--version")
  {
    std::cout << "vis4gs " << VIS4GS_VERSION << "\n";
    return 0;
  }
  const std::string name = argv[1];
  for (const auto& command : Vis4GSRegisteredCommands())
  {
    if (name != command.Name)
    {
      continue;
    }
    // VTK's errors and warnings in the program's form: "vis4gs NAME: error: FILE: problem".
    vtkGaussianOutputWindow::Install("vis4gs " + name);
    Vis4GSArguments args(command.Name, command.Summary);
    Vis4GSDefineArguments(command, args);
    const std::vector<std::string> rest(argv + 2, argv + argc);
    switch (args.Parse(rest, std::cerr))
    {
      case Vis4GSArguments::Result::Help:
        args.PrintHelp(std::cout);
        return 0;
      case Vis4GSArguments::Result::Error:
        return 2;
      case Vis4GSArguments::Result::Ok:
        break;
    }
    try
    {
      const int threads = args.GetInt("threads");
      if (threads < 0)
      {
        throw std::runtime_error("--threads must be 0 or more");
      }
      if (threads > 0)
      {
        omp_set_num_threads(threads);
      }
      return command.Run(args);
    }
    catch (const std::exception& e)
    {
      std::cerr << "vis4gs " << name << ": error: " << e.what() << "\n";
      return 1;
    }
  }
  std::cerr << "vis4gs: error: unknown command '" << name << "'\n\n";
  PrintUsage(std::cerr);
  return 2;
}
