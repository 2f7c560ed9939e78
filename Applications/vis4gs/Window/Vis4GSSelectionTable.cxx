// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSSelectionTable.h"

#include "ScoreRegistry.h"
#include "Vis4GSDataModel.h"
#include "vtkGaussianSelectionHub.h"

#include "vtkDataArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <QHeaderView>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

//------------------------------------------------------------------------------
namespace
{
constexpr vtkIdType MaximumRows = 1000; // rows the table shows of a selection

// The columns after id and centre: opacity, largest scale, then every registered score.
std::vector<std::string> AttributeColumns()
{
  std::vector<std::string> names{ "Opacity", "Scale" };
  for (const vis4gs::ScoreDefinition& d : vis4gs::ScoreDefinitions())
  {
    names.emplace_back(d.ArrayName);
  }
  return names;
}
}

//------------------------------------------------------------------------------
Vis4GSSelectionTable::Vis4GSSelectionTable(QWidget* parent)
  : QTableWidget(parent)
{
  QStringList headers{ "GaussianId", "x", "y", "z" };
  for (const std::string& name : AttributeColumns())
  {
    headers << QString::fromStdString(name);
  }
  this->setColumnCount(headers.size());
  this->setHorizontalHeaderLabels(headers);
  this->setSortingEnabled(true);
  this->horizontalHeader()->setStretchLastSection(true);
}

//------------------------------------------------------------------------------
void Vis4GSSelectionTable::Show(vtkPolyData* scene, const std::vector<vtkIdType>& selected)
{
  this->setSortingEnabled(false);
  this->setRowCount(0);
  if (scene)
  {
    // Only the first MaximumRows rows are shown: their rows are looked up for a prefix of the
    // (sorted) ids, grown until it yields them, not for a selection of millions.
    vtkNew<vtkIdTypeArray> rows;
    vtkDataArray* idColumn = scene->GetPointData()->GetArray(vis4gs::arrays::GaussianId);
    std::size_t prefix = std::min<std::size_t>(selected.size(), MaximumRows);
    for (;;)
    {
      vtkGaussianSelectionHub::IdsToIndices(
        selected.data(), static_cast<vtkIdType>(prefix), idColumn, rows);
      if (rows->GetNumberOfTuples() >= MaximumRows || prefix == selected.size())
      {
        break;
      }
      prefix = std::min(selected.size(), 4 * prefix);
    }
    vtkPointData* pd = scene->GetPointData();
    std::vector<vtkDataArray*> columns{
      pd->GetArray(vis4gs::arrays::GaussianId), nullptr, nullptr, nullptr
    };
    for (const std::string& name : AttributeColumns())
    {
      columns.push_back(pd->GetArray(name.c_str()));
    }
    const int scaleColumn = 5;
    const int shown = static_cast<int>(std::min<vtkIdType>(rows->GetNumberOfTuples(), MaximumRows));
    this->setRowCount(shown);
    for (int k = 0; k < shown; ++k)
    {
      const vtkIdType r = rows->GetValue(k);
      double p[3];
      scene->GetPoint(r, p);
      for (int c = 0; c < static_cast<int>(columns.size()); ++c)
      {
        double value = NAN;
        if (c >= 1 && c <= 3)
        {
          value = p[c - 1];
        }
        else if (c == scaleColumn && columns[c])
        {
          value = std::max({ columns[c]->GetComponent(r, 0),
            columns[c]->GetComponent(r, 1),
            columns[c]->GetComponent(r, 2) });
        }
        else if (columns[c])
        {
          value = columns[c]->GetComponent(r, 0);
        }
        auto* item = new QTableWidgetItem;
        item->setData(Qt::DisplayRole, value);
        this->setItem(k, c, item);
      }
    }
  }
  this->setSortingEnabled(true);
}
