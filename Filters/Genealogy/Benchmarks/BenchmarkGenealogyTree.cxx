// Benchmark: the densification tree of a SYNTHETIC Bicycle-sized log (4.89M final Gaussians,
// ~10M nodes) through vtkGaussianGenealogyTreeFilter: Core genealogy, vtkTree construction
// (fast path) and, in the same run, the naive construction with vtkMutableDirectedGraph
// AddChild one vertex at a time; then level-of-detail filter index and queries.
// The fast path is run twice: valid by construction (default) and through vtkTree's own
// validation (ValidateStructure). Whole-filter wall and process CPU times (all threads) are
// printed with the peak RSS of each run, then the compact output (CompactTree) with the RSS
// the tree keeps after the filter's transients are gone, beside the plain vtkTree's.
// Usage: BenchmarkGenealogyTree [--total=N] [--final=N] [--no-naive] [--no-validate]
//   [--no-compact]
#include "vtkGaussianGenealogyTreeFilter.h"
#include "vtkGaussianTreeLevelOfDetail.h"

#include "SyntheticEventLog.h"

#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkTable.h"
#include "vtkTree.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <string>

namespace
{
double StatusMiB(const char* key)
{
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
  {
    if (line.rfind(key, 0) == 0)
    {
      return std::atof(line.c_str() + std::strlen(key)) / 1024.0;
    }
  }
  return -1.0;
}
void ResetPeak()
{
  std::ofstream f("/proc/self/clear_refs");
  f << "5";
}
long long Arg(int argc, char* argv[], const char* name, long long fallback)
{
  const std::size_t len = std::strlen(name);
  for (int i = 1; i < argc; ++i)
  {
    if (std::strncmp(argv[i], name, len) == 0 && argv[i][len] == '=')
    {
      return std::atoll(argv[i] + len + 1);
    }
  }
  return fallback;
}
bool Flag(int argc, char* argv[], const char* name)
{
  for (int i = 1; i < argc; ++i)
  {
    if (std::strcmp(argv[i], name) == 0)
    {
      return true;
    }
  }
  return false;
}
double ProcessCpu()
{
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
} // namespace

int main(int argc, char* argv[])
{
  vis4gs::SyntheticLogParameters prm;
  prm.TotalGaussians = Arg(argc, argv, "--total", prm.TotalGaussians);
  prm.FinalGaussians = Arg(argc, argv, "--final", prm.FinalGaussians);
  vtkNew<vtkTable> table;
  vtkIdType initial = 0;
  int last = 0;
  {
    const auto log = vis4gs::GenerateSyntheticEventLog(prm);
    initial = log.InitialGaussians;
    last = log.LastIteration;
    const vtkIdType n = static_cast<vtkIdType>(log.Events.Size());
    vtkNew<vtkIntArray> it;
    vtkNew<vtkUnsignedCharArray> kind;
    vtkNew<vtkIdTypeArray> parent, child;
    it->SetName("Iteration");
    kind->SetName("Kind");
    parent->SetName("Parent");
    child->SetName("Child");
    it->SetNumberOfTuples(n);
    kind->SetNumberOfTuples(n);
    parent->SetNumberOfTuples(n);
    child->SetNumberOfTuples(n);
    std::copy(log.Events.Iteration.begin(), log.Events.Iteration.end(), it->GetPointer(0));
    std::copy(log.Events.Kind.begin(), log.Events.Kind.end(), kind->GetPointer(0));
    std::copy(log.Events.Parent.begin(), log.Events.Parent.end(), parent->GetPointer(0));
    std::copy(log.Events.Child.begin(), log.Events.Child.end(), child->GetPointer(0));
    table->AddColumn(it);
    table->AddColumn(kind);
    table->AddColumn(parent);
    table->AddColumn(child);
    std::printf("SYNTHETIC log: %lld events, %lld final Gaussians\n",
      static_cast<long long>(n),
      static_cast<long long>(log.FinalGaussians));
  }

  // Mode 0: fast path, valid by construction; 1: fast path through vtkTree's validation;
  // 2: naive AddChild per vertex; 3: compact output (vtkGaussianCompactTree).
  const char* names[4] = { "fast, valid by construction",
    "fast, vtkTree validation",
    "naive AddChild per vertex",
    "fast, compact tree (CompactTree)" };
  for (int mode = 0; mode < 4; ++mode)
  {
    if ((mode == 1 && Flag(argc, argv, "--no-validate")) ||
      (mode == 2 && Flag(argc, argv, "--no-naive")) ||
      (mode == 3 && Flag(argc, argv, "--no-compact")))
    {
      continue;
    }
    ResetPeak();
    const double before = StatusMiB("VmRSS:");
    vtkNew<vtkGaussianGenealogyTreeFilter> filter;
    filter->SetInputData(table);
    filter->SetNumberOfInitialGaussians(initial);
    filter->SetLastIteration(last);
    filter->SetValidateStructure(mode == 1);
    filter->SetNaiveConstruction(mode == 2);
    filter->SetCompactTree(mode == 3);
    const double wall0 = Now(), cpu0 = ProcessCpu();
    filter->Update();
    const double wall = Now() - wall0, cpu = ProcessCpu() - cpu0;
    const double peak = StatusMiB("VmHWM:");
    std::printf("%s: %lld vertices; whole filter wall %.3f s (process CPU %.3f s); Core "
                "genealogy wall %.3f s (CPU %.3f s), vtkTree with arrays wall %.3f s (CPU %.3f "
                "s); RSS before %.0f MiB, peak %.0f MiB, after %.0f MiB\n",
      names[mode],
      static_cast<long long>(filter->GetOutput()->GetNumberOfVertices()),
      wall,
      cpu,
      filter->GetGenealogySeconds(),
      filter->GetGenealogyCPUSeconds(),
      filter->GetTreeSeconds(),
      filter->GetTreeCPUSeconds(),
      before,
      peak,
      StatusMiB("VmRSS:"));
    std::fflush(stdout);
    if (mode != 0 && mode != 3)
    {
      continue;
    }
    vtkNew<vtkGaussianTreeLevelOfDetail> lod;
    lod->SetInputConnection(filter->GetOutputPort());
    lod->BuildVisibleTreeOff();
    for (double z : { 0.1, 0.5, 1.0, 1.5 })
    {
      lod->SetZoom(z);
      lod->Update();
      std::printf("  LOD filter z=%.2f: %lld visible, index %.3f s, query wall %.2f ms (CPU %.2f "
                  "ms)\n",
        z,
        static_cast<long long>(lod->GetNumberOfVisibleVertices()),
        lod->GetIndexSeconds(),
        lod->GetQuerySeconds() * 1e3,
        lod->GetQueryCPUSeconds() * 1e3);
    }
    lod->BuildVisibleTreeOn();
    lod->SetZoom(0.5);
    lod->Modified();
    lod->Update();
    std::printf("  LOD filter z=0.50 with visible subtree: %lld vertices, query CPU %.2f ms\n",
      static_cast<long long>(lod->GetOutput()->GetNumberOfVertices()),
      lod->GetQueryCPUSeconds() * 1e3);
  }
  return 0;
}
