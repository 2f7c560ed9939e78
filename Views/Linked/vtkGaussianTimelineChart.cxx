/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianTimelineChart.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianTimelineChart.h"

#include "vtkAxis.h"
#include "vtkContext2D.h"
#include "vtkContextMouseEvent.h"
#include "vtkObjectFactory.h"
#include "vtkPen.h"

#include <cmath>

vtkStandardNewMacro(vtkGaussianTimelineChart);

//------------------------------------------------------------------------------
double vtkGaussianTimelineChart::SceneToIteration(float sceneX)
{
  vtkAxis* axis = this->GetAxis(vtkAxis::BOTTOM);
  const float x1 = axis->GetPoint1()[0], x2 = axis->GetPoint2()[0];
  if (x2 == x1)
  {
    return axis->GetMinimum();
  }
  return axis->GetMinimum() + (sceneX - x1) / (x2 - x1) * (axis->GetMaximum() - axis->GetMinimum());
}

//------------------------------------------------------------------------------
float vtkGaussianTimelineChart::IterationToScene(double iteration)
{
  vtkAxis* axis = this->GetAxis(vtkAxis::BOTTOM);
  const float x1 = axis->GetPoint1()[0], x2 = axis->GetPoint2()[0];
  const double span = axis->GetMaximum() - axis->GetMinimum();
  if (span == 0)
  {
    return x1;
  }
  return static_cast<float>(x1 + (iteration - axis->GetMinimum()) / span * (x2 - x1));
}

//------------------------------------------------------------------------------
bool vtkGaussianTimelineChart::Paint(vtkContext2D* painter)
{
  const bool result = this->Superclass::Paint(painter);
  vtkAxis* bottom = this->GetAxis(vtkAxis::BOTTOM);
  vtkAxis* left = this->GetAxis(vtkAxis::LEFT);
  for (const bool second : { false, true })
  {
    const double iteration = second ? this->ComparisonCursorIteration : this->CursorIteration;
    if (iteration >= 0 && iteration >= bottom->GetMinimum() && iteration <= bottom->GetMaximum())
    {
      const float x = this->IterationToScene(iteration);
      vtkNew<vtkPen> pen;
      pen->SetColor(second ? 200 : 220, 40 * !second, second ? 200 : 40, 255);
      pen->SetWidth(2.f);
      pen->SetLineType(second ? vtkPen::DASH_LINE : vtkPen::SOLID_LINE);
      painter->ApplyPen(pen);
      painter->DrawLine(x, left->GetPoint1()[1], x, left->GetPoint2()[1]);
    }
  }
  return result;
}

//------------------------------------------------------------------------------
bool vtkGaussianTimelineChart::MouseButtonPressEvent(const vtkContextMouseEvent& mouse)
{
  if (mouse.GetButton() == vtkContextMouseEvent::LEFT_BUTTON)
  {
    this->LeftPressed = true;
    this->PressX = mouse.GetScenePos().GetX();
    this->PressY = mouse.GetScenePos().GetY();
  }
  return this->Superclass::MouseButtonPressEvent(mouse);
}

//------------------------------------------------------------------------------
bool vtkGaussianTimelineChart::MouseButtonReleaseEvent(const vtkContextMouseEvent& mouse)
{
  const bool result = this->Superclass::MouseButtonReleaseEvent(mouse);
  if (mouse.GetButton() == vtkContextMouseEvent::LEFT_BUTTON && this->LeftPressed)
  {
    this->LeftPressed = false;
    const float x = mouse.GetScenePos().GetX(), y = mouse.GetScenePos().GetY();
    vtkAxis* bottom = this->GetAxis(vtkAxis::BOTTOM);
    vtkAxis* left = this->GetAxis(vtkAxis::LEFT);
    const bool still = std::abs(x - this->PressX) + std::abs(y - this->PressY) < 3.f;
    const bool inside = x >= bottom->GetPoint1()[0] && x <= bottom->GetPoint2()[0] &&
      y >= left->GetPoint1()[1] && y <= left->GetPoint2()[1];
    if (still && inside)
    {
      int iteration = static_cast<int>(std::lround(this->SceneToIteration(x)));
      this->InvokeEvent(IterationClickedEvent, &iteration);
    }
  }
  return result;
}

//------------------------------------------------------------------------------
void vtkGaussianTimelineChart::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CursorIteration: " << this->CursorIteration << "\n";
  os << indent << "ComparisonCursorIteration: " << this->ComparisonCursorIteration << "\n";
}
