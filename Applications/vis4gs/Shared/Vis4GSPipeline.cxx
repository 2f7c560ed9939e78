// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSPipeline.h"

#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkGaussianOutputWindow.h"

//------------------------------------------------------------------------------
Vis4GSErrorCollector::Vis4GSErrorCollector(vtkAlgorithm* algorithm)
  : Algorithm(algorithm)
{
  this->Callback->SetClientData(&this->Messages);
  this->Callback->SetCallback(
    [](vtkObject*, unsigned long, void* client, void* callData)
    {
      auto* messages = static_cast<std::string*>(client);
      const char* text = static_cast<const char*>(callData);
      // VTK hands the message as its output window would print it: "ERROR: In file, line
      // N\nvtkClass (0x...): problem"; people are shown the problem.
      std::string message = vtkGaussianOutputWindow::CleanMessage(text ? text : "");
      *messages += (messages->empty() ? "" : "; ") + (message.empty() ? "error" : message);
    });
  this->Tag = algorithm->AddObserver(vtkCommand::ErrorEvent, this->Callback);
}

//------------------------------------------------------------------------------
Vis4GSErrorCollector::~Vis4GSErrorCollector()
{
  this->Algorithm->RemoveObserver(this->Tag);
}

//------------------------------------------------------------------------------
std::string Vis4GSUpdate(vtkAlgorithm* algorithm, int port)
{
  Vis4GSErrorCollector errors(algorithm);
  algorithm->Update(port);
  return errors.GetMessages();
}

//------------------------------------------------------------------------------
std::string Vis4GSUpdateInformation(vtkAlgorithm* algorithm)
{
  Vis4GSErrorCollector errors(algorithm);
  algorithm->UpdateInformation();
  return errors.GetMessages();
}
