// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSSoak.h"

#include "Vis4GSCleanupPanel.h"
#include "Vis4GSDocument.h"
#include "Vis4GSMainWindow.h"
#include "vtkGaussianSceneView.h"
#include "vtkGaussianSelectionHub.h"

#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkRenderWindow.h"

#include <QApplication>
#include <QDir>
#include <QFile>
#include <QSlider>
#include <QTimer>

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{

struct Sample
{
  double ResidentMB = 0;
  double HeapMB = 0;
  /// What malloc holds from the system (every arena's pages and the blocks mapped whole).
  double MallocSystemMB = 0;
  /// The resident size by kind of mapping (/proc/self/smaps), to tell where growth outside the
  /// heap in use lives: the main arena's [heap]; other anonymous memory (threads' arenas and
  /// stacks, Mesa's buffers); anonymous executable memory (llvmpipe's compiled shaders);
  /// file-backed (libraries, the log's and the scene's pages, fonts).
  double HeapSegmentMB = 0;
  double AnonymousMB = 0;
  double ExecutableMB = 0;
  double FileMB = 0;
  int Mappings = 0;
  int Descriptors = 0;
  int Threads = 0;
  int TempEntries = 0;
};

int CountEntries(const QString& folder)
{
  return static_cast<int>(
    QDir(folder)
      .entryList(QDir::AllEntries | QDir::Hidden | QDir::System | QDir::NoDotAndDotDot)
      .size());
}

void MeasureMappings(Sample& s)
{
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  double* kind = nullptr;
  while (std::getline(smaps, line))
  {
    std::istringstream fields(line);
    std::string first;
    fields >> first;
    if (!first.empty() && first.back() != ':')
    {
      // A mapping's header: "start-end perms offset dev inode [path]".
      std::string perms, offset, device, inode, path;
      fields >> perms >> offset >> device >> inode;
      std::getline(fields >> std::ws, path);
      ++s.Mappings;
      if (path == "[heap]")
      {
        kind = &s.HeapSegmentMB;
      }
      else if (path.empty() || path[0] == '[')
      {
        kind = perms.find('x') != std::string::npos ? &s.ExecutableMB : &s.AnonymousMB;
      }
      else
      {
        kind = &s.FileMB;
      }
    }
    else if (first == "Rss:" && kind)
    {
      double kB = 0;
      fields >> kB;
      *kind += kB * 1024.0 / 1e6;
    }
  }
}

Sample Measure()
{
  Sample s;
  // Memory in use, which a leak makes grow: the heap's allocated bytes (every arena, and the
  // blocks mmap'ed whole). The resident size also holds what the allocator keeps free, which
  // depends on the order of allocations across threads (fragmentation); it is measured after
  // malloc_trim gave back what it can, and recorded.
  const struct mallinfo2 heap = mallinfo2();
  s.HeapMB = static_cast<double>(heap.uordblks + heap.hblkhd) / 1e6;
  malloc_trim(0);
  const struct mallinfo2 trimmed = mallinfo2();
  s.MallocSystemMB = static_cast<double>(trimmed.arena + trimmed.hblkhd) / 1e6;
  MeasureMappings(s);
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  s.ResidentMB = static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1e6;
  s.Descriptors = CountEntries("/proc/self/fd");
  s.Threads = CountEntries("/proc/self/task");
  s.TempEntries = CountEntries(QDir::tempPath());
  return s;
}

struct SoakState
{
  Vis4GSSoakOptions Options;
  int Cycle = 0;
  std::vector<Sample> Samples;
  std::ofstream Csv;
  std::chrono::steady_clock::time_point Started;
  std::chrono::steady_clock::time_point Opened; ///< when the cycle's file was opened
  bool Running = false; // a cycle's actions are under way (scoresComputed may come again)
};

/// The actions of one cycle on the loaded, scored document; false when the fine-tune failed.
bool Exercise(Vis4GSMainWindow& w, const Vis4GSSoakOptions& options)
{
  const std::shared_ptr<Vis4GSDocument> doc = w.GetDocument();
  auto* slider = w.findChild<QSlider*>("iteration");
  if (doc && doc->Snapshots.size() > 1 && slider)
  {
    slider->setValue(slider->maximum() - 1);
    QApplication::processEvents();
    slider->setValue(slider->maximum());
    QApplication::processEvents();
  }
  vtkGaussianSceneView* view = w.GetSceneView();
  const int* size = view->GetRenderWindow()->GetSize();
  const double x = size[0] / 2.0, y = size[1] / 2.0;
  view->SelectSingle(x, y, vtkGaussianSelectionHub::REPLACE);
  view->SelectRay(x, y, vtkGaussianSelectionHub::ADD);
  view->SelectFrame(x - 20, y - 20, x + 20, y + 20, vtkGaussianSelectionHub::REPLACE);
  vtkNew<vtkPoints> stroke;
  for (double dx : { -6.0, 0.0, 6.0 })
  {
    stroke->InsertNextPoint(x + dx, y, 0.0);
  }
  view->SelectBrush(stroke, vtkGaussianSelectionHub::SUBTRACT);
  QApplication::processEvents();
  Vis4GSCleanupPanel* panel = w.GetCleanupPanel();
  bool ok = true;
  if (panel && panel->ApplyRule("opacity<=0.05", Vis4GSCleanupPanel::REPLACE) &&
    doc->CamerasWithImages > 0 && w.GetScoreCameras())
  {
    panel->MeasureRemoval();
    if (panel->WaitForMeasurement() && options.FineTuneIterations > 0)
    {
      // The repaired log is not kept: the cycle exercises the trainer, its writer and the
      // panel's repaired figures, and a file left would count as one more each cycle.
      const QString repaired = options.Directory + "/soak-fine-tune.h5";
      ok = panel->StartFineTune(repaired, options.FineTuneIterations, false, false) &&
        panel->WaitForFineTune();
      QFile::remove(repaired);
    }
  }
  QApplication::processEvents();
  return ok;
}

double Mean(const std::vector<Sample>& s, std::size_t from, std::size_t count, double Sample::*what)
{
  double sum = 0;
  for (std::size_t i = from; i < from + count; ++i)
  {
    sum += s[i].*what;
  }
  return sum / static_cast<double>(count);
}

int Finish(const SoakState& state)
{
  // The files differ (a log keeps its reader and more threads than a scene): every comparison
  // is between cycles of the same files, windows of whole rounds of the files.
  const std::vector<Sample>& s = state.Samples;
  const std::size_t n = s.size();
  const std::size_t files = static_cast<std::size_t>(state.Options.Files.size());
  const std::size_t warm = std::min<std::size_t>(n / 2, 20) / files * files;
  const std::size_t window =
    files * std::max<std::size_t>(1, std::min<std::size_t>(10 / files, (n - warm) / (2 * files)));
  const double after = Mean(s, warm, window, &Sample::HeapMB);
  const double end = Mean(s, n - window, window, &Sample::HeapMB);
  const double residentAfter = Mean(s, warm, window, &Sample::ResidentMB);
  const double residentEnd = Mean(s, n - window, window, &Sample::ResidentMB);
  std::size_t same = warm;
  while (same % files != (n - 1) % files)
  {
    ++same;
  }
  const Sample& a = s[same];
  const Sample& b = s[n - 1];
  const Sample& first = s[(n - 1) % files];
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - state.Started).count();
  std::cout << "soak: " << n << " cycles in " << seconds << " s; heap in use " << s.front().HeapMB
            << " MB after the first cycle, " << after << " MB after the warm-up of " << warm
            << " cycles (mean of " << window << "), " << end << " MB at the end (mean of the last "
            << window << "): growth " << end - after << " MB (bound " << state.Options.BoundMB
            << " MB)" << std::endl;
  std::cout << "soak: resident memory (after malloc_trim) " << s.front().ResidentMB << " MB, "
            << residentAfter << " MB after the warm-up, " << residentEnd
            << " MB at the end: growth " << residentEnd - residentAfter << " MB; peak "
            << std::max_element(s.begin(),
                 s.end(),
                 [](const Sample& l, const Sample& r) { return l.ResidentMB < r.ResidentMB; })
                 ->ResidentMB
            << " MB" << std::endl;
  // Where the resident growth lives (not bounded: the heap in use is; see the header).
  std::cout << "soak: resident parts after the warm-up -> at the end (means, MB):";
  const std::pair<const char*, double Sample::*> parts[] = { { "malloc from the system",
                                                               &Sample::MallocSystemMB },
    { "[heap]", &Sample::HeapSegmentMB },
    { "other anonymous", &Sample::AnonymousMB },
    { "anonymous executable", &Sample::ExecutableMB },
    { "file-backed", &Sample::FileMB } };
  for (const auto& part : parts)
  {
    std::cout << " " << part.first << " " << Mean(s, warm, window, part.second) << " -> "
              << Mean(s, n - window, window, part.second) << ";";
  }
  std::cout << " mappings " << a.Mappings << " -> " << b.Mappings << std::endl;
  std::cout << "soak: file descriptors " << a.Descriptors << " -> " << b.Descriptors << ", threads "
            << a.Threads << " -> " << b.Threads << ", temporary entries " << a.TempEntries << " -> "
            << b.TempEntries << " (" << QDir::tempPath().toStdString() << ")" << std::endl;
  bool ok = true;
  auto check = [&ok](bool condition, const std::string& what)
  {
    std::cout << (condition ? "ok: " : "FAILED: ") << what << std::endl;
    ok = ok && condition;
  };
  check(end - after <= state.Options.BoundMB, "the heap in use grows within the bound");
  check(b.Descriptors <= a.Descriptors, "no file descriptor is left open");
  check(b.Threads <= a.Threads, "no thread is left running");
  check(b.TempEntries <= first.TempEntries, "no temporary file is left behind");
  std::cout << (ok ? "soak passed" : "soak FAILED") << std::endl;
  return ok ? 0 : 1;
}

void OpenNext(Vis4GSMainWindow* window, const std::shared_ptr<SoakState>& state)
{
  const QStringList& files = state->Options.Files;
  state->Opened = std::chrono::steady_clock::now();
  window->Open(files[state->Cycle % files.size()]);
}

} // namespace

//------------------------------------------------------------------------------
void Vis4GSInstallSoak(Vis4GSMainWindow* window, const Vis4GSSoakOptions& options)
{
  auto state = std::make_shared<SoakState>();
  state->Options = options;
  state->Options.Cycles = std::max(10, options.Cycles);
  QDir().mkpath(options.Directory);
  state->Csv.open((options.Directory + "/soak.csv").toStdString());
  state->Csv << "cycle,file,heap_mb,resident_mb,descriptors,threads,temporary_entries,seconds,"
                "open_and_score_s,actions_s,malloc_system_mb,heap_segment_mb,anonymous_mb,"
                "executable_mb,file_mb,mappings\n";
  state->Started = std::chrono::steady_clock::now();
  QObject::connect(window,
    &Vis4GSMainWindow::scoresComputed,
    window,
    [window, state]
    {
      if (state->Running)
      {
        return;
      }
      state->Running = true;
      QTimer::singleShot(0,
        window,
        [window, state]
        {
          const auto scored = std::chrono::steady_clock::now();
          if (!Exercise(*window, state->Options))
          {
            std::cout << "soak FAILED: the clean-up panel's fine-tune failed in cycle "
                      << state->Cycle << std::endl;
            QApplication::exit(1);
            return;
          }
          const auto acted = std::chrono::steady_clock::now();
          const Sample s = Measure();
          state->Samples.push_back(s);
          state->Csv << state->Cycle << ","
                     << QFileInfo(state->Options.Files[state->Cycle % state->Options.Files.size()])
                          .fileName()
                          .toStdString()
                     << "," << s.HeapMB << "," << s.ResidentMB << "," << s.Descriptors << ","
                     << s.Threads << "," << s.TempEntries << ","
                     << std::chrono::duration<double>(
                          std::chrono::steady_clock::now() - state->Started)
                          .count()
                     << "," << std::chrono::duration<double>(scored - state->Opened).count() << ","
                     << std::chrono::duration<double>(acted - scored).count() << ","
                     << s.MallocSystemMB << "," << s.HeapSegmentMB << "," << s.AnonymousMB << ","
                     << s.ExecutableMB << "," << s.FileMB << "," << s.Mappings << std::endl;
          ++state->Cycle;
          state->Running = false;
          if (state->Cycle >= state->Options.Cycles)
          {
            state->Csv.close();
            QApplication::exit(Finish(*state));
            return;
          }
          OpenNext(window, state);
        });
    });
  QObject::connect(window,
    &Vis4GSMainWindow::loadFailed,
    window,
    [](const QString& error)
    {
      std::cout << "soak FAILED: " << error.toStdString() << std::endl;
      QApplication::exit(1);
    });
  QTimer::singleShot(0, window, [window, state] { OpenNext(window, state); });
}
