/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianTimelineChart.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class   vtkGaussianTimelineChart
 * @brief   vtkChartXY over iterations with an iteration cursor and click-to-pick
 *
 * Draws a vertical cursor at CursorIteration (when >= 0) over the plot area. A left click
 * (press and release without dragging) inside the plot area invokes IterationClickedEvent
 * with a pointer to the clicked iteration (int, rounded) as call data; dragging still pans
 * as in vtkChartXY.
 */
#ifndef vtkGaussianTimelineChart_h
#define vtkGaussianTimelineChart_h

#include "vis4gsViewsLinkedModule.h" // For export macro
#include "vtkChartXY.h"
#include "vtkCommand.h" // For vtkCommand::UserEvent

class VIS4GSVIEWSLINKED_EXPORT vtkGaussianTimelineChart : public vtkChartXY
{
public:
  static vtkGaussianTimelineChart* New();
  vtkTypeMacro(vtkGaussianTimelineChart, vtkChartXY);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Events
  {
    /// Call data: int* iteration.
    IterationClickedEvent = vtkCommand::UserEvent + 4102
  };

  ///@{
  /**
   * Iteration of the cursor; negative hides it. Default -1.
   */
  vtkSetMacro(CursorIteration, double);
  vtkGetMacro(CursorIteration, double);
  ///@}

  ///@{
  /**
   * Iteration of a second cursor, dashed magenta: the other state of a comparison (issue 20);
   * negative hides it. Default -1.
   */
  vtkSetMacro(ComparisonCursorIteration, double);
  vtkGetMacro(ComparisonCursorIteration, double);
  ///@}

  /// The iteration (data x) under a scene position, from the bottom axis.
  double SceneToIteration(float sceneX);
  /// The scene x of an iteration.
  float IterationToScene(double iteration);

  bool Paint(vtkContext2D* painter) override;
  bool MouseButtonPressEvent(const vtkContextMouseEvent& mouse) override;
  bool MouseButtonReleaseEvent(const vtkContextMouseEvent& mouse) override;

protected:
  vtkGaussianTimelineChart() = default;
  ~vtkGaussianTimelineChart() override = default;

  double CursorIteration = -1;
  double ComparisonCursorIteration = -1;
  float PressX = 0.f;
  float PressY = 0.f;
  bool LeftPressed = false;

private:
  vtkGaussianTimelineChart(const vtkGaussianTimelineChart&) = delete;
  void operator=(const vtkGaussianTimelineChart&) = delete;
};

#endif
