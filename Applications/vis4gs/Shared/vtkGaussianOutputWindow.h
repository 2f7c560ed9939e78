// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkGaussianOutputWindow
 * @brief VTK's output window for people: the errors and warnings of VTK's readers and filters
 * in the program's own form, "vis4gs analyze: error: FILE: problem", without VTK's decorations.
 *
 * VTK prints an error as "ERROR: In /path/file.cxx, line N\nvtkClass (0x55...): message", and
 * vtkLogger (loguru) prints it once more with a time stamp, a thread id and colour escapes
 * even when standard error is a file. Install() makes one of these the output window and turns
 * vtkLogger's standard-error output off, so that each message is printed once, cleaned
 * (CleanMessage: no "In file, line", no object address, no escape), after the prefix and
 * "error: " or "warning: ". A warning seen before is not printed again; the pipeline's
 * "Algorithm X returned failure for request: vtkInformation ..." dump is dropped (the failing
 * algorithm reports its own error, to this window or to the caller's Vis4GSErrorCollector,
 * which may print it after the dump). Debug text is dropped. The vis4gs program installs one at
 * start for every command, the view included.
 *
 * Defaults: Prefix "vis4gs", the stream std::cerr.
 */
#ifndef vtkGaussianOutputWindow_h
#define vtkGaussianOutputWindow_h

#include "vtkOutputWindow.h"

#include <ostream>
#include <set>
#include <string>

class vtkGaussianOutputWindow : public vtkOutputWindow
{
public:
  static vtkGaussianOutputWindow* New();
  vtkTypeMacro(vtkGaussianOutputWindow, vtkOutputWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Makes a new one, with @p prefix ("vis4gs analyze"), VTK's output window, and turns
  /// vtkLogger's standard-error output off (it would print every message a second time).
  static void Install(const std::string& prefix);

  /// What comes before "error: " and "warning: " ("vis4gs analyze").
  void SetPrefix(const std::string& prefix) { this->Prefix = prefix; }
  const std::string& GetPrefix() const { return this->Prefix; }

  /// Where the messages go (not owned; nullptr: std::cerr). Tests give a string stream.
  void SetStream(std::ostream* stream) { this->Stream = stream; }

  /// Errors and warnings printed, and warnings not printed again (seen before).
  int GetNumberOfErrors() const { return this->Errors; }
  int GetNumberOfWarnings() const { return this->Warnings; }
  int GetNumberOfRepeatedWarnings() const { return this->Repeated; }
  /// The executive's "Algorithm X returned failure" dumps dropped.
  int GetNumberOfDroppedFailures() const { return this->DroppedFailures; }

  /**
   * @p text without VTK's decorations: the "ERROR: In file, line N" (or "Warning: In", "Generic
   * Warning: In", "Debug: In") header, every "vtkClass (0x...): " and "(nullptr): " prefix, an
   * address after a class name ("vtkGaussianSceneReader(0x55...)" becomes the name), terminal
   * escape sequences, and the blank lines and spaces around it. The error collectors of the
   * commands and the window (Vis4GSErrorCollector) use it too.
   */
  static std::string CleanMessage(const std::string& text);

  void DisplayText(const char* text) override;
  void DisplayErrorText(const char* text) override;
  void DisplayWarningText(const char* text) override;
  void DisplayGenericWarningText(const char* text) override;
  void DisplayDebugText(const char* text) override;

protected:
  vtkGaussianOutputWindow();
  ~vtkGaussianOutputWindow() override;

private:
  vtkGaussianOutputWindow(const vtkGaussianOutputWindow&) = delete;
  void operator=(const vtkGaussianOutputWindow&) = delete;

  void Print(const char* kind, const std::string& message);
  void Warn(const char* text);

  std::string Prefix = "vis4gs";
  std::ostream* Stream = nullptr;
  std::set<std::string> WarningsSeen;
  int Errors = 0;
  int Warnings = 0;
  int Repeated = 0;
  int DroppedFailures = 0;
};

#endif
