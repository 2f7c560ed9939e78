// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSSelectionTable.h
 * @brief Panel C's table of the selected Gaussians: id, centre, opacity, largest scale and
 * the scores, one sortable row per selected Gaussian of the scene (the first 1000).
 */
#ifndef Vis4GSSelectionTable_h
#define Vis4GSSelectionTable_h

#include "vtkType.h" // For vtkIdType

#include <QTableWidget>

#include <vector>

class vtkPolyData;

class Vis4GSSelectionTable : public QTableWidget
{
public:
  explicit Vis4GSSelectionTable(QWidget* parent = nullptr);

  /// Shows the Gaussians of @p scene whose GaussianId is in the sorted @p selected.
  void Show(vtkPolyData* scene, const std::vector<vtkIdType>& selected);
};

#endif
