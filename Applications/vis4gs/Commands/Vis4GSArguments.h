// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSArguments.h
 * @brief Command-line options of the vis4gs subcommands, in f3d's style: long kebab-case
 * options `--name=value`, booleans as `--name` / `--no-name`, every option documented with its
 * type and default in `--help`.
 */
#ifndef Vis4GSArguments_h
#define Vis4GSArguments_h

#include <map>
#include <ostream>
#include <string>
#include <vector>

class Vis4GSArguments
{
public:
  Vis4GSArguments(std::string command, std::string summary);

  /// An option taking a value: `--name=VALUE`. @p type names the value in --help ("N", "FILE").
  void AddOption(const std::string& name,
    const std::string& type,
    const std::string& defaultValue,
    const std::string& help);
  /// A boolean: `--name` sets it, `--no-name` clears it.
  void AddFlag(const std::string& name, bool defaultValue, const std::string& help);
  /// A positional argument, in order.
  void AddPositional(const std::string& name, const std::string& help, bool required = true);

  enum class Result
  {
    Ok,
    Help,
    Error
  };
  /// Parses @p args (without the program and command names); messages go to @p err.
  Result Parse(const std::vector<std::string>& args, std::ostream& err);
  void PrintHelp(std::ostream& os) const;

  std::string Get(const std::string& name) const;
  bool GetFlag(const std::string& name) const;
  int GetInt(const std::string& name) const;
  double GetDouble(const std::string& name) const;
  /// Comma-separated numbers, e.g. --resolution=1280,720.
  std::vector<double> GetNumbers(const std::string& name) const;
  /// True when the user gave the option (as opposed to its default).
  bool IsSet(const std::string& name) const;
  std::string GetPositional(const std::string& name) const;

private:
  struct Option
  {
    std::string Name, Type, Default, Help;
    bool IsFlag = false;
  };
  struct Positional
  {
    std::string Name, Help;
    bool Required = true;
  };
  const Option* Find(const std::string& name) const;

  std::string Command, Summary;
  std::vector<Option> Options;
  std::vector<Positional> Positionals;
  std::map<std::string, std::string> Values;
  std::map<std::string, std::string> PositionalValues;
};

#endif
