// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSArguments.h"

#include <iomanip>
#include <sstream>
#include <stdexcept>

//------------------------------------------------------------------------------
Vis4GSArguments::Vis4GSArguments(std::string command, std::string summary)
  : Command(std::move(command))
  , Summary(std::move(summary))
{
  this->AddFlag("help", false, "Print this help and exit.");
}

//------------------------------------------------------------------------------
void Vis4GSArguments::AddOption(const std::string& name,
  const std::string& type,
  const std::string& defaultValue,
  const std::string& help)
{
  this->Options.push_back({ name, type, defaultValue, help, false });
}

//------------------------------------------------------------------------------
void Vis4GSArguments::AddFlag(const std::string& name, bool defaultValue, const std::string& help)
{
  this->Options.push_back({ name, "", defaultValue ? "true" : "false", help, true });
}

//------------------------------------------------------------------------------
void Vis4GSArguments::AddPositional(const std::string& name, const std::string& help, bool required)
{
  this->Positionals.push_back({ name, help, required });
}

//------------------------------------------------------------------------------
const Vis4GSArguments::Option* Vis4GSArguments::Find(const std::string& name) const
{
  for (const auto& o : this->Options)
  {
    if (o.Name == name)
    {
      return &o;
    }
  }
  return nullptr;
}

//------------------------------------------------------------------------------
Vis4GSArguments::Result Vis4GSArguments::Parse(const std::vector<std::string>& args,
  std::ostream& err)
{
  std::size_t positional = 0;
  for (const std::string& arg : args)
  {
    if (arg.rfind("--", 0) == 0)
    {
      const std::size_t eq = arg.find('=');
      std::string name = arg.substr(2, eq == std::string::npos ? std::string::npos : eq - 2);
      const Option* option = this->Find(name);
      if (!option && name.rfind("no-", 0) == 0)
      {
        const Option* negated = this->Find(name.substr(3));
        if (negated && negated->IsFlag && eq == std::string::npos)
        {
          this->Values[negated->Name] = "false";
          continue;
        }
      }
      if (!option)
      {
        err << "vis4gs " << this->Command << ": error: unknown option '--" << name
            << "' (see vis4gs " << this->Command << " --help)\n";
        return Result::Error;
      }
      if (option->IsFlag)
      {
        if (eq != std::string::npos)
        {
          err << "vis4gs " << this->Command << ": error: '--" << name << "' takes no value; use --"
              << name << " or --no-" << name << "\n";
          return Result::Error;
        }
        this->Values[name] = "true";
      }
      else
      {
        if (eq == std::string::npos)
        {
          err << "vis4gs " << this->Command << ": error: '--" << name << "' needs a value: --"
              << name << "=" << option->Type << "\n";
          return Result::Error;
        }
        this->Values[name] = arg.substr(eq + 1);
      }
    }
    else
    {
      if (positional >= this->Positionals.size())
      {
        err << "vis4gs " << this->Command << ": error: unexpected argument '" << arg << "'\n";
        return Result::Error;
      }
      this->PositionalValues[this->Positionals[positional++].Name] = arg;
    }
  }
  if (this->GetFlag("help"))
  {
    return Result::Help;
  }
  for (std::size_t i = positional; i < this->Positionals.size(); ++i)
  {
    if (this->Positionals[i].Required)
    {
      err << "vis4gs " << this->Command << ": error: missing " << this->Positionals[i].Name
          << " (see vis4gs " << this->Command << " --help)\n";
      return Result::Error;
    }
  }
  return Result::Ok;
}

//------------------------------------------------------------------------------
void Vis4GSArguments::PrintHelp(std::ostream& os) const
{
  os << "Usage: vis4gs " << this->Command;
  for (const auto& p : this->Positionals)
  {
    os << (p.Required ? " " : " [") << p.Name << (p.Required ? "" : "]");
  }
  os << " [options]\n\n" << this->Summary << "\n";
  if (!this->Positionals.empty())
  {
    os << "\nArguments:\n";
    for (const auto& p : this->Positionals)
    {
      os << "  " << std::left << std::setw(28) << p.Name << p.Help << "\n";
    }
  }
  os << "\nOptions:\n";
  for (const auto& o : this->Options)
  {
    const std::string head =
      o.IsFlag ? "--" + o.Name + ", --no-" + o.Name : "--" + o.Name + "=" + o.Type;
    os << "  " << std::left << std::setw(28) << head;
    if (head.size() >= 28)
    {
      // A long flag pair gets its own line, so that it never runs into its description.
      os << "\n" << std::string(30, ' ');
    }
    os << o.Help;
    if (!o.IsFlag && !o.Default.empty())
    {
      os << " (default: " << o.Default << ")";
    }
    else if (o.IsFlag && o.Name != "help")
    {
      os << " (default: " << (o.Default == "true" ? "on" : "off") << ")";
    }
    os << "\n";
  }
}

//------------------------------------------------------------------------------
bool Vis4GSArguments::IsSet(const std::string& name) const
{
  return this->Values.count(name) > 0;
}

//------------------------------------------------------------------------------
std::string Vis4GSArguments::Get(const std::string& name) const
{
  auto it = this->Values.find(name);
  if (it != this->Values.end())
  {
    return it->second;
  }
  const Option* option = this->Find(name);
  if (!option)
  {
    throw std::logic_error("vis4gs: option --" + name + " is not declared");
  }
  return option->Default;
}

//------------------------------------------------------------------------------
bool Vis4GSArguments::GetFlag(const std::string& name) const
{
  return this->Get(name) == "true";
}

//------------------------------------------------------------------------------
int Vis4GSArguments::GetInt(const std::string& name) const
{
  const std::string value = this->Get(name);
  std::size_t used = 0;
  int result = 0;
  try
  {
    result = std::stoi(value, &used);
  }
  catch (const std::exception&)
  {
    used = 0;
  }
  if (used == 0 || used != value.size())
  {
    throw std::runtime_error("--" + name + "=" + value + ": expected an integer");
  }
  return result;
}

//------------------------------------------------------------------------------
double Vis4GSArguments::GetDouble(const std::string& name) const
{
  const std::string value = this->Get(name);
  std::size_t used = 0;
  double result = 0;
  try
  {
    result = std::stod(value, &used);
  }
  catch (const std::exception&)
  {
    used = 0;
  }
  if (used == 0 || used != value.size())
  {
    throw std::runtime_error("--" + name + "=" + value + ": expected a number");
  }
  return result;
}

//------------------------------------------------------------------------------
std::vector<double> Vis4GSArguments::GetNumbers(const std::string& name) const
{
  std::vector<double> numbers;
  std::stringstream ss(this->Get(name));
  std::string item;
  while (std::getline(ss, item, ','))
  {
    std::size_t used = 0;
    try
    {
      numbers.push_back(std::stod(item, &used));
    }
    catch (const std::exception&)
    {
      used = 0;
    }
    if (used == 0 || used != item.size())
    {
      throw std::runtime_error(
        "--" + name + "=" + this->Get(name) + ": expected comma-separated numbers");
    }
  }
  return numbers;
}

//------------------------------------------------------------------------------
std::string Vis4GSArguments::GetPositional(const std::string& name) const
{
  auto it = this->PositionalValues.find(name);
  return it == this->PositionalValues.end() ? std::string() : it->second;
}
