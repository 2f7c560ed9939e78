/*=========================================================================

  Program:   Vis4GS
  Module:    Vis4GSRequestedPort.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @file Vis4GSRequestedPort.h
 * @brief "Produce only the requested output port", shared by the algorithms with several
 * independent outputs (vtkGaussianTrainingLogReader, vtkGaussianSession).
 *
 * vtkDemandDrivenPipeline re-executes an algorithm for every output port that is out of date;
 * a reader whose ports are independent (a snapshot, the metrics, the events) would then read
 * all of them to show one. An algorithm answers REQUEST_DATA_NOT_GENERATED with
 * MarkOtherPortsNotGenerated() and produces RequestedOutputPort() only: the other ports keep
 * their data and stay out of date, so that they execute when they are asked for.
 */
#ifndef Vis4GSRequestedPort_h
#define Vis4GSRequestedPort_h

#include "vis4gsIOSceneModule.h" // For export macro

class vtkInformation;
class vtkInformationVector;

namespace vis4gs
{
/// The output port @p request is for (FROM_OUTPUT_PORT); -1 when it names none: every port.
VIS4GSIOSCENE_EXPORT int RequestedOutputPort(vtkInformation* request);

/// Sets DATA_NOT_GENERATED on every output of @p outInfo but the requested one (and removes it
/// there); with no requested port every output is generated.
VIS4GSIOSCENE_EXPORT void MarkOtherPortsNotGenerated(vtkInformation* request,
  vtkInformationVector* outInfo);
} // namespace vis4gs

#endif
