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
