/*=========================================================================

  Program:   Vis4GS
  Module:    Vis4GSViewInput.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class Vis4GSViewInput
 * @brief A view's input connection: an algorithm's output port that the view updates when it
 * updates or renders, as a representation would, instead of data handed to it (issue 33).
 *
 * Pull() updates the producer's port and says whether what it holds differs from what the
 * last Pull() saw. "Differs" compares the data's content, not the data object: the arrays of
 * every attribute (and the points) by identity and MTime and the element counts. A producer
 * that re-executes a port only to pass its cached data on (vtkGaussianSession after a new
 * selection: the Gaussians, tree and metrics ports) hands over the same arrays, and a view
 * that rebuilt its splats or its tree layout then would redo seconds of work at millions of
 * Gaussians for nothing.
 *
 * The producer is held by a reference (vtkAlgorithmOutput does not hold one), so a view keeps
 * its pipeline alive as a mapper does.
 */
#ifndef Vis4GSViewInput_h
#define Vis4GSViewInput_h

#include "vis4gsViewsLinkedModule.h" // For export macro

#include "vtkDataObject.h"   // For vtkSmartPointer<vtkDataObject>
#include "vtkSmartPointer.h" // For the producer held
#include "vtkType.h"         // For vtkMTimeType

#include <vector> // For the content stamp

class vtkAlgorithm;
class vtkAlgorithmOutput;

class VIS4GSVIEWSLINKED_EXPORT Vis4GSViewInput
{
public:
  /// Connects @p output (null: disconnects). The next Pull() reports a change, unless
  /// @p output is the port connected already.
  void SetConnection(vtkAlgorithmOutput* output);
  /// The connected port (null when none).
  vtkAlgorithmOutput* GetConnection() const;
  bool IsConnected() const { return this->Producer != nullptr; }

  /**
   * Updates the connected port. Returns true when its data differs from the last Pull()'s
   * (the first Pull() after SetConnection() always does), with @p copy a new data object of
   * the port's type sharing its arrays (a shallow copy: the producer re-executes into its own
   * output object later, which must not touch what the view draws, nor its MTime, which the
   * views' caches are keyed by); false when it is the same, when nothing is connected or when
   * the update failed (the producer reported why), leaving @p copy unchanged.
   */
  bool Pull(vtkSmartPointer<vtkDataObject>& copy);

private:
  vtkSmartPointer<vtkAlgorithm> Producer;
  int Port = 0;
  bool Pulled = false;
  std::vector<vtkMTimeType> Stamp;
};

#endif
