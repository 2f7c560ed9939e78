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

#include <QAbstractTableModel>
#include <QHeaderView>

#include <algorithm>
#include <cmath>
#include <numeric>
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
// The shown rows' values (row-major, NaN where the scene lacks the column), in display order.
class Vis4GSSelectionTableModel : public QAbstractTableModel
{
public:
  QStringList Headers;
  std::vector<double> Values;
  int Rows = 0;

  int rowCount(const QModelIndex& parent) const override { return parent.isValid() ? 0 : Rows; }
  int columnCount(const QModelIndex& parent) const override
  {
    return parent.isValid() ? 0 : static_cast<int>(this->Headers.size());
  }
  double Value(int row, int column) const
  {
    return this->Values[static_cast<std::size_t>(row) * this->Headers.size() +
      static_cast<std::size_t>(column)];
  }
  QVariant data(const QModelIndex& index, int role) const override
  {
    if (role != Qt::DisplayRole || !index.isValid() || index.row() >= this->Rows)
    {
      return QVariant();
    }
    return this->Value(index.row(), index.column());
  }
  QVariant headerData(int section, Qt::Orientation orientation, int role) const override
  {
    if (role == Qt::DisplayRole && orientation == Qt::Horizontal && section >= 0 &&
      section < this->Headers.size())
    {
      return this->Headers[section];
    }
    return QAbstractTableModel::headerData(section, orientation, role);
  }
  void sort(int column, Qt::SortOrder order) override
  {
    if (column < 0 || column >= this->Headers.size() || this->Rows == 0)
    {
      return;
    }
    // Rows by the column's value; NaN (no value) last either way, ties in the earlier order.
    std::vector<int> perm(static_cast<std::size_t>(this->Rows));
    std::iota(perm.begin(), perm.end(), 0);
    std::stable_sort(perm.begin(),
      perm.end(),
      [&](int a, int b)
      {
        const double va = this->Value(a, column), vb = this->Value(b, column);
        if (std::isnan(va) || std::isnan(vb))
        {
          return !std::isnan(va) && std::isnan(vb);
        }
        return order == Qt::AscendingOrder ? va < vb : va > vb;
      });
    emit this->layoutAboutToBeChanged();
    const std::size_t nc = static_cast<std::size_t>(this->Headers.size());
    std::vector<double> sorted(this->Values.size());
    for (std::size_t k = 0; k < perm.size(); ++k)
    {
      std::copy_n(this->Values.begin() + static_cast<std::ptrdiff_t>(perm[k] * nc),
        nc,
        sorted.begin() + static_cast<std::ptrdiff_t>(k * nc));
    }
    this->Values.swap(sorted);
    emit this->layoutChanged();
  }
  void Reset(std::vector<double>&& values, int rows)
  {
    this->beginResetModel();
    this->Values = std::move(values);
    this->Rows = rows;
    this->endResetModel();
  }
};

//------------------------------------------------------------------------------
Vis4GSSelectionTable::Vis4GSSelectionTable(QWidget* parent)
  : QTableView(parent)
  , Model(new Vis4GSSelectionTableModel)
{
  this->Model->Headers = QStringList{ "GaussianId", "x", "y", "z" };
  for (const std::string& name : AttributeColumns())
  {
    this->Model->Headers << QString::fromStdString(name);
  }
  this->setModel(this->Model.get());
  this->setSortingEnabled(true);
  this->horizontalHeader()->setStretchLastSection(true);
}

//------------------------------------------------------------------------------
Vis4GSSelectionTable::~Vis4GSSelectionTable()
{
  this->setModel(nullptr);
}

//------------------------------------------------------------------------------
int Vis4GSSelectionTable::GetNumberOfRows() const
{
  return this->Model->Rows;
}

//------------------------------------------------------------------------------
double Vis4GSSelectionTable::GetValue(int row, int column) const
{
  return row >= 0 && row < this->Model->Rows && column >= 0 && column < this->Model->Headers.size()
    ? this->Model->Value(row, column)
    : NAN;
}

//------------------------------------------------------------------------------
void Vis4GSSelectionTable::Show(vtkPolyData* scene, const std::vector<vtkIdType>& selected)
{
  std::vector<double> values;
  int shown = 0;
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
    shown = static_cast<int>(std::min<vtkIdType>(rows->GetNumberOfTuples(), MaximumRows));
    values.assign(static_cast<std::size_t>(shown) * columns.size(), NAN);
    auto* out = values.data();
    for (int k = 0; k < shown; ++k)
    {
      const vtkIdType r = rows->GetValue(k);
      double p[3];
      scene->GetPoint(r, p);
      for (int c = 0; c < static_cast<int>(columns.size()); ++c, ++out)
      {
        if (c >= 1 && c <= 3)
        {
          *out = p[c - 1];
        }
        else if (c == scaleColumn && columns[c])
        {
          *out = std::max({ columns[c]->GetComponent(r, 0),
            columns[c]->GetComponent(r, 1),
            columns[c]->GetComponent(r, 2) });
        }
        else if (columns[c])
        {
          *out = columns[c]->GetComponent(r, 0);
        }
      }
    }
  }
  this->Model->Reset(std::move(values), shown);
  // In the order the user chose (the header's indicator), as the table always is.
  if (this->isSortingEnabled())
  {
    this->Model->sort(this->horizontalHeader()->sortIndicatorSection(),
      this->horizontalHeader()->sortIndicatorOrder());
  }
}
