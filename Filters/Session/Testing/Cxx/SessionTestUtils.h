// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SessionTestUtils.h
 * @brief What the session's tests share: the errors an algorithm reports, collected.
 */
#ifndef SessionTestUtils_h
#define SessionTestUtils_h

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkNew.h"

#include <string>

namespace sessiontest
{
/// Collects the errors @p algorithm reports (and keeps its executive's "returned failure" off
/// the output window) while it lives.
struct ErrorText
{
  std::string Text;
  vtkNew<vtkCallbackCommand> Command;
  vtkNew<vtkCallbackCommand> Quiet;
  explicit ErrorText(vtkAlgorithm* algorithm)
  {
    this->Command->SetClientData(this);
    this->Command->SetCallback([](vtkObject*, unsigned long, void* client, void* call)
      { static_cast<ErrorText*>(client)->Text += static_cast<const char*>(call); });
    algorithm->AddObserver(vtkCommand::ErrorEvent, this->Command);
    algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, this->Quiet);
  }
};
}

#endif
