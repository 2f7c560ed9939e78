// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSSelectionExport.h
 * @brief What the application's File and Selection menus write: the selected GaussianIds as
 * CSV, and the selected Gaussians (or the scene without them) as PLY, SPZ v4 or PlayCanvas
 * compressed PLY (by the name's ending), through Core's writers.
 */
#ifndef Vis4GSSelectionExport_h
#define Vis4GSSelectionExport_h

#include <QString>

class vtkGaussianSelectionHub;
class vtkPolyData;

/// A message for the status bar and how long to show it.
struct Vis4GSExportReport
{
  QString Message;
  int Milliseconds = 5000;
};

/// Writes the hub's selected GaussianIds, one per line under a "GaussianId" header.
Vis4GSExportReport Vis4GSWriteSelectedIds(const QString& path, vtkGaussianSelectionHub* hub);

/**
 * Writes the Gaussians of @p scene that are selected in @p hub, or with @p deleteSelection
 * those that are not: SPZ v4 for a name ending in .spz (the message gives the quantisation
 * error and what was left out), the compressed PLY for .compressed.ply, else PLY.
 */
Vis4GSExportReport Vis4GSWriteSelectedScene(const QString& path,
  vtkPolyData* scene,
  vtkGaussianSelectionHub* hub,
  bool deleteSelection);

#endif
