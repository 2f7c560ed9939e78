// Shared helpers of the Filters/Genealogy tests (header-only, test code).
#ifndef GenealogyTestHelpers_h
#define GenealogyTestHelpers_h

#include "vtkCommand.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include "TrainingLogTypes.h"

#include <iostream>
#include <string>

#define GT_CHECK(cond)                                                                             \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #cond << std::endl;           \
      ++failures;                                                                                  \
    }                                                                                              \
  } while (false)

/// Collects error and warning messages instead of printing them.
class GenealogyMessageObserver : public vtkCommand
{
public:
  static GenealogyMessageObserver* New() { return new GenealogyMessageObserver; }
  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    const std::string text = data ? static_cast<const char*>(data) : "";
    (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings) += text + "\n";
  }
  std::string Errors;
  std::string Warnings;
};

/// Events table with the reader's column names.
inline vtkSmartPointer<vtkTable> EventsTable(const vis4gs::EventTable& e)
{
  auto table = vtkSmartPointer<vtkTable>::New();
  vtkNew<vtkIntArray> it;
  vtkNew<vtkUnsignedCharArray> kind;
  vtkNew<vtkIdTypeArray> parent, child;
  it->SetName("Iteration");
  kind->SetName("Kind");
  parent->SetName("Parent");
  child->SetName("Child");
  const vtkIdType n = static_cast<vtkIdType>(e.Size());
  it->SetNumberOfTuples(n);
  kind->SetNumberOfTuples(n);
  parent->SetNumberOfTuples(n);
  child->SetNumberOfTuples(n);
  for (vtkIdType r = 0; r < n; ++r)
  {
    it->SetValue(r, e.Iteration[r]);
    kind->SetValue(r, e.Kind[r]);
    parent->SetValue(r, e.Parent[r]);
    child->SetValue(r, e.Child[r]);
  }
  table->AddColumn(it);
  table->AddColumn(kind);
  table->AddColumn(parent);
  table->AddColumn(child);
  return table;
}

inline void AddEvent(vis4gs::EventTable& t,
  std::int32_t it,
  int kind,
  std::int64_t parent,
  std::int64_t child)
{
  t.Iteration.push_back(it);
  t.Kind.push_back(static_cast<std::uint8_t>(kind));
  t.Parent.push_back(parent);
  t.Child.push_back(child);
}

/// The hand-computed log of Core/Genealogy/Testing/TestGenealogy.cxx (N0 = 2, last 1000).
inline vis4gs::EventTable HandEvents()
{
  vis4gs::EventTable t;
  AddEvent(t, 100, 1, 0, 2);
  AddEvent(t, 200, 2, 0, 3);
  AddEvent(t, 200, 2, 0, 4);
  AddEvent(t, 300, 1, 3, 5);
  AddEvent(t, 400, 3, 4, -1);
  AddEvent(t, 500, 3, 1, -1);
  AddEvent(t, 600, 2, 5, 6);
  AddEvent(t, 600, 2, 5, 7);
  return t;
}

#endif
