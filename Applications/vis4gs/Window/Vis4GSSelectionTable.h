// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSSelectionTable.h
 * @brief Panel C's table of the selected Gaussians: id, centre, opacity, largest scale and
 * the scores, one sortable row per selected Gaussian of the scene (the first 1000).
 *
 * The values of the shown rows are read once per selection into a table of numbers that a model
 * hands to the view as it paints: Qt asks only for the cells on screen, where a QTableWidget made
 * an item per cell (9,000 items, about 5 ms of each pick of a large selection).
 */
#ifndef Vis4GSSelectionTable_h
#define Vis4GSSelectionTable_h

#include "vtkType.h" // For vtkIdType

#include <QTableView>

#include <memory>
#include <vector>

class vtkPolyData;
class Vis4GSSelectionTableModel;

class Vis4GSSelectionTable : public QTableView
{
public:
  explicit Vis4GSSelectionTable(QWidget* parent = nullptr);
  ~Vis4GSSelectionTable() override;

  /// Shows the Gaussians of @p scene whose GaussianId is in the sorted @p selected.
  void Show(vtkPolyData* scene, const std::vector<vtkIdType>& selected);

  /// Rows shown (at most 1000) and the value shown in a cell (NaN: none), in display order.
  int GetNumberOfRows() const;
  double GetValue(int row, int column) const;

private:
  std::unique_ptr<Vis4GSSelectionTableModel> Model;
};

#endif
