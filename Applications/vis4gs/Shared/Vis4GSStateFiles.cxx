// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSStateFiles.h"

#include "vtkGaussianSession.h" // IsTrainingLogFile: a log by its content

#include <algorithm>
#include <cctype>
#include <filesystem>

bool Vis4GSIsLogPath(const std::string& path)
{
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(),
    extension.end(),
    extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  // By content too: a live log is LOG.h5.tmp while its trainer writes it (issue 32).
  return extension == ".h5" || extension == ".hdf5" ||
    vtkGaussianSession::IsTrainingLogFile(path.c_str());
}
