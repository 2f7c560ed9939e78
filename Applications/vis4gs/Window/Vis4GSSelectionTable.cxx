// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSSelectionTable.h"

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

//------------------------------------------------------------------------------
Vis4GSSelectionTable::Vis4GSSelectionTable(QWidget* parent)
  : QTableWidget(parent)
{
  this->setColumnCount(10);
  this->setHorizontalHeaderLabels({ "GaussianId",
    "x",
    "y",
    "z",
    "Opacity",
    "Scale",
    "ViewCoverage",
    "BlurScore",
    "NeedleScore",
    "NeedleShape" });
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
    vtkNew<vtkIdTypeArray> rows;
    vtkGaussianSelectionHub::IdsToIndices(selected.data(),
      static_cast<vtkIdType>(selected.size()),
      scene->GetPointData()->GetArray(vis4gs::arrays::GaussianId),
      rows);
    vtkPointData* pd = scene->GetPointData();
    vtkDataArray* columns[] = { pd->GetArray(vis4gs::arrays::GaussianId),
      nullptr,
      nullptr,
      nullptr,
      pd->GetArray("Opacity"),
      pd->GetArray("Scale"),
      pd->GetArray(vis4gs::arrays::ViewCoverage),
      pd->GetArray(vis4gs::arrays::BlurScore),
      pd->GetArray(vis4gs::arrays::NeedleScore),
      pd->GetArray(vis4gs::arrays::NeedleShape) };
    const int shown = static_cast<int>(std::min<vtkIdType>(rows->GetNumberOfTuples(), 1000));
    this->setRowCount(shown);
    for (int k = 0; k < shown; ++k)
    {
      const vtkIdType r = rows->GetValue(k);
      double p[3];
      scene->GetPoint(r, p);
      for (int c = 0; c < 10; ++c)
      {
        double value = NAN;
        if (c >= 1 && c <= 3)
        {
          value = p[c - 1];
        }
        else if (c == 5 && columns[5])
        {
          value = std::max({ columns[5]->GetComponent(r, 0),
            columns[5]->GetComponent(r, 1),
            columns[5]->GetComponent(r, 2) });
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
