// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSStagingFolder.h"

#include <algorithm>
#include <stdexcept>
#include <system_error>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;

//------------------------------------------------------------------------------
Vis4GSStagingFolder::Vis4GSStagingFolder(const fs::path& output, const std::string& command)
  : Output(output)
  , Path(output / (".vis4gs-" + command + "-partial-" + std::to_string(::getpid())))
{
  std::error_code ec;
  fs::create_directories(this->Path, ec);
  if (ec)
  {
    throw std::runtime_error(output.string() + ": cannot write the outputs there (" + ec.message() +
      ", creating " + this->Path.filename().string() + ")");
  }
}

//------------------------------------------------------------------------------
Vis4GSStagingFolder::~Vis4GSStagingFolder()
{
  std::error_code ec;
  fs::remove_all(this->Path, ec);
}

//------------------------------------------------------------------------------
namespace
{
// Moves the entries of @p from into @p to; a folder that exists in both (analyze's images/ of
// an earlier run) is merged file by file. report.html goes last.
void MoveInto(const fs::path& from, const fs::path& to)
{
  std::vector<fs::path> entries;
  for (const auto& entry : fs::directory_iterator(from))
  {
    entries.push_back(entry.path());
  }
  std::stable_partition(entries.begin(),
    entries.end(),
    [](const fs::path& p) { return p.filename() != "report.html"; });
  for (const fs::path& entry : entries)
  {
    const fs::path target = to / entry.filename();
    std::error_code ec;
    if (fs::is_directory(entry) && fs::is_directory(target, ec))
    {
      MoveInto(entry, target);
      continue;
    }
    fs::rename(entry, target, ec);
    if (ec)
    {
      throw std::runtime_error(target.string() + ": cannot be moved into place: " + ec.message());
    }
  }
}
}

//------------------------------------------------------------------------------
void Vis4GSStagingFolder::Commit()
{
  MoveInto(this->Path, this->Output);
}
