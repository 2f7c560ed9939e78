/*=========================================================================

  Program:   Vis4GS
  Module:    IOSceneTestUtils.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
// Helpers for the IOScene tests: failure counting, a temporary folder, and an observer that
// captures (and so silences) the errors and warnings a test provokes on purpose.
#ifndef IOSceneTestUtils_h
#define IOSceneTestUtils_h

#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkNew.h"

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <unistd.h>

namespace iotest
{
inline int& Failures()
{
  static int failures = 0;
  return failures;
}

inline void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++Failures();
  }
}

class TempDir
{
public:
  TempDir()
  {
    char buf[] = "/tmp/vis4gs-ioscene-XXXXXX";
    this->Path = ::mkdtemp(buf) ? buf : "/tmp";
  }
  ~TempDir() { std::system(("rm -rf '" + this->Path + "'").c_str()); }
  std::string operator/(const std::string& name) const { return this->Path + "/" + name; }
  std::string Path;
};

/// Captures ErrorEvent and WarningEvent messages of an algorithm and its executive.
class MessageObserver : public vtkCommand
{
public:
  static MessageObserver* New() { return new MessageObserver; }
  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    const std::string msg = data ? static_cast<const char*>(data) : "";
    (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings).push_back(msg);
  }
  void Watch(vtkAlgorithm* algorithm)
  {
    algorithm->AddObserver(vtkCommand::ErrorEvent, this);
    algorithm->AddObserver(vtkCommand::WarningEvent, this);
    algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, this);
  }
  bool ErrorContains(const std::string& fragment) const
  {
    for (const auto& e : this->Errors)
    {
      if (e.find(fragment) != std::string::npos)
      {
        return true;
      }
    }
    return false;
  }
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;
};
}

#endif
