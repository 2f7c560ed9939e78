// SPDX-License-Identifier: BSD-3-Clause
// `vis4gs view FILE --stages-test=STAGE1_CSV,EXACT_CSV`: the application's progressive scores
// (issue 31) against `vis4gs analyze`'s: stage 1's arrays appear first (labelled approximate,
// equal to `analyze --stop-after-stage=1`), then the exact arrays replace them (equal to
// `analyze`'s), the window answering events in between; then the file is opened again and the
// panel's Stop button pressed as soon as stage 1 shows: stage 1's arrays stay, labelled.
#include "Vis4GSSelfTest.h"

#include "Vis4GSDocument.h"
#include "Vis4GSMainWindow.h"

#include "vtkAbstractArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include <QApplication>
#include <QElapsedTimer>
#include <QLabel>
#include <QPushButton>
#include <QTimer>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace
{
// A scores.csv of `vis4gs analyze`: column name -> (GaussianId -> value).
using Columns = std::map<std::string, std::map<long long, double>>;

bool ReadScoresCsv(const std::string& path, Columns& columns)
{
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line))
  {
    std::cout << "FAILED: cannot read " << path << std::endl;
    return false;
  }
  std::vector<std::string> header;
  std::stringstream names(line);
  for (std::string name; std::getline(names, name, ',');)
  {
    header.push_back(name);
  }
  while (std::getline(in, line))
  {
    std::stringstream row(line);
    std::string cell;
    std::getline(row, cell, ',');
    const long long id = std::stoll(cell);
    for (std::size_t k = 1; k < header.size() && std::getline(row, cell, ','); ++k)
    {
      columns[header[k]][id] = std::stod(cell);
    }
  }
  return !columns.empty();
}

// The scene's arrays named in @p reference, Gaussian by Gaussian, against it: the CSV prints 9
// significant digits, so equal means equal to them (a NaN equals a NaN).
bool SameAsCsv(vtkPolyData* scene, const Columns& reference, std::string& why)
{
  vtkDataArray* ids = scene->GetPointData()->GetArray("GaussianId");
  if (!ids)
  {
    why = "the scene has no GaussianId";
    return false;
  }
  for (const auto& column : reference)
  {
    vtkDataArray* a = scene->GetPointData()->GetArray(column.first.c_str());
    if (!a)
    {
      why = "no " + column.first + " array";
      return false;
    }
    std::size_t compared = 0;
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      const auto it = column.second.find(static_cast<long long>(ids->GetTuple1(i)));
      if (it == column.second.end())
      {
        continue;
      }
      const double mine = a->GetTuple1(i), theirs = it->second;
      const bool same = (std::isnan(mine) && std::isnan(theirs)) ||
        std::abs(mine - theirs) <= 2e-8 * std::max(std::abs(theirs), 1e-30);
      if (!same)
      {
        std::ostringstream s;
        s.precision(10);
        s << column.first << " of Gaussian " << it->first << ": " << mine << " here, " << theirs
          << " in the CSV";
        why = s.str();
        return false;
      }
      ++compared;
    }
    if (compared != column.second.size())
    {
      why = column.first + ": " + std::to_string(compared) + " of " +
        std::to_string(column.second.size()) + " CSV rows found in the scene";
      return false;
    }
  }
  return true;
}

std::string StageLabel(vtkPolyData* scene)
{
  auto* label = vtkStringArray::SafeDownCast(
    scene ? scene->GetFieldData()->GetAbstractArray("ScoreStage") : nullptr);
  return label && label->GetNumberOfValues() > 0 ? label->GetValue(0) : std::string();
}

struct StagesTest
{
  Vis4GSMainWindow* Window = nullptr;
  QString File;
  Columns Stage1, Exact;
  bool Ok = true;
  int Phase = 0; // 0: both stages; 1: opened again, stopped after stage 1
  int Ticks = 0; // GUI timer ticks while stage 2 ran
  int TicksAtStage1 = -1;
  qint64 LongestGapMs = 0;
  QElapsedTimer SinceTick;
  QTimer Ticker;

  void Check(bool condition, const std::string& what)
  {
    std::cout << (condition ? "ok: " : "FAILED: ") << what << std::endl;
    this->Ok = this->Ok && condition;
  }
  vtkPolyData* Scene() const
  {
    const auto doc = this->Window->GetDocument();
    return doc ? doc->Shown() : nullptr;
  }
  std::string PanelLabel() const
  {
    auto* label = this->Window->findChild<QLabel*>("score-stage");
    return label ? label->text().toStdString() : std::string("(no score-stage label)");
  }
  void Finish()
  {
    std::cout << "GUI timer: " << this->Ticks << " ticks, longest gap " << this->LongestGapMs
              << " ms" << std::endl;
    std::cout << (this->Ok ? "stages test passed" : "stages test FAILED") << std::endl;
    QApplication::exit(this->Ok ? 0 : 1);
  }

  void OnStage(int stage, int of)
  {
    vtkPolyData* scene = this->Scene();
    const std::string label = StageLabel(scene);
    std::string why;
    const std::string phase = this->Phase == 0 ? "" : " (opened again)";
    if (stage == 1)
    {
      this->TicksAtStage1 = this->Ticks;
      this->Check(of == 2, "stage 1 of " + std::to_string(of) + phase);
      this->Check(label.rfind("stage 1 of 2, approximate: every 8th training view", 0) == 0,
        "stage 1's arrays are labelled in the scene: '" + label + "'" + phase);
      this->Check(this->PanelLabel() == label, "the panel shows it: '" + this->PanelLabel() + "'");
      this->Check(SameAsCsv(scene, this->Stage1, why),
        "stage 1's arrays equal vis4gs analyze --stop-after-stage=1's scores.csv" + phase +
          (why.empty() ? "" : ": " + why));
      if (this->Phase == 1)
      {
        auto* stop = this->Window->findChild<QPushButton*>("stop-scores");
        this->Check(stop && stop->isEnabled(), "the Stop button is enabled while scores run");
        if (stop)
        {
          stop->click();
        }
      }
      return;
    }
    this->Check(this->Phase == 0, "the exact stage comes in the run that is not stopped");
    this->Check(label == "stage 2 of 2, exact", "the exact stage is labelled: '" + label + "'");
    this->Check(this->PanelLabel() == label, "the panel shows it: '" + this->PanelLabel() + "'");
    this->Check(SameAsCsv(scene, this->Exact, why),
      "the exact arrays replaced stage 1's and equal vis4gs analyze's scores.csv" +
        (why.empty() ? "" : ": " + why));
    this->Check(!SameAsCsv(scene, this->Stage1, why), "and differ from stage 1's");
    this->Check(this->TicksAtStage1 >= 0 && this->Ticks > this->TicksAtStage1,
      "the window answered its timer while the exact stage ran (" +
        std::to_string(this->Ticks - this->TicksAtStage1) + " ticks)");
  }

  void OnScoresComputed()
  {
    if (this->Phase == 0)
    {
      this->Phase = 1;
      this->Window->Open(this->File);
      return;
    }
    vtkPolyData* scene = this->Scene();
    std::string why;
    const std::string label = StageLabel(scene);
    this->Check(label.rfind("stage 1 of 2, approximate", 0) == 0,
      "after Stop the scene keeps stage 1's label: '" + label + "'");
    this->Check(this->PanelLabel().find("approximate") != std::string::npos &&
        this->PanelLabel().find("(stopped)") != std::string::npos,
      "the panel says approximate and stopped: '" + this->PanelLabel() + "'");
    this->Check(SameAsCsv(scene, this->Stage1, why),
      "and stage 1's arrays" + (why.empty() ? "" : ": " + why));
    this->Finish();
  }
};
}

//------------------------------------------------------------------------------
bool Vis4GSInstallScoreStagesTest(Vis4GSMainWindow* window,
  const QString& file,
  const std::string& stage1Csv,
  const std::string& exactCsv)
{
  auto test = std::make_shared<StagesTest>();
  test->Window = window;
  test->File = file;
  if (!ReadScoresCsv(stage1Csv, test->Stage1) || !ReadScoresCsv(exactCsv, test->Exact))
  {
    return false;
  }
  test->Ticker.setInterval(20);
  QObject::connect(&test->Ticker,
    &QTimer::timeout,
    window,
    [raw = test.get()]
    {
      ++raw->Ticks;
      raw->LongestGapMs = std::max(raw->LongestGapMs, raw->SinceTick.restart());
    });
  test->SinceTick.start();
  test->Ticker.start();
  QObject::connect(window,
    &Vis4GSMainWindow::scoreStageShown,
    window,
    [test](int stage, int of) { test->OnStage(stage, of); });
  QObject::connect(
    window, &Vis4GSMainWindow::scoresComputed, window, [test] { test->OnScoresComputed(); });
  QObject::connect(
    window, &Vis4GSMainWindow::loadFailed, window, [](const QString&) { QApplication::exit(1); });
  return true;
}
