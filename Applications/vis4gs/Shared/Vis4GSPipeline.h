// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSPipeline.h
 * @brief Running the VTK readers and filters from the commands: VTK algorithms report errors
 * (ErrorEvent) rather than throw, so the commands collect the messages to throw or show them.
 */
#ifndef Vis4GSPipeline_h
#define Vis4GSPipeline_h

#include "vtkCallbackCommand.h"
#include "vtkNew.h"

#include <string>

class vtkAlgorithm;

/// Collects the error messages @p algorithm reports while this lives, cleaned of VTK's
/// decorations (vtkGaussianOutputWindow::CleanMessage). An algorithm observed for its errors
/// does not print them: the caller shows or throws them.
class Vis4GSErrorCollector
{
public:
  explicit Vis4GSErrorCollector(vtkAlgorithm* algorithm);
  ~Vis4GSErrorCollector();
  Vis4GSErrorCollector(const Vis4GSErrorCollector&) = delete;
  Vis4GSErrorCollector& operator=(const Vis4GSErrorCollector&) = delete;
  /// The messages so far, separated by "; " (empty: none).
  const std::string& GetMessages() const { return this->Messages; }

private:
  vtkAlgorithm* Algorithm;
  vtkNew<vtkCallbackCommand> Callback;
  unsigned long Tag = 0;
  std::string Messages;
};

/// Updates output @p port of @p algorithm; returns the errors it reported (empty: success).
std::string Vis4GSUpdate(vtkAlgorithm* algorithm, int port = 0);

/// Updates @p algorithm's information (a reader opens its file: header, what it holds); returns
/// the errors it reported (empty: success).
std::string Vis4GSUpdateInformation(vtkAlgorithm* algorithm);

#endif
