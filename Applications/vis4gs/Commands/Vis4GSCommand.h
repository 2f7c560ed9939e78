// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSCommand.h
 * @brief The registry of vis4gs subcommands. Each subcommand lives in its own
 * vis4gs<Name>Command.cxx and registers itself with VIS4GS_REGISTER_COMMAND, so adding one
 * touches no other file but the CMakeLists' source list.
 */
#ifndef Vis4GSCommand_h
#define Vis4GSCommand_h

#include "Vis4GSArguments.h"

#include <string>
#include <vector>

struct Vis4GSCommand
{
  /// Subcommand name, as typed: `vis4gs <Name>`.
  const char* Name;
  /// One line for `vis4gs --help`.
  const char* Summary;
  /// Declares the command's options and positionals (common ones are already declared).
  void (*Define)(Vis4GSArguments& args);
  /// Runs the command; returns the process exit code. Exceptions become "vis4gs <cmd>: msg".
  int (*Run)(const Vis4GSArguments& args);
};

/// Adds @p command to the registry; returns true so it can initialise a static.
bool Vis4GSRegisterCommand(const Vis4GSCommand& command);

/// Registered commands in the order of DESIGN §5 (then any other, by name).
std::vector<Vis4GSCommand> Vis4GSRegisteredCommands();

/// The registered command named @p name, or nullptr.
const Vis4GSCommand* Vis4GSFindCommand(const std::string& name);

/// Declares @p command's arguments: the options every command takes (--threads, --verbose,
/// --help) and the command's own.
void Vis4GSDefineArguments(const Vis4GSCommand& command, Vis4GSArguments& args);

/// @p text with <, > and & escaped for an HTML page (the reports of analyze and demo).
std::string Vis4GSHtml(const std::string& text);

#define VIS4GS_REGISTER_COMMAND(name, summary, define, run)                                        \
  namespace                                                                                        \
  {                                                                                                \
  const bool vis4gsCommandRegistered = Vis4GSRegisterCommand({ name, summary, define, run });      \
  }

#endif
