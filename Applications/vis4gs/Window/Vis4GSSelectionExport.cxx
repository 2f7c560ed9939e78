// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSSelectionExport.h"

#include "GaussianIO.h"
#include "Vis4GSDataModel.h"
#include "vtkGaussianSelectionHub.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <QFile>
#include <QTextStream>

#include <exception>
#include <string>

//------------------------------------------------------------------------------
Vis4GSExportReport Vis4GSWriteSelectedIds(const QString& path, vtkGaussianSelectionHub* hub)
{
  QFile file(path);
  if (!file.open(QIODevice::WriteOnly | QIODevice::Text))
  {
    return { path + ": could not be written", 5000 };
  }
  QTextStream out(&file);
  out << "GaussianId\n";
  for (vtkIdType id : hub->GetSelectedIdVector())
  {
    out << static_cast<long long>(id) << "\n";
  }
  return { path + " written", 3000 };
}

//------------------------------------------------------------------------------
Vis4GSExportReport Vis4GSWriteSelectedScene(const QString& path,
  vtkPolyData* scene,
  vtkGaussianSelectionHub* hub,
  bool deleteSelection)
{
  // Keep (or drop) the selected Gaussians, then write through Core's writers.
  vtkDataArray* ids = scene->GetPointData()->GetArray(vis4gs::arrays::GaussianId);
  vtkNew<vtkPolyData> subset;
  vtkNew<vtkPoints> points;
  subset->GetPointData()->CopyAllocate(scene->GetPointData());
  for (vtkIdType i = 0; ids && i < scene->GetNumberOfPoints(); ++i)
  {
    if (hub->IsSelected(static_cast<vtkIdType>(ids->GetComponent(i, 0))) != deleteSelection)
    {
      const vtkIdType j = points->InsertNextPoint(scene->GetPoint(i));
      subset->GetPointData()->CopyData(scene->GetPointData(), i, j);
    }
  }
  subset->SetPoints(points);
  subset->GetFieldData()->ShallowCopy(scene->GetFieldData());
  vis4gs::GaussianCloud cloud;
  std::string error;
  if (!vis4gs::PolyDataToGaussianCloud(subset, cloud, &error))
  {
    return { QString::fromStdString(error), 5000 };
  }
  try
  {
    // Written by the name's format, with what a lossy one lost (as vis4gs convert says it).
    const std::string line = vis4gs::WriteGaussianScene(path.toStdString(), cloud);
    return { path + ": " + QString::fromStdString(line), 15000 };
  }
  catch (const std::exception& e)
  {
    return { e.what(), 5000 };
  }
}
