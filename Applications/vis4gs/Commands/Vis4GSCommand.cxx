// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSCommand.h"

#include <algorithm>

namespace
{
std::vector<Vis4GSCommand>& Registry()
{
  // Function-local so registration from other translation units' statics is order-safe.
  static std::vector<Vis4GSCommand> commands;
  return commands;
}

int Rank(const std::string& name)
{
  static const char* order[] = { "view", "analyze", "train", "render", "demo" };
  for (int i = 0; i < 5; ++i)
  {
    if (name == order[i])
    {
      return i;
    }
  }
  return 5;
}
}

//------------------------------------------------------------------------------
bool Vis4GSRegisterCommand(const Vis4GSCommand& command)
{
  Registry().push_back(command);
  return true;
}

//------------------------------------------------------------------------------
std::vector<Vis4GSCommand> Vis4GSRegisteredCommands()
{
  std::vector<Vis4GSCommand> commands = Registry();
  std::sort(commands.begin(),
    commands.end(),
    [](const Vis4GSCommand& a, const Vis4GSCommand& b)
    {
      const int ra = Rank(a.Name), rb = Rank(b.Name);
      return ra != rb ? ra < rb : std::string(a.Name) < b.Name;
    });
  return commands;
}

//------------------------------------------------------------------------------
const Vis4GSCommand* Vis4GSFindCommand(const std::string& name)
{
  for (const Vis4GSCommand& command : Registry())
  {
    if (name == command.Name)
    {
      return &command;
    }
  }
  return nullptr;
}

//------------------------------------------------------------------------------
void Vis4GSDefineArguments(const Vis4GSCommand& command, Vis4GSArguments& args)
{
  args.AddOption("threads", "N", "0", "Number of threads; 0 uses every core.");
  args.AddFlag("verbose", false, "Print details of each step.");
  command.Define(args);
}

//------------------------------------------------------------------------------
std::string Vis4GSHtml(const std::string& text)
{
  std::string o;
  for (char c : text)
  {
    o += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  }
  return o;
}
