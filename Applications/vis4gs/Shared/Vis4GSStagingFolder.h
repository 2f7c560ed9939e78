// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSStagingFolder.h
 * @brief The outputs of a command that writes a folder (analyze, demo) are written to a hidden
 * folder inside it and moved into place only when all of them are written, so that a failure (a
 * full disk, a read-only folder, a process killed under MPI) leaves no partial scores.csv,
 * scores.ply or report.html, and the files of an earlier run stay as they were.
 */
#ifndef Vis4GSStagingFolder_h
#define Vis4GSStagingFolder_h

#include <filesystem>
#include <string>

class Vis4GSStagingFolder
{
public:
  /// Creates @p output (when missing) and "<output>/.vis4gs-<command>-partial-<pid>" in it;
  /// throws std::runtime_error naming the folder and the problem.
  Vis4GSStagingFolder(const std::filesystem::path& output, const std::string& command);
  /// Removes the hidden folder and what is left in it (everything, unless committed).
  ~Vis4GSStagingFolder();
  Vis4GSStagingFolder(const Vis4GSStagingFolder&) = delete;
  Vis4GSStagingFolder& operator=(const Vis4GSStagingFolder&) = delete;

  /// The hidden folder the outputs are written to.
  const std::filesystem::path& Get() const { return this->Path; }

  /// Renames every file into the output folder, report.html last (it marks a complete run); a
  /// folder already there (images/) is merged file by file. Renames within one file system
  /// need no space; throws naming the file on failure.
  void Commit();

private:
  std::filesystem::path Output;
  std::filesystem::path Path;
};

#endif
