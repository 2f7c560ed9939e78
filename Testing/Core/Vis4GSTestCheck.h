// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSTestCheck.h
 * @brief The checks of the VTK modules' C++ tests (the Core tests use GoogleTest): every check
 * runs and reports, and the test's exit status says whether any failed.
 *
 *     namespace { vis4gs::testing::CheckCounter Check; }
 *     ...
 *     Check(a == b, "the ids survive the round trip");
 *     return Check.ExitCode();
 */
#ifndef vis4gs_TestCheck_h
#define vis4gs_TestCheck_h

#include <cstdlib>
#include <iostream>

namespace vis4gs
{
namespace testing
{

class CheckCounter
{
public:
  /// Prints "ERROR: check failed: @p what" to stderr when @p ok is false, and counts it.
  void operator()(bool ok, const char* what)
  {
    if (!ok)
    {
      std::cerr << "ERROR: check failed: " << what << "\n";
      ++this->Failures;
    }
  }
  int GetFailures() const { return this->Failures; }
  int ExitCode() const { return this->Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE; }

private:
  int Failures = 0;
};

} // namespace testing
} // namespace vis4gs

#endif
