// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSPipeline.h"

#include "vtkAlgorithm.h"
#include "vtkCommand.h"

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
      *messages += (messages->empty() ? "" : "; ") + std::string(text ? text : "error");
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
