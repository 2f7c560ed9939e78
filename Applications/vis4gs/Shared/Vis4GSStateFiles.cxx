// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSStateFiles.h"

#include "vtkGaussianSession.h" // IsTrainingLogPath: the session's rule

bool Vis4GSIsLogPath(const std::string& path)
{
  // By content too: a live log is LOG.h5.tmp while its trainer writes it (issue 32).
  return vtkGaussianSession::IsTrainingLogPath(path.c_str());
}
