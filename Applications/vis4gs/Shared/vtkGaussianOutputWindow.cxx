// SPDX-License-Identifier: BSD-3-Clause
#include "vtkGaussianOutputWindow.h"

#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"

#include <iostream>
#include <regex>
#include <sstream>

vtkStandardNewMacro(vtkGaussianOutputWindow);

//------------------------------------------------------------------------------
vtkGaussianOutputWindow::vtkGaussianOutputWindow() = default;

//------------------------------------------------------------------------------
vtkGaussianOutputWindow::~vtkGaussianOutputWindow() = default;

//------------------------------------------------------------------------------
void vtkGaussianOutputWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Prefix: " << this->Prefix << "\n";
  os << indent << "Stream: " << (this->Stream ? "set" : "std::cerr") << "\n";
  os << indent << "NumberOfErrors: " << this->Errors << "\n";
  os << indent << "NumberOfWarnings: " << this->Warnings << "\n";
  os << indent << "NumberOfRepeatedWarnings: " << this->Repeated << "\n";
  os << indent << "NumberOfDroppedFailures: " << this->DroppedFailures << "\n";
  os << indent << "WarningsSeen: " << this->WarningsSeen.size() << "\n";
}

//------------------------------------------------------------------------------
void vtkGaussianOutputWindow::Install(const std::string& prefix)
{
  vtkNew<vtkGaussianOutputWindow> window;
  window->SetPrefix(prefix);
  vtkOutputWindow::SetInstance(window);
  // vtkOutputWindowDisplayErrorText logs each message through vtkLogger before it reaches the
  // output window: with loguru's standard-error sink on, every message would come twice, the
  // second time with a time stamp, a thread id and colour escapes.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

//------------------------------------------------------------------------------
std::string vtkGaussianOutputWindow::CleanMessage(const std::string& text)
{
  static const std::regex escape("\x1b\\[[0-9;]*[A-Za-z]");
  static const std::regex header("^(ERROR|Warning|Generic Warning|Debug): In .*, line [0-9]+$");
  static const std::regex objectPrefix("^(\\w+ )?\\((0x[0-9a-fA-F]+|nullptr)\\): ");
  static const std::regex address("(\\w+) ?\\(0x[0-9a-fA-F]+\\)");
  const std::string plain = std::regex_replace(text, escape, "");
  std::istringstream lines(plain);
  std::string line;
  std::string out;
  while (std::getline(lines, line))
  {
    if (std::regex_match(line, header))
    {
      continue;
    }
    line = std::regex_replace(line, objectPrefix, "", std::regex_constants::format_first_only);
    line = std::regex_replace(line, address, "$1");
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos)
    {
      continue;
    }
    const auto last = line.find_last_not_of(" \t\r");
    out += (out.empty() ? "" : "\n") + line.substr(first, last - first + 1);
  }
  return out;
}

//------------------------------------------------------------------------------
void vtkGaussianOutputWindow::Print(const char* kind, const std::string& message)
{
  std::ostream& os = this->Stream ? *this->Stream : std::cerr;
  os << this->Prefix << ": " << kind << message << "\n" << std::flush;
}

//------------------------------------------------------------------------------
void vtkGaussianOutputWindow::DisplayText(const char* text)
{
  const std::string message = CleanMessage(text ? text : "");
  if (!message.empty())
  {
    this->Print("", message);
  }
}

//------------------------------------------------------------------------------
void vtkGaussianOutputWindow::DisplayErrorText(const char* text)
{
  const std::string raw = text ? text : "";
  if (raw.find("returned failure for request") != std::string::npos)
  {
    // The executive's dump of the request (a vtkInformation printed whole) says nothing the
    // failing algorithm did not: our readers and filters report their own error (to this
    // window, or to the command's Vis4GSErrorCollector, which prints it after this).
    ++this->DroppedFailures;
    return;
  }
  const std::string message = CleanMessage(raw);
  if (!message.empty())
  {
    this->Print("error: ", message);
    ++this->Errors;
  }
}

//------------------------------------------------------------------------------
void vtkGaussianOutputWindow::Warn(const char* text)
{
  const std::string message = CleanMessage(text ? text : "");
  if (message.empty())
  {
    return;
  }
  if (!this->WarningsSeen.insert(message).second)
  {
    ++this->Repeated;
    return;
  }
  this->Print("warning: ", message);
  ++this->Warnings;
}

//------------------------------------------------------------------------------
void vtkGaussianOutputWindow::DisplayWarningText(const char* text)
{
  this->Warn(text);
}

//------------------------------------------------------------------------------
void vtkGaussianOutputWindow::DisplayGenericWarningText(const char* text)
{
  this->Warn(text);
}

//------------------------------------------------------------------------------
void vtkGaussianOutputWindow::DisplayDebugText(const char*)
{
  // Debug output is for developers, who switch it on per object and read it in a debugger.
}
