/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianTimelineView.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianTimelineView.h"

#include "Vis4GSDataModel.h" // vis4gs::arrays, the column names of the metrics tables

#include "Vis4GSHubLink.h"
#include "Vis4GSViewInput.h"
#include "vtkAxis.h"
#include "vtkCallbackCommand.h"
#include "vtkChartLegend.h"
#include "vtkChartMatrix.h"
#include "vtkContextScene.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianTimelineChart.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPen.h"
#include "vtkPlot.h"
#include "vtkPlotPoints.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTable.h"
#include "vtkTextProperty.h"
#include "vtkVector.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkGaussianTimelineView);

namespace
{
const unsigned char Palette[8][3] = { { 31, 119, 180 },
  { 255, 127, 14 },
  { 44, 160, 44 },
  { 214, 39, 40 },
  { 148, 103, 189 },
  { 140, 86, 75 },
  { 227, 119, 194 },
  { 127, 127, 127 } };

bool HasFiniteValue(vtkDataArray* a)
{
  for (vtkIdType i = 0; a && i < a->GetNumberOfTuples(); ++i)
  {
    if (std::isfinite(a->GetComponent(i, 0)))
    {
      return true;
    }
  }
  return false;
}

bool AllFinite(vtkDataArray* a)
{
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    if (!std::isfinite(a->GetComponent(i, 0)))
    {
      return false;
    }
  }
  return true;
}
}

struct vtkGaussianTimelineView::vtkInternals
{
  vtkNew<vtkChartMatrix> Matrix;
  vtkNew<vtkGaussianTimelineChart> Charts[3];
  vtkSmartPointer<vtkTable> Metrics, TestMetrics, History;
  vtkSmartPointer<vtkTable> ComparisonMetrics, ComparisonTestMetrics;
  /// The finite rows of metric columns that have NaN (a merged train/test table).
  std::vector<vtkSmartPointer<vtkTable>> FiniteRows;
  vtkNew<vtkTable> Wide;
  Vis4GSViewInput MetricsInput, HistoryInput;
  Vis4GSHubLink Hub;
  vtkNew<vtkCallbackCommand> HubCommand;
  vtkNew<vtkCallbackCommand> ClickCommand;
  int Iteration = -1;
  int ComparisonIteration = -1;
  int HistoryLines = 0;
  int MetricPlots = 0;
  int ComparisonPlots = 0;
};

//------------------------------------------------------------------------------
vtkGaussianTimelineView::vtkGaussianTimelineView()
  : Internals(new vtkInternals)
{
  this->SetHistoryProperty("Opacity");
  this->RunName = strcpy(new char[2], "A");
  this->ComparisonRunName = strcpy(new char[2], "B");
  this->SetIterationColumn(vis4gs::arrays::MetricIteration);
  this->SetCountColumn(vis4gs::arrays::MetricGaussians);
  this->SetPSNRColumn(vis4gs::arrays::MetricPSNR);
  this->SetSSIMColumn(vis4gs::arrays::MetricSSIM);
  this->SetLPIPSColumn(vis4gs::arrays::MetricLPIPS);
  this->SetHistoryIterationColumn(vis4gs::arrays::HistoryIteration);
  this->SetHistoryIdColumn(vis4gs::arrays::GaussianId);
  auto& in = *this->Internals;
  in.Matrix->SetSize(vtkVector2i(1, 3));
  in.Matrix->SetGutter(vtkVector2f(30.f, 30.f));
  const char* titles[3] = { "Quality", "Gaussians", "Selected Gaussians" };
  in.ClickCommand->SetClientData(this);
  in.ClickCommand->SetCallback([](vtkObject*, unsigned long, void* client, void* data)
    { static_cast<vtkGaussianTimelineView*>(client)->OnChartClicked(*static_cast<int*>(data)); });
  for (int k = 0; k < 3; ++k)
  {
    vtkGaussianTimelineChart* chart = in.Charts[k];
    in.Matrix->SetChart(vtkVector2i(0, 2 - k), chart);
    chart->SetTitle(titles[k]);
    chart->GetTitleProperties()->SetFontSize(12);
    chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(k == HISTORY ? "iteration" : "");
    chart->GetAxis(vtkAxis::LEFT)->SetTitle("");
    chart->GetAxis(vtkAxis::RIGHT)->SetTitle("");
    chart->SetShowLegend(true);
    chart->AddObserver(vtkGaussianTimelineChart::IterationClickedEvent, in.ClickCommand);
  }
  this->GetScene()->AddItem(in.Matrix);
  this->GetRenderer()->SetBackground(1, 1, 1);
  in.HubCommand->SetClientData(this);
  in.HubCommand->SetCallback(
    [](vtkObject*, unsigned long event, void* client, void*)
    {
      auto* self = static_cast<vtkGaussianTimelineView*>(client);
      if (event == vtkGaussianSelectionHub::IterationChangedEvent)
      {
        self->SetIteration(self->GetSelectionHub()->GetIteration());
      }
      else
      {
        self->UpdatePlots();
      }
    });
}

//------------------------------------------------------------------------------
vtkGaussianTimelineView::~vtkGaussianTimelineView()
{
  this->SetSelectionHub(nullptr);
  this->SetHistoryProperty(nullptr);
  delete[] this->RunName;
  delete[] this->ComparisonRunName;
  this->SetIterationColumn(nullptr);
  this->SetCountColumn(nullptr);
  this->SetPSNRColumn(nullptr);
  this->SetSSIMColumn(nullptr);
  this->SetLPIPSColumn(nullptr);
  this->SetHistoryIterationColumn(nullptr);
  this->SetHistoryIdColumn(nullptr);
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineView::SetMetrics(vtkTable* metrics)
{
  this->Internals->MetricsInput.SetConnection(nullptr);
  this->Internals->Metrics = metrics;
  this->UpdatePlots();
}

//------------------------------------------------------------------------------
vtkTable* vtkGaussianTimelineView::GetMetrics()
{
  return this->Internals->Metrics;
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineView::SetTestMetrics(vtkTable* metrics)
{
  this->Internals->TestMetrics = metrics;
  this->UpdatePlots();
}

//------------------------------------------------------------------------------
vtkTable* vtkGaussianTimelineView::GetTestMetrics()
{
  return this->Internals->TestMetrics;
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineView::SetComparisonMetrics(vtkTable* metrics)
{
  this->Internals->ComparisonMetrics = metrics;
  this->UpdatePlots();
}

//------------------------------------------------------------------------------
vtkTable* vtkGaussianTimelineView::GetComparisonMetrics()
{
  return this->Internals->ComparisonMetrics;
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineView::SetComparisonTestMetrics(vtkTable* metrics)
{
  this->Internals->ComparisonTestMetrics = metrics;
  this->UpdatePlots();
}

//------------------------------------------------------------------------------
vtkTable* vtkGaussianTimelineView::GetComparisonTestMetrics()
{
  return this->Internals->ComparisonTestMetrics;
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineView::SetRunName(const char* name)
{
  vtkSetStringBodyMacro(RunName, name);
  this->UpdatePlots();
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineView::SetComparisonRunName(const char* name)
{
  vtkSetStringBodyMacro(ComparisonRunName, name);
  this->UpdatePlots();
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineView::SetHistory(vtkTable* history)
{
  this->Internals->HistoryInput.SetConnection(nullptr);
  this->Internals->History = history;
  this->UpdatePlots();
}

//------------------------------------------------------------------------------
vtkTable* vtkGaussianTimelineView::GetHistory()
{
  return this->Internals->History;
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineView::SetMetricsConnection(vtkAlgorithmOutput* metrics)
{
  this->Internals->MetricsInput.SetConnection(metrics);
  this->Modified();
}
vtkAlgorithmOutput* vtkGaussianTimelineView::GetMetricsConnection()
{
  return this->Internals->MetricsInput.GetConnection();
}
void vtkGaussianTimelineView::SetHistoryConnection(vtkAlgorithmOutput* history)
{
  this->Internals->HistoryInput.SetConnection(history);
  this->Modified();
}
vtkAlgorithmOutput* vtkGaussianTimelineView::GetHistoryConnection()
{
  return this->Internals->HistoryInput.GetConnection();
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineView::Update()
{
  auto& in = *this->Internals;
  vtkSmartPointer<vtkDataObject> data;
  bool changed = false;
  if (in.MetricsInput.Pull(data))
  {
    in.Metrics = vtkTable::SafeDownCast(data);
    changed = true;
  }
  if (in.HistoryInput.Pull(data))
  {
    in.History = vtkTable::SafeDownCast(data);
    changed = true;
  }
  if (changed)
  {
    this->UpdatePlots();
  }
  this->Superclass::Update();
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineView::Render()
{
  this->Update();
  this->Superclass::Render();
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineView::SetSelectionHub(vtkGaussianSelectionHub* hub)
{
  auto& in = *this->Internals;
  if (!in.Hub.Link(hub, in.HubCommand, this, true))
  {
    return;
  }
  if (hub)
  {
    in.Iteration = hub->GetIteration();
  }
  this->UpdatePlots();
}

//------------------------------------------------------------------------------
vtkGaussianSelectionHub* vtkGaussianTimelineView::GetSelectionHub()
{
  return this->Internals->Hub;
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineView::SetIteration(int iteration)
{
  auto& in = *this->Internals;
  in.Iteration = iteration;
  for (auto& chart : in.Charts)
  {
    chart->SetCursorIteration(iteration);
  }
  this->GetScene()->SetDirty(true);
  this->Modified();
}

//------------------------------------------------------------------------------
int vtkGaussianTimelineView::GetIteration()
{
  return this->Internals->Iteration;
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineView::SetComparisonIteration(int iteration)
{
  auto& in = *this->Internals;
  in.ComparisonIteration = iteration;
  for (auto& chart : in.Charts)
  {
    chart->SetComparisonCursorIteration(iteration);
  }
  this->GetScene()->SetDirty(true);
  this->Modified();
}

//------------------------------------------------------------------------------
int vtkGaussianTimelineView::GetComparisonIteration()
{
  return this->Internals->ComparisonIteration;
}

//------------------------------------------------------------------------------
vtkGaussianTimelineChart* vtkGaussianTimelineView::GetChart(int which)
{
  return (which >= 0 && which < 3) ? this->Internals->Charts[which].GetPointer() : nullptr;
}

//------------------------------------------------------------------------------
int vtkGaussianTimelineView::GetNumberOfHistoryLines()
{
  return this->Internals->HistoryLines;
}

//------------------------------------------------------------------------------
vtkTable* vtkGaussianTimelineView::GetHistoryLines()
{
  return this->Internals->Wide;
}

//------------------------------------------------------------------------------
int vtkGaussianTimelineView::GetNumberOfMetricPlots()
{
  return this->Internals->MetricPlots;
}

//------------------------------------------------------------------------------
int vtkGaussianTimelineView::GetNumberOfComparisonPlots()
{
  return this->Internals->ComparisonPlots;
}

//------------------------------------------------------------------------------
int vtkGaussianTimelineView::SnapIteration(int iteration)
{
  vtkTable* m = this->Internals->Metrics;
  vtkDataArray* it =
    m ? vtkDataArray::SafeDownCast(m->GetColumnByName(this->IterationColumn)) : nullptr;
  if (!it || it->GetNumberOfTuples() == 0)
  {
    return iteration;
  }
  double best = it->GetComponent(0, 0);
  for (vtkIdType i = 1; i < it->GetNumberOfTuples(); ++i)
  {
    const double v = it->GetComponent(i, 0);
    if (std::abs(v - iteration) < std::abs(best - iteration))
    {
      best = v;
    }
  }
  return static_cast<int>(best);
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineView::OnChartClicked(int iteration)
{
  int snapped = this->SnapIteration(iteration);
  this->InvokeEvent(IterationSelectedEvent, &snapped);
  if (this->Internals->Hub)
  {
    this->Internals->Hub->SetIteration(snapped);
  }
  else
  {
    this->SetIteration(snapped);
  }
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineView::UpdatePlots()
{
  auto& in = *this->Internals;
  for (auto& chart : in.Charts)
  {
    chart->ClearPlots();
  }
  in.MetricPlots = 0;
  in.ComparisonPlots = 0;
  in.HistoryLines = 0;
  in.FiniteRows.clear();
  double xmin = std::numeric_limits<double>::max(), xmax = std::numeric_limits<double>::lowest();

  // With a second run, both runs' entries carry the run's name and the second run's lines are
  // dotted (its test metrics dash-dotted), so the two runs differ by style, the metrics by
  // colour.
  const bool comparing = in.ComparisonMetrics || in.ComparisonTestMetrics;
  auto addMetric = [&](vtkTable* table,
                     const char* column,
                     int chart,
                     int corner,
                     const unsigned char* color,
                     int lineType,
                     const char* label,
                     bool second)
  {
    if (!table || !column)
    {
      return;
    }
    auto* x = vtkDataArray::SafeDownCast(table->GetColumnByName(this->IterationColumn));
    auto* y = vtkDataArray::SafeDownCast(table->GetColumnByName(column));
    if (!x || !y || !HasFiniteValue(y))
    {
      return;
    }
    if (!AllFinite(y))
    {
      // A line through NaN breaks at every gap: the test columns of the log reader's merged
      // table (NaN where the test set was not measured) would draw as scattered dots.
      vtkNew<vtkTable> finite;
      vtkSmartPointer<vtkDataArray> fx, fy;
      fx.TakeReference(x->NewInstance());
      fy.TakeReference(y->NewInstance());
      fx->SetName(x->GetName());
      fy->SetName(y->GetName());
      for (vtkIdType i = 0; i < y->GetNumberOfTuples(); ++i)
      {
        if (std::isfinite(y->GetComponent(i, 0)))
        {
          fx->InsertNextTuple1(x->GetComponent(i, 0));
          fy->InsertNextTuple1(y->GetComponent(i, 0));
        }
      }
      finite->AddColumn(fx);
      finite->AddColumn(fy);
      in.FiniteRows.emplace_back(finite);
      table = finite;
      x = fx;
    }
    double range[2];
    x->GetRange(range);
    xmin = std::min(xmin, range[0]);
    xmax = std::max(xmax, range[1]);
    vtkPlot* plot = in.Charts[chart]->AddPlot(vtkChart::LINE);
    plot->SetInputData(table, this->IterationColumn, column);
    plot->SetColor(color[0], color[1], color[2], 255);
    plot->SetWidth(2.f);
    const char* run = second ? this->ComparisonRunName : this->RunName;
    plot->SetLabel(comparing ? std::string(label) + " [" + (run ? run : "") + "]" : label);
    plot->GetPen()->SetLineType(lineType);
    if (corner)
    {
      in.Charts[chart]->SetPlotCorner(plot, corner);
    }
    ++in.MetricPlots;
    in.ComparisonPlots += second ? 1 : 0;
  };
  const int solid = vtkPen::SOLID_LINE, dashed = vtkPen::DASH_LINE;
  for (const bool second : { false, true })
  {
    vtkTable* train = second ? in.ComparisonMetrics : in.Metrics;
    // Test metrics: their own table, else the Test-prefixed columns of a merged table (the log
    // reader's metrics port).
    vtkTable* ownTest = second ? in.ComparisonTestMetrics : in.TestMetrics;
    vtkTable* test = ownTest ? ownTest : train;
    auto testColumn = [&](const char* column) -> std::string
    {
      return ownTest || !column ? std::string(column ? column : "")
                                : vis4gs::arrays::MetricTestPrefix + std::string(column);
    };
    const std::string testPSNR = testColumn(this->PSNRColumn);
    const std::string testSSIM = testColumn(this->SSIMColumn);
    const std::string testLPIPS = testColumn(this->LPIPSColumn);
    const int trainLine = second ? static_cast<int>(vtkPen::DOT_LINE) : solid;
    const int testLine = second ? static_cast<int>(vtkPen::DASH_DOT_LINE) : dashed;
    addMetric(train, this->PSNRColumn, QUALITY, 0, Palette[0], trainLine, "PSNR", second);
    addMetric(train, this->SSIMColumn, QUALITY, 1, Palette[1], trainLine, "SSIM", second);
    addMetric(train, this->LPIPSColumn, QUALITY, 1, Palette[2], trainLine, "LPIPS", second);
    addMetric(test, testPSNR.c_str(), QUALITY, 0, Palette[0], testLine, "PSNR test", second);
    addMetric(test, testSSIM.c_str(), QUALITY, 1, Palette[1], testLine, "SSIM test", second);
    addMetric(test, testLPIPS.c_str(), QUALITY, 1, Palette[2], testLine, "LPIPS test", second);
  }
  addMetric(in.Metrics, this->CountColumn, COUNT, 0, Palette[4], solid, "Gaussians", false);
  addMetric(in.ComparisonMetrics,
    this->CountColumn,
    COUNT,
    0,
    Palette[4],
    vtkPen::DOT_LINE,
    "Gaussians",
    true);
  in.Charts[QUALITY]->GetAxis(vtkAxis::LEFT)->SetTitle("PSNR (dB)");
  in.Charts[QUALITY]->GetAxis(vtkAxis::RIGHT)->SetTitle("SSIM, LPIPS");
  in.Charts[COUNT]->GetAxis(vtkAxis::LEFT)->SetTitle("count");

  // History of the selected Gaussians: long table -> one column per Gaussian.
  in.Wide->Initialize();
  vtkTable* h = in.History;
  auto* hit =
    h ? vtkDataArray::SafeDownCast(h->GetColumnByName(this->HistoryIterationColumn)) : nullptr;
  auto* hid = h ? vtkDataArray::SafeDownCast(h->GetColumnByName(this->HistoryIdColumn)) : nullptr;
  auto* hval = (h && this->HistoryProperty)
    ? vtkDataArray::SafeDownCast(h->GetColumnByName(this->HistoryProperty))
    : nullptr;
  in.Charts[HISTORY]->SetTitle(
    std::string("Selected Gaussians: ") + (this->HistoryProperty ? this->HistoryProperty : ""));
  if (hit && hid && hval)
  {
    std::vector<double> iterations;
    std::map<vtkIdType, std::map<double, double>> series;
    for (vtkIdType r = 0; r < h->GetNumberOfRows(); ++r)
    {
      const vtkIdType id = static_cast<vtkIdType>(hid->GetComponent(r, 0));
      if (in.Hub && !in.Hub->IsSelected(id))
      {
        continue;
      }
      if (series.count(id) == 0 && static_cast<int>(series.size()) >= this->MaximumHistoryLines)
      {
        continue;
      }
      const double t = hit->GetComponent(r, 0);
      // A vector property is drawn by the chosen component, else by its largest (Scale).
      const int components = hval->GetNumberOfComponents();
      double value = hval->GetComponent(r, 0);
      if (this->HistoryComponent >= 0 && this->HistoryComponent < components)
      {
        value = hval->GetComponent(r, this->HistoryComponent);
      }
      else
      {
        for (int c = 1; c < components; ++c)
        {
          value = std::max(value, hval->GetComponent(r, c));
        }
      }
      series[id][t] = value;
      iterations.push_back(t);
    }
    std::sort(iterations.begin(), iterations.end());
    iterations.erase(std::unique(iterations.begin(), iterations.end()), iterations.end());
    if (!iterations.empty() && !series.empty())
    {
      vtkNew<vtkDoubleArray> x;
      x->SetName("Iteration");
      for (double t : iterations)
      {
        x->InsertNextValue(t);
      }
      in.Wide->AddColumn(x);
      xmin = std::min(xmin, iterations.front());
      xmax = std::max(xmax, iterations.back());
      int k = 0;
      for (auto& s : series)
      {
        vtkNew<vtkDoubleArray> y;
        const std::string name = "Gaussian " + std::to_string(static_cast<long long>(s.first));
        y->SetName(name.c_str());
        for (double t : iterations)
        {
          auto f = s.second.find(t);
          y->InsertNextValue(
            f == s.second.end() ? std::numeric_limits<double>::quiet_NaN() : f->second);
        }
        in.Wide->AddColumn(y);
        vtkPlot* plot = in.Charts[HISTORY]->AddPlot(vtkChart::LINE);
        plot->SetInputData(in.Wide, "Iteration", name);
        const unsigned char* c = Palette[k % 8];
        plot->SetColor(c[0], c[1], c[2], 255);
        plot->SetWidth(2.f);
        if (auto* points = vtkPlotPoints::SafeDownCast(plot))
        {
          points->SetMarkerStyle(vtkPlotPoints::CIRCLE);
          points->SetMarkerSize(5.f);
        }
        ++k;
      }
      in.HistoryLines = k;
    }
  }
  in.Charts[HISTORY]
    ->GetAxis(vtkAxis::LEFT)
    ->SetTitle(this->HistoryProperty ? this->HistoryProperty : "");
  // One iteration range for the three charts, so the cursor lines up.
  if (xmax >= xmin)
  {
    const double pad = std::max(1.0, 0.02 * (xmax - xmin));
    for (auto& chart : in.Charts)
    {
      vtkAxis* axis = chart->GetAxis(vtkAxis::BOTTOM);
      axis->SetBehavior(vtkAxis::FIXED);
      axis->SetRange(xmin - pad, xmax + pad);
    }
  }
  for (auto& chart : in.Charts)
  {
    chart->RecalculateBounds();
    chart->SetCursorIteration(in.Iteration);
  }
  this->GetScene()->SetDirty(true);
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineView::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  auto& in = *this->Internals;
  auto str = [](const char* s) { return s ? s : "(none)"; };
  os << indent << "Metrics: " << in.Metrics.GetPointer() << "\n";
  os << indent << "TestMetrics: " << in.TestMetrics.GetPointer() << "\n";
  os << indent << "ComparisonMetrics: " << in.ComparisonMetrics.GetPointer() << "\n";
  os << indent << "ComparisonTestMetrics: " << in.ComparisonTestMetrics.GetPointer() << "\n";
  os << indent << "RunName: " << str(this->RunName) << "\n";
  os << indent << "ComparisonRunName: " << str(this->ComparisonRunName) << "\n";
  os << indent << "History: " << in.History.GetPointer() << "\n";
  os << indent << "MetricsConnection: " << in.MetricsInput.GetConnection() << "\n";
  os << indent << "HistoryConnection: " << in.HistoryInput.GetConnection() << "\n";
  os << indent << "HistoryProperty: " << str(this->HistoryProperty) << "\n";
  os << indent << "MaximumHistoryLines: " << this->MaximumHistoryLines << "\n";
  os << indent << "HistoryComponent: " << this->HistoryComponent << "\n";
  os << indent << "IterationColumn: " << str(this->IterationColumn) << "\n";
  os << indent << "CountColumn: " << str(this->CountColumn) << "\n";
  os << indent << "PSNRColumn: " << str(this->PSNRColumn) << "\n";
  os << indent << "SSIMColumn: " << str(this->SSIMColumn) << "\n";
  os << indent << "LPIPSColumn: " << str(this->LPIPSColumn) << "\n";
  os << indent << "HistoryIterationColumn: " << str(this->HistoryIterationColumn) << "\n";
  os << indent << "HistoryIdColumn: " << str(this->HistoryIdColumn) << "\n";
  os << indent << "SelectionHub: " << in.Hub.GetPointer() << "\n";
  os << indent << "Iteration: " << in.Iteration << "\n";
  os << indent << "ComparisonIteration: " << in.ComparisonIteration << "\n";
}
